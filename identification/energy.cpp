// Energy-based damping measures (paper 003 W/T; research note §3.5).
#include "identification/energy.hpp"

#include <stdexcept>

#include "core/units.hpp"

namespace sb::identification {

double dissipated_energy_per_cycle(std::complex<double> force_n,
                                   std::complex<double> displacement_m) {
    // ∫ f ẋ dt over one period = (2π/ω) · ½ Re{F conj(iωX)} = π Im{F conj(X)}.
    return kPi * (force_n * std::conj(displacement_m)).imag();
}

double dissipated_energy_per_cycle_from_acceleration(std::complex<double> force_n,
                                                     std::complex<double> acceleration_m_s2,
                                                     double omega_rad_s) {
    return dissipated_energy_per_cycle(force_n, -acceleration_m_s2 / (omega_rad_s * omega_rad_s));
}

double kinetic_energy_amplitude(double mass_kg, double omega_rad_s,
                                std::complex<double> displacement_m) {
    return 0.5 * mass_kg * omega_rad_s * omega_rad_s * std::norm(displacement_m);
}

double specific_damping_capacity(double dissipated_j, double kinetic_j) {
    if (!(kinetic_j > 0.0)) throw std::invalid_argument("specific_damping_capacity: T must be > 0");
    return dissipated_j / kinetic_j;
}

double damping_ratio_from_capacity(double capacity) { return capacity / (4.0 * kPi); }

double loss_factor_from_capacity(double capacity) { return capacity / (2.0 * kPi); }

double subtract_background(double damping_ratio, double background_damping_ratio) {
    return damping_ratio - background_damping_ratio;
}

}  // namespace sb::identification

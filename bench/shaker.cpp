// The electrodynamic shaker's coil, suspension and back-EMF at the drive point.
#include "bench/shaker.hpp"

#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace sb::bench {

std::complex<double> blocked_force_per_volt(const ShakerSpec& shaker, double frequency_hz) {
    const double w = hz_to_rad_s(frequency_hz);
    const std::complex<double> impedance(shaker.coil_resistance_ohm, w * shaker.coil_inductance_h);
    return shaker.force_factor_n_per_a / impedance;
}

ShakerCoil::ShakerCoil(const Eigen::Vector3d& direction, const ShakerSpec& shaker,
                       const Eigen::Vector3d& rest_position_m)
    : direction_(direction.normalized()), shaker_(shaker), rest_position_m_(rest_position_m) {
    if (!(shaker.coil_resistance_ohm > 0.0)) {
        throw std::invalid_argument("shaker: the coil resistance must be > 0");
    }
}

PointLoad ShakerCoil::step(const PointMotion& motion, double dt_s) {
    // The motion over the step, extrapolated from its start with its acceleration: the load
    // applies at the step's end, and a dashpot's force lagging a step would act as a negative
    // mass c dt (the frequency of a voltage-referenced FRF up by 2e-4 on the paper-000 bench).
    const double v0 = direction_.dot(motion.velocity_m_s);
    const double a = direction_.dot(motion.acceleration_m_s2);
    const double v = v0 + a * dt_s;
    const double u =
        direction_.dot(motion.position_m - rest_position_m_) + (v0 + 0.5 * a * dt_s) * dt_s;
    const double bl = shaker_.force_factor_n_per_a;
    const double r = shaker_.coil_resistance_ohm;
    const double tau = shaker_.coil_inductance_h / r;
    // L di/dt + R i = -Bl v(t) with v(t) = v0 + a t, exactly: the particular solution
    // -Bl (v(t) - tau a) / R, and the rest decaying with the coil's time constant tau = L / R.
    const double particular_start = -bl * (v0 - tau * a) / r;
    const double particular_end = -bl * (v - tau * a) / r;
    const double decay = tau > 0.0 ? std::exp(-dt_s / tau) : 0.0;
    current_a_ = particular_end + (current_a_ - particular_start) * decay;
    const double force = bl * current_a_ - shaker_.suspension_stiffness_n_per_m * u -
                         shaker_.suspension_damping_n_s_per_m * v;
    PointLoad load;
    load.force_n = force * direction_;
    return load;
}

AttachmentState ShakerCoil::state() const {
    AttachmentState s;
    s.coil_current_a = current_a_;
    return s;
}

void ShakerCoil::restore(const AttachmentState& state) {
    if (state.dem || state.describing || state.sliders) {
        throw std::invalid_argument("a shaker's coil was given another model's state");
    }
    current_a_ = state.coil_current_a.value_or(0.0);
}

DescribingFunction::Value ShakerCoil::describing(double, double frequency_hz) const {
    const double w = hz_to_rad_s(frequency_hz);
    const std::complex<double> i(0.0, 1.0);
    const std::complex<double> impedance(shaker_.coil_resistance_ohm,
                                         w * shaker_.coil_inductance_h);
    const double bl = shaker_.force_factor_n_per_a;
    DescribingFunction::Value value;
    value.apparent_mass_kg = -shaker_.suspension_stiffness_n_per_m / (w * w) -
                             i * shaker_.suspension_damping_n_s_per_m / w -
                             i * bl * bl / (w * impedance);
    return value;
}

}  // namespace sb::bench

// Energy-based damping measures: dissipated energy per cycle and specific damping capacity.
#pragma once

#include <complex>

namespace sb::identification {

/// Energy dissipated per cycle W = π Im(F conj(X)) [J] from the fundamental complex amplitudes
/// (peak, x(t) = Re{X e^{iωt}}) of the force [N] and of the displacement [m] where it acts
/// (note §3.5: the cycle average of f·ẋ times the period).
double dissipated_energy_per_cycle(std::complex<double> force_n,
                                   std::complex<double> displacement_m);

/// The same from an acceleration amplitude [m/s²] at angular frequency [rad/s]: X = −A/ω².
double dissipated_energy_per_cycle_from_acceleration(std::complex<double> force_n,
                                                     std::complex<double> acceleration_m_s2,
                                                     double omega_rad_s);

/// Peak kinetic energy T = ½ m ω² |X|² [J] of a mass [kg] moving with displacement amplitude
/// X [m] at ω [rad/s] — the "kinetic energy per cycle" of paper 003 (seed 003, Table 2).
double kinetic_energy_amplitude(double mass_kg, double omega_rad_s,
                                std::complex<double> displacement_m);

/// Specific damping capacity ψ = W/T [-] (paper 003, "ratio of dissipated energy per cycle to
/// kinetic energy per cycle"). Throws std::invalid_argument unless T > 0.
double specific_damping_capacity(double dissipated_j, double kinetic_j);

/// Equivalent viscous damping ratio ζ = ψ/(4π) [-] (W = 2πcωX²/2·2, T = ½mω²X² at ω = ωn).
double damping_ratio_from_capacity(double capacity);

/// Loss factor η = ψ/(2π) [-].
double loss_factor_from_capacity(double capacity);

/// Damping of the dampers alone: measured ζ minus the bare rig's background ζ [-] (damping
/// ratios of light, viscous-like mechanisms add).
double subtract_background(double damping_ratio, double background_damping_ratio);

}  // namespace sb::identification

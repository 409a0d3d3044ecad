// Set-up helpers: radii from the size distribution, random filling, settling, save/load,
// automatic stiffness and time step.
#pragma once

#include <cstdint>
#include <string>

#include "dem/solver.hpp"

namespace sb::dem {

/// Radii for options.count particles: monodisperse, or the size classes by number fraction
/// (largest remainder rounding, classes interleaved by a seeded shuffle) [m].
std::vector<double> make_radii(const ParticleOptions& options, std::uint64_t seed = 1);

/// Random non-overlapping insertion in the enclosure frame (fixed seed, rejection sampling,
/// largest spheres first). Throws std::runtime_error if the cavity is too full.
ParticleSet fill_random(const SolverOptions& options, std::uint64_t seed = 1,
                        int max_attempts_per_particle = 20000);

/// Settling options.
struct SettleOptions {
    double dt_s = 1e-5;                 ///< time step [s]
    double kinetic_threshold_j = 1e-9;  ///< at rest below this translational kinetic energy [J]
    double max_time_s = 5.0;            ///< give up after this simulated time [s]
    double min_time_s = 0.05;           ///< settle at least this long [s]
    Violations validate() const;
};

/// Runs the solver with a static enclosure until the translational kinetic energy is below the
/// threshold; returns the settled particles (enclosure frame, velocities and spins zeroed). Throws
/// std::runtime_error on timeout.
ParticleSet settle(const SolverOptions& options, const ParticleSet& initial,
                   const SettleOptions& settle_options = {});

/// CSV: "x_m,y_m,z_m,radius_m,vx_m_s,vy_m_s,vz_m_s,wx,wy,wz" with 17 significant digits.
void save_particles(const std::string& path, const ParticleSet& particles);
ParticleSet load_particles(const std::string& path);

/// Legacy ASCII VTK polydata (points with radius, velocity, angular velocity, id, locked).
void write_vtk(const std::string& path, const ParticleState& state);

/// Inputs of the automatic stiffness choice.
struct AutoStiffnessInput {
    NormalLaw law = NormalLaw::hooke;
    double particle_diameter_m = 3e-3;
    double density_kg_m3 = 7800.0;
    double max_overlap_fraction = 0.01;  ///< allowed largest overlap / diameter [-]
    double impact_speed_m_s = 0.0;       ///< largest expected impact speed; 0 = estimate
    double level_m_s2 = 0.0;             ///< target acceleration amplitude a (for estimate)
    double frequency_hz = 0.0;           ///< excitation frequency f (for estimate)
    double gap_m = 0.0;                  ///< free flight across the cavity (for estimate)
    double gravity_m_s2 = kStandardGravity;
    double restitution = 0.9;                ///< for the damped contact time (Hooke)
    double time_step_fraction = 1.0 / 20.0;  ///< dt = fraction * contact time
    bool wall_contact = true;                ///< size for particle-wall (m_eff = m), else m/2
    Violations validate() const;
};

/// The chosen values, for logging.
struct AutoStiffness {
    double impact_speed_m_s = 0.0;  ///< used speed (given or a/(2 pi f) + sqrt(2 a_max gap))
    double effective_mass_kg = 0.0;
    double max_overlap_m = 0.0;
    double stiffness = 0.0;  ///< Hooke [N/m] or Hertz [N/m^1.5]
    double contact_time_s = 0.0;
    double time_step_s = 0.0;
};

AutoStiffness auto_stiffness(const AutoStiffnessInput& input);

/// Hertz contact duration 2.9432 (5 m*/(4 k))^{2/5} v^{-1/5} (undamped; = 2.87 (m*^2/(R* E*^2
/// v))^{1/5} with k = 4/3 E* sqrt(R*)) [s].
double hertz_contact_time(double m_eff, double k, double v);
/// Linear spring-dashpot contact duration pi / sqrt(k/m* - (c/2m*)^2) [s].
double hooke_contact_time(double m_eff, double k, double restitution);

}  // namespace sb::dem

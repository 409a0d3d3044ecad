// Set-up helpers: radii from the size distribution, random filling, settling, pouring,
// save/load, automatic stiffness and time step.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "dem/solver.hpp"

namespace sb::dem {

/// Radii for options.count particles: monodisperse, or the size classes by number fraction
/// (largest remainder rounding, classes interleaved by a seeded shuffle), each then scattered
/// by options.diameter_scatter (nominal (1 + s u), u uniform in [-sqrt 3, sqrt 3)); the same
/// radii for a seed [m].
std::vector<double> make_radii(const ParticleOptions& options, std::uint64_t seed = 1);

/// Random non-overlapping insertion in the enclosure frame (fixed seed, rejection sampling
/// with a uniform-grid overlap test, largest spheres first). Random sequential insertion jams
/// near a solid fraction of 0.38: throws std::runtime_error if the cavity is too full (use
/// pour() for denser beds).
ParticleSet fill_random(const SolverOptions& options, std::uint64_t seed = 1,
                        int max_attempts_per_particle = 20000);

/// Settling options.
struct SettleOptions {
    double dt_s = 1e-5;                 ///< largest time step [s] (settling_step_s)
    double kinetic_threshold_j = 1e-9;  ///< at rest below this translational kinetic energy [J]
    double max_time_s = 5.0;            ///< give up after this simulated time [s]
    double min_time_s = 0.05;           ///< settle at least this long [s]
    /// Settle with the history-spring friction (contact.tangential = coulomb_spring, same mu)
    /// when the configured law is the stateless directional_coulomb: that law has no static
    /// friction (it ramps to zero below the regularisation slip speed), so a bed on it creeps
    /// and rearranges for a long time instead of coming to rest.
    bool static_friction = true;
    Violations validate() const;
};

/// Steps per contact time below which settling shortens its step. Semi-implicit Euler on a
/// Hooke contact resolved by too few steps returns more energy than it should from each
/// bounce, and the bed never comes to rest: 120 spheres of 3 mm at restitution 0.9 settle at
/// 3.6 steps per contact (k = 4.2e5 N/m, dt = 1e-5 s), one filling in five does not in 5 s
/// at 2.5, and at 1.8 the overlaps blow up (k = 8.5e5 and 1.7e6 N/m); at 3.5 all settle.
inline constexpr double kSettleStepsPerContact = 3.5;

/// The settling step: SettleOptions::dt_s, or a kSettleStepsPerContact-th of the shortest
/// contact where that is shorter: Hooke undamped (two of the smallest spheres, or one against a
/// wall of its own stiffness); Hertz at the speed of a fall across the enclosure's largest
/// extent under the options' gravity (the pair's constant, or 4/3 E* sqrt(R*) of each pair
/// from the materials when the constant is 0; a flat wall).
double settling_step_s(const SolverOptions& options, const ParticleSet& initial,
                       const SettleOptions& so);

/// The kinetic energy is checked every kSettleCheckInterval steps; the bed is at rest once it
/// stays below the threshold for kSettleQuietChecks checks in a row (a bouncing bed passes
/// through low kinetic energy at its turning points).
inline constexpr int kSettleCheckInterval = 100;
inline constexpr int kSettleQuietChecks = 5;

/// Runs the solver with a static enclosure (options.gravity_m_s2 in the enclosure frame) until
/// the translational kinetic energy is at rest by the criterion above; returns the settled
/// particles in the enclosure frame with the velocities and spins they have then (not zeroed,
/// so a saved state continues exactly). Throws std::runtime_error on timeout.
ParticleSet settle(const SolverOptions& options, const ParticleSet& initial,
                   const SettleOptions& settle_options = {});

/// Sum of 1/2 m v^2 over the particles [J] (spin excluded: a sphere spinning about its
/// contact normal meets no resistance).
double translational_kinetic_energy(const ParticleState& particles);

/// Pouring options.
struct PourOptions {
    /// Candidate places drawn per sphere and batch; a batch ends at the first sphere that
    /// finds no free place.
    int max_attempts_per_particle = 5000;
    int max_batches = 50;  ///< insert-and-settle rounds before giving up
    /// Every batch but the last settles only until its kinetic energy is below this multiple
    /// of settle.kinetic_threshold_j (the spheres have landed; the next batch goes into the
    /// space left above them); the last one settles to rest [-].
    double batch_kinetic_factor = 100.0;
    /// Sliding and rolling friction of the batches as a fraction of the configured ones [-].
    /// 1 pours the loose bed friction gives (about 0.55-0.58 in the bulk with mu = 0.6);
    /// 0 packs densely (about 0.6-0.64, as tapping a damper does) when a given mass must fit.
    /// The bed is settled once more with the configured friction at the end.
    double friction_scale = 1.0;
    Violations validate() const;
};

/// Where a pour stands inside one of its settles: enough to continue it bitwise. The batches
/// before are the spheres of `solver`; the settle's options follow from the pour's and from
/// `batch` and `final_settle`.
struct PourProgress {
    std::uint64_t seed = 0;         ///< the pour's seed
    int batch = 0;                  ///< the batch being settled (0 for the first)
    bool final_settle = false;      ///< the last settle, with the configured friction
    std::int64_t settle_steps = 0;  ///< steps of this settle taken
    int quiet_checks = 0;           ///< consecutive quiet checks of the rest criterion so far
    /// The insertion generator after this batch's insertion (std::mt19937_64's text form).
    std::string generator_state;
    SolverState solver;  ///< the settling bed, enclosure at rest at the origin
};

/// Saving a pour's progress, and continuing a saved one. Every kSettleCheckInterval steps of
/// settling `due()` is asked (cheap); when it says yes, `save()` gets the progress there.
struct PourCheckpoints {
    std::function<bool()> due;
    std::function<void(const PourProgress&)> save;
    /// Continue from this progress (taken by `save` from a pour with the same arguments)
    /// instead of starting; throws std::invalid_argument for one that does not fit them.
    const PourProgress* resume = nullptr;
};

/// Fills the cavity the way a bed is poured: a batch of spheres is inserted at random without
/// overlap into the free space (uniform-grid overlap test), settled under gravity inside the
/// real enclosure until at rest (settle()), and the next batch goes into the space left above
/// the bed, until all options.particles.count spheres are in. Works for any gravity direction
/// in the enclosure frame (a horizontally mounted damper fills along gravity), any shape and
/// obstacles, and reaches the poured packing (about 0.55-0.6 in the bulk) that random
/// insertion (0.38) cannot. The spheres keep the order of make_radii(options.particles, seed)
/// (size classes mixed); deterministic for a seed. Throws std::invalid_argument for bad
/// options or zero gravity, std::runtime_error if the settled bed leaves no room for the rest.
///
/// A pour of tens of thousands of spheres settles for hours; `checkpoints` saves its progress
/// as it goes and continues a saved one (PourCheckpoints): a pour resumed from any of its
/// progress records gives bitwise the bed of the uninterrupted pour.
ParticleSet pour(const SolverOptions& options, std::uint64_t seed = 1,
                 const SettleOptions& settle_options = {}, const PourOptions& pour_options = {},
                 const PourCheckpoints& checkpoints = {});

/// Solid fraction of the cavity: sphere volume / cavity volume, obstacles not subtracted [-].
double solid_fraction(const ParticleSet& particles, const Enclosure& enclosure);

/// CSV: "x_m,y_m,z_m,radius_m,vx_m_s,vy_m_s,vz_m_s,wx,wy,wz" with 17 significant digits.
void save_particles(const std::string& path, const ParticleSet& particles);
ParticleSet load_particles(const std::string& path);
/// The same CSV as text (17 significant digits: parse_particles_text() gives the doubles back
/// exactly); `name` stands for the file in messages.
std::string particles_text(const ParticleSet& particles);
ParticleSet parse_particles_text(const std::string& text, const std::string& name);
/// Legacy VTK polydata of a bed in its enclosure frame (velocities relative to the
/// enclosure), for ParaView.
std::string vtk_text(const ParticleSet& local);

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
    double time_step_fraction = 1.0 / 40.0;  ///< dt = fraction * shortest contact time
    /// The smallest spheres of a bed of several sizes: the contact times, and so the time
    /// step, are theirs (the shortest); 0 = particle_diameter_m (one size).
    double smallest_diameter_m = 0.0;
    /// Size k for particle-wall impacts (m* = m, the larger overlap at a given speed), else for
    /// particle-particle impacts (m* = m/2). The time step always follows from the shorter
    /// particle-particle contact time.
    bool wall_contact = true;
    Violations validate() const;
};

/// The chosen values, for logging.
struct AutoStiffness {
    double impact_speed_m_s = 0.0;   ///< used speed (given or a/(2 pi f) + sqrt(2 a_max gap))
    double effective_mass_kg = 0.0;  ///< m* the stiffness was sized for [kg]
    double max_overlap_m = 0.0;
    double stiffness = 0.0;  ///< Hooke [N/m] or Hertz [N/m^1.5]
    /// particle-wall, m* = m of the smallest spheres, at the impact speed [s]
    double wall_contact_time_s = 0.0;
    /// particle-particle, two of the smallest spheres, m* = m/2 (1/sqrt 2 of the wall's for
    /// Hooke, 2^{-2/5} for Hertz) [s]
    double pair_contact_time_s = 0.0;
    double contact_time_s = 0.0;  ///< the shortest of the two (= pair) [s]
    double time_step_s = 0.0;     ///< time_step_fraction * contact_time_s [s]
};

/// Stiffness from the allowed overlap at the impact speed (1/2 m* v^2 = elastic energy at
/// delta_max), time step from the shortest contact time. Throws std::invalid_argument.
AutoStiffness auto_stiffness(const AutoStiffnessInput& input);
/// One line for the run log: stiffness, impact speed, overlap, both contact times, time step.
std::string describe(const AutoStiffness& chosen, NormalLaw law);

/// Hertz contact duration 2.9432 (5 m*/(4 k))^{2/5} v^{-1/5} (undamped; = 2.87 (m*^2/(R* E*^2
/// v))^{1/5} with k = 4/3 E* sqrt(R*)) [s].
double hertz_contact_time(double m_eff, double k, double v);
/// Linear spring-dashpot contact duration pi / sqrt(k/m* - (c/2m*)^2) [s].
double hooke_contact_time(double m_eff, double k, double restitution);
/// Hertz constant k = 4/3 E* sqrt(R*) [N/m^1.5] of two spheres of radii r_a, r_b (R* = r_a r_b
/// / (r_a + r_b); r_b infinite for a flat wall), E* = 1 / ((1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b)
/// (Johnson, Contact Mechanics, 1985, §4.2).
double hertz_constant(const Material& a, double r_a_m, const Material& b, double r_b_m);

/// The contact stiffness and time step for an excitation of one level and frequency (a
/// stepped-sine sweep), and the line that says so in the run log.
struct ExcitationContact {
    double stiffness = 0.0;            ///< Hooke [N/m] or Hertz [N/m^1.5]
    double time_step_s = 0.0;          ///< DEM time step [s]
    double pair_contact_time_s = 0.0;  ///< of two of the smallest spheres [s]
    double impact_speed_m_s = 0.0;     ///< the largest expected impact speed (0: no
                                       ///< excitation given, with a given Hooke stiffness) [m/s]
    std::string log;
    std::string stiffness_log;  ///< log without its time step
};

/// The given stiffness, or auto_stiffness() sized for the largest spheres (largest_diameter_m(),
/// the diameter scatter included) at the largest impact speed of the excitation (peak acceleration
/// a, frequency f, free flight across the enclosure height); the time step is time_step_fraction
/// times the particle-particle contact time of the smallest spheres (smallest_diameter_m(),
/// m* = m/2), the shortest contact of the bed: Hooke damped with `restitution`, Hertz at the
/// impact speed auto_stiffness() estimates. Throws
/// std::invalid_argument (auto_stiffness()'s checks) for inputs it cannot size.
ExcitationContact choose_contact(const ParticleOptions& particles,
                                 const EnclosureOptions& enclosure, NormalLaw law,
                                 double restitution, std::optional<double> given_stiffness,
                                 double max_overlap_fraction, double time_step_fraction,
                                 double peak_acceleration_m_s2, double frequency_hz);

/// The Hertz contact of the materials (no stiffness to choose: each pair's constant 4/3 E*
/// sqrt(R*) from the Young's moduli and Poisson ratios, ExcitationContact::stiffness 0 as
/// ContactOptions::normal_stiffness reads it) and its time step: time_step_fraction times the
/// shorter contact of two of the smallest spheres and of one against a flat wall of the
/// stiffer of `contact`'s wall and side materials, at the largest impact speed
/// choose_contact() estimates (the rest of `contact` is not read). Throws
/// std::invalid_argument for inputs it cannot size.
ExcitationContact materials_contact(const ParticleOptions& particles,
                                    const EnclosureOptions& enclosure,
                                    const ContactOptions& contact, double time_step_fraction,
                                    double peak_acceleration_m_s2, double frequency_hz);

}  // namespace sb::dem

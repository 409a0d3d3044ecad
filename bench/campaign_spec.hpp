// What a stepped-sine campaign runs: arrangements x levels x frequencies, dampers, controller.
// The config keys that fill these structs are declared once, in bench/config_schema.cpp.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "control/options.hpp"
#include "core/violation.hpp"
#include "dem/options.hpp"
#include "dem/setup.hpp"

namespace sb::bench {

/// How the specimen is mounted for one series of sweeps (paper 000, Figs. 1-2): the beam
/// oscillating horizontally or vertically, and the damper axis at an angle to the motion.
struct ArrangementSpec {
    enum class Oscillation { horizontal, vertical };
    static constexpr std::pair<Oscillation, std::string_view> kOscillationNames[] = {
        {Oscillation::horizontal, "horizontal"}, {Oscillation::vertical, "vertical"}};
    std::string name;  ///< e.g. "H-0", "V-45"
    Oscillation oscillation = Oscillation::horizontal;
    double damper_angle_deg = 0.0;  ///< angle between the damper axis and the motion [deg]
    double block_mass_kg = 0.0;     ///< mounting block added at each damper point [kg]
    /// Cathetus of the mounting block, a right isosceles wedge lying on one cathetus with the
    /// enclosure on its hypotenuse (paper 000 Table 1: 20 mm at 45 deg); 0: no wedge [m].
    double block_cathetus_m = 0.0;
    /// Further displacement of the enclosure's mounting face (a spacer, a side mount),
    /// structure frame [m].
    Eigen::Vector3d mount_lift_m{0.0, 0.0, 0.0};
    /// Misalignment of the mount: gravity turned about the beam axis x by this angle
    /// (right-handed; horizontal oscillation: a component g sin(angle) along -z, the motion)
    /// [deg].
    double gravity_tilt_deg = 0.0;

    /// Constraints across keys (the wedge tilts the damper by 45 deg).
    [[nodiscard]] Violations validate() const;
};

/// The frequency grid of every sweep: given, or built around the first mode.
struct FrequencyGridSpec {
    enum class Direction { up, down };
    static constexpr std::pair<Direction, std::string_view> kDirectionNames[] = {
        {Direction::up, "up"}, {Direction::down, "down"}};
    std::vector<double> values_hz;  ///< explicit grid; empty: built around the first mode
    double low_ratio = 0.85;        ///< lowest frequency / first natural frequency [-]
    double high_ratio = 1.15;       ///< highest frequency / first natural frequency [-]
    int count = 11;                 ///< points of the built grid
    /// Damping ratio used to place the built grid: points equally spaced in the phase of a
    /// single mode with this damping, hence denser near resonance [-].
    double grid_damping_ratio = 0.03;
    Direction direction = Direction::up;  ///< step upward or downward
    /// Most frequencies a sweep on this grid adds near its peak when its half-power or
    /// circle-fit estimate is not resolved (0: none).
    int refine_points = 10;

    /// Constraints across keys (high_ratio above low_ratio).
    [[nodiscard]] Violations validate() const;
};

/// The contact law of a damper as the config gives it; the DEM's ContactOptions follow from
/// it per sweep (contact_options()), after every override.
struct ContactSpec {
    dem::NormalLaw normal = dem::NormalLaw::hooke;
    dem::DampingLaw damping = dem::DampingLaw::restitution;
    dem::TangentialLaw tangential = dem::TangentialLaw::directional_coulomb;
    dem::RollingLaw rolling = dem::RollingLaw::constant_torque;
    /// Hooke [N/m] or Hertz [N/m^1.5]; absent: chosen per sweep from max_overlap_fraction at
    /// the largest expected impact speed.
    std::optional<double> normal_stiffness;
    double tangential_stiffness_ratio = 2.0 / 7.0;
    double slip_regularisation_m_s = 1e-4;
    dem::PairProperties particle_particle{};
    /// Particle-wall coefficients; absent: the particle-particle ones (resolved when the
    /// DEM options are made, so a changed particle value carries over).
    std::optional<double> wall_restitution;
    std::optional<double> wall_sliding_friction;
    std::optional<double> wall_rolling_friction;
    std::optional<double> wall_dissipative_constant_s;
    std::optional<double> wall_dashpot_n_s_per_m;
    dem::Material wall_material{};
    /// Particle-rod coefficients and rod material of an obstacle grid; absent: the wall's
    /// (the damping constants of the viscoelastic and viscous laws always are the wall's).
    std::optional<double> rod_restitution;
    std::optional<double> rod_sliding_friction;
    std::optional<double> rod_rolling_friction;
    std::optional<double> rod_youngs_modulus_pa;
    std::optional<double> rod_poisson_ratio;
    /// Particle-side coefficients and material of the lateral surface (paper 000: a PMMA
    /// tube between aluminium ends); absent: the wall's.
    std::optional<double> side_restitution;
    std::optional<double> side_sliding_friction;
    std::optional<double> side_rolling_friction;
    std::optional<double> side_youngs_modulus_pa;
    std::optional<double> side_poisson_ratio;
    /// Automatic stiffness: largest overlap as a fraction of the diameter at the largest
    /// expected impact speed [-].
    double max_overlap_fraction = 0.01;
    /// DEM step / pair contact time [-]; absent: the largest of dem::kTimeStepLadder at
    /// which single impacts give the converged restitution (dem::automatic_time_step_fraction:
    /// a tenth for e >= 0.9 and Hertz 0.7, a twentieth for Hooke 0.7, finer below;
    /// docs/validation.md).
    std::optional<double> time_step_fraction;
    /// What an automatic stiffness is sized for: the largest level of the campaign (one
    /// stiffness, one time step for every sweep, so the damping curve does not change its
    /// numerics along the levels) or each sweep's own level; or, for the Hertz law, no sizing
    /// at all: each pair's constant from the materials (dem::materials_contact, its time step
    /// for the campaign's largest level).
    enum class StiffnessFor { campaign, level, materials };
    static constexpr std::pair<StiffnessFor, std::string_view> kStiffnessForNames[] = {
        {StiffnessFor::campaign, "campaign"},
        {StiffnessFor::level, "level"},
        {StiffnessFor::materials, "materials"}};
    StiffnessFor stiffness_for = StiffnessFor::campaign;

    /// The level [g] an automatic contact is sized for: the sweep's own with stiffness_for =
    /// "level", else the campaign's largest.
    [[nodiscard]] double sized_for_g(double level_g, double largest_level_g) const {
        return stiffness_for == StiffnessFor::level ? level_g : largest_level_g;
    }
    /// The particle-wall coefficients in use.
    [[nodiscard]] dem::PairProperties particle_wall() const;
    /// The particle-rod coefficients, when any differs from the wall's.
    [[nodiscard]] std::optional<dem::PairProperties> particle_rod() const;
    /// The rod material, when it differs from the wall's.
    [[nodiscard]] std::optional<dem::Material> rod_material() const;
    /// The particle-side coefficients, when any differs from the wall's.
    [[nodiscard]] std::optional<dem::PairProperties> particle_side() const;
    /// The lateral surface's material, when it differs from the wall's.
    [[nodiscard]] std::optional<dem::Material> side_material() const;
    /// The DEM contact options with `normal_stiffness` (the given or the chosen one).
    [[nodiscard]] dem::ContactOptions contact_options(double normal_stiffness) const;
};

/// A particle damper attached to the structure.
struct DamperSpec {
    /// dem: the particles simulated; rigid: an equal rigid mass; describing_function: the
    /// complex apparent mass a characterisation measured (docs/characterisation.md).
    enum class Model { dem, rigid, describing_function };
    static constexpr std::pair<Model, std::string_view> kModelNames[] = {
        {Model::dem, "dem"},
        {Model::rigid, "rigid"},
        {Model::describing_function, "describing-function"}};
    /// How the bed is filled before it settles: random insertion into the whole cavity
    /// (loose beds, up to a solid fraction of about 0.35) or pouring in batches that settle
    /// under gravity (dense beds such as paper 002's 90 % fill).
    enum class Fill { random, pour };
    static constexpr std::pair<Fill, std::string_view> kFillNames[] = {{Fill::random, "random"},
                                                                       {Fill::pour, "pour"}};
    std::string name;
    std::string point;  ///< named point of the structure it is attached to
    /// Enclosure frame origin (inner bottom centre) relative to the point, structure frame,
    /// before the arrangement's tilt [m].
    Eigen::Vector3d mount_offset_m{0.0, 0.0, 0.0};
    /// Thickness of the enclosure's bottom plate: the enclosure stands, and turns, on its
    /// outer bottom face, this far below the origin along the axis [m].
    double bottom_thickness_m = 0.0;
    /// Name of the structure's lumped mass that is this damper's enclosure: moved and turned
    /// with the mounting of every arrangement; empty: none.
    std::string enclosure_mass;
    /// Particles locked to the enclosure (a rigid bed moved through the coupling loop; a
    /// check of the loop against the linear model).
    bool locked = false;
    /// A share of the particles held to the enclosure and freed at a set time of the run
    /// (paper 004's electromagnet); `locked` holds them all for good instead.
    dem::LockOptions lock{};
    /// dem: particles simulated; rigid: particles replaced by an equal rigid mass;
    /// describing_function: the apparent mass of `characterization_file`.
    Model model = Model::dem;
    /// characterization.csv of `shakerbench characterize` (model = describing_function).
    std::filesystem::path characterization_file;
    /// How many times the characterised bed this damper holds: the describing function's
    /// apparent mass (and bed mass) multiplied by it, a representative part of a bed (a
    /// quarter of its footprint, a column of a grid's cells) characterised for the whole.
    double characterization_scale = 1.0;
    int threads = 1;                      ///< OpenMP threads of this damper's DEM
    double guard_overlap_fraction = 0.5;  ///< overlap / radius beyond which the run stops [-]
    dem::EnclosureOptions enclosure{};
    dem::ParticleOptions particles{};
    ContactSpec contact{};
    dem::SettleOptions settle{};
    Fill fill = Fill::random;

    /// The DEM options of this damper with the contact stiffness `normal_stiffness`; gravity
    /// is the caller's.
    [[nodiscard]] dem::SolverOptions solver_options(double normal_stiffness) const;
    /// The contact stiffness and DEM time step for an excitation of peak acceleration
    /// `peak_acceleration_m_s2` at `frequency_hz` (dem::choose_contact, and
    /// dem::with_automatic_time_step when contact.time_step_fraction is absent).
    [[nodiscard]] dem::ExcitationContact excitation_contact(double peak_acceleration_m_s2,
                                                            double frequency_hz) const;
    /// Constraints across keys, as the DEM module checks them: keys relative to
    /// dem::SolverOptions under "solver." and to dem::SettleOptions under "settle.".
    [[nodiscard]] Violations validate() const;
};

/// A recorded channel besides the control and response accelerations: a named point's
/// acceleration, velocity or displacement along any direction (absolute under base
/// excitation), or the force a damper applies to the structure (paper 001 drives z and reads
/// y and z; paper 004 reads the tip displacement).
struct ChannelSpec {
    enum class Quantity { acceleration, velocity, displacement, damper_force };
    static constexpr std::pair<Quantity, std::string_view> kQuantityNames[] = {
        {Quantity::acceleration, "acceleration"},
        {Quantity::velocity, "velocity"},
        {Quantity::displacement, "displacement"},
        {Quantity::damper_force, "damper-force"}};
    std::string name;  ///< channel name; empty: made from the quantity, point and direction
    Quantity quantity = Quantity::acceleration;
    std::string point;   ///< named point (motion quantities)
    std::string damper;  ///< the damper whose force on the structure is read (damper-force)
    /// Direction of the reading (normalised when used); absent: the excitation direction.
    std::optional<Eigen::Vector3d> direction;
};

/// A run from rest instead of a stepped sine: each sweep (arrangement x fixed-drive
/// amplitude) drives the specimen at one frequency for a set time, starting at rest, and
/// records the time histories and their envelope per period (paper 004's eccentric exciter
/// with the granules released at 5 s).
struct TransientSpec {
    double duration_s = 0.0;             ///< 0: a stepped-sine campaign [s]
    std::optional<double> frequency_hz;  ///< drive frequency [Hz]
    int checkpoint_periods = 20;         ///< periods between checkpoints

    [[nodiscard]] bool on() const { return duration_s > 0.0; }
};

/// A random test instead of a stepped sine (paper 003, Figs. 6-8): each sweep drives the
/// specimen with band-limited Gaussian noise, holds the RMS of the control channel in the band
/// (or drives a fixed RMS force), and estimates H1 by Welch's averaged spectra
/// (docs/campaign.md, random tests).
struct RandomSpec {
    double low_hz = 0.0;           ///< lower edge of the drive and analysis band [Hz]
    double high_hz = 0.0;          ///< upper edge; 0: no random test [Hz]
    double resolution_hz = 0.125;  ///< line spacing; a segment lasts 1 / resolution [s]
    int averages = 16;             ///< Hann segments averaged, overlapping by half [-]
    int level_blocks = 8;          ///< most segments run to bring the level in [-]
    double tolerance = 0.05;       ///< relative RMS error at which the level holds [-]
    int checkpoint_segments = 4;   ///< half segments of the averaging between checkpoints [-]

    [[nodiscard]] bool on() const { return high_hz > 0.0; }
    /// Segments run in all at most: the level's, then the acquisition's half-overlapping ones.
    [[nodiscard]] double longest_run_s() const {
        return (level_blocks + 0.5 * (averages + 1)) / resolution_hz;
    }
};

/// What a campaign writes besides points.csv and damping.csv.
struct OutputSpec {
    bool series = false;  ///< time histories of the steady windows in series/
    int series_samples_per_period = 128;
    bool uff = true;    ///< transfer functions as UFF58
    bool plots = true;  ///< SVG plots through gnuplot, when it is installed
    /// energy.csv: per point and DEM damper, the energy per period over the steady window by
    /// mechanism and per horizontal layer (the DEM's energy ledger).
    bool energy = false;
    int energy_layers = 10;  ///< layers along gravity of energy.csv
    /// ParaView files of the beds in vtk/: none, at the point of largest response of each
    /// sweep, or at every point.
    enum class Vtk { none, resonance, all };
    static constexpr std::pair<Vtk, std::string_view> kVtkNames[] = {
        {Vtk::none, "none"}, {Vtk::resonance, "resonance"}, {Vtk::all, "all"}};
    Vtk vtk = Vtk::none;
};

/// How each point's drive amplitude is set: by the RMS controller to a target level at the
/// control point (paper 000, section 3.2), or fixed per sweep, as an open-loop test holds its
/// signal generator's voltage or its eccentric's throw (papers 002 and 004).
struct DriveSpec {
    enum class Kind { controlled, fixed };
    static constexpr std::pair<Kind, std::string_view> kKindNames[] = {
        {Kind::controlled, "controlled"}, {Kind::fixed, "fixed"}};
    /// What a fixed amplitude is: the excitation's own input (a force [N], a base
    /// acceleration [m/s^2], through physics.shaker a voltage [V]) or, under base excitation,
    /// the base displacement [m], whose acceleration (2 pi f)^2 X grows along the sweep.
    enum class Quantity { excitation, base_displacement };
    static constexpr std::pair<Quantity, std::string_view> kQuantityNames[] = {
        {Quantity::excitation, "excitation"}, {Quantity::base_displacement, "base-displacement"}};
    Kind kind = Kind::controlled;
    Quantity quantity = Quantity::excitation;
    /// Peak drive amplitudes of a fixed drive, one sweep each (they are its levels).
    std::vector<double> amplitudes;

    [[nodiscard]] bool fixed() const { return kind == Kind::fixed; }
    /// The amplitude in the excitation's unit of the fixed drive `amplitude` at `frequency_hz`.
    [[nodiscard]] double excitation_amplitude(double amplitude, double frequency_hz) const;
};

struct CampaignSpec {
    /// How the structure starts every point after the first of a sweep (the first always
    /// starts from the linear steady state, the particles from their settled bed; later
    /// points keep the particles' state):
    /// - previous_state: where the previous point left it (a lightly damped specimen then
    ///   carries the frequency step's transient for 1/(2 pi zeta) periods per e-fold);
    /// - linear_steady_state: the linear steady state at the new frequency and start
    ///   amplitude, exact for a linear specimen but, with 0.5 % damping, far from a
    ///   particle-damped beam's response near resonance;
    /// - equivalent_steady_state (default): that state scaled in amplitude and phase to the
    ///   response the previous point's equivalent driven mode predicts (bench/driven_mode.hpp):
    ///   exact for a linear specimen, and near the steady state of a particle-damped one.
    enum class PointStart { previous_state, linear_steady_state, equivalent_steady_state };
    static constexpr std::pair<PointStart, std::string_view> kPointStartNames[] = {
        {PointStart::previous_state, "previous-state"},
        {PointStart::equivalent_steady_state, "equivalent-steady-state"},
        {PointStart::linear_steady_state, "linear-steady-state"}};

    std::vector<double> levels_g;  ///< target RMS levels at the control point [g]
    DriveSpec drive;
    /// Every arrangement the config defines, in file order.
    std::vector<ArrangementSpec> arrangements;
    /// The names of the arrangements to run, in order; empty: all defined.
    std::vector<std::string> arrangement_selection;
    FrequencyGridSpec frequencies;
    std::string control_point = "damper";      ///< named point whose acceleration is controlled
    std::vector<std::string> response_points;  ///< other recorded points (acceleration)
    std::vector<ChannelSpec> channels;         ///< further channels, any direction and quantity
    TransientSpec transient;                   ///< a run from rest instead of stepped sines
    RandomSpec random;                         ///< a random test instead of stepped sines
    std::vector<DamperSpec> dampers;
    /// The controller; without an initial amplitude every sweep starts from the linear model.
    control::ControllerOptions controller = [] {
        control::ControllerOptions options;
        options.initial_amplitude.reset();
        return options;
    }();
    OutputSpec output;
    std::uint64_t seed = 1;  ///< particle filling
    /// Fillings of the bed per sweep (seeds seed, seed + 1, ...): the damping per level is
    /// their mean, with their scatter.
    int seeds = 1;
    PointStart point_start = PointStart::equivalent_steady_state;
    /// When the controller changes the amplitude within a point by the ratio r, the
    /// structure's harmonic response is scaled by r about its mean over the last period
    /// (SpecimenPlant): exact for a linear specimen, and it spares a particle-damped beam the
    /// slow transient (several periods per 1/(2 pi zeta)) that the jump would otherwise start.
    bool scale_response_on_update = true;

    /// The arrangements to run, in order (the selection, or every one defined).
    [[nodiscard]] std::vector<ArrangementSpec> selected_arrangements() const;
    /// The level of every sweep: levels_g, or under a fixed drive its amplitudes.
    [[nodiscard]] const std::vector<double>& levels() const {
        return drive.fixed() ? drive.amplitudes : levels_g;
    }
};

}  // namespace sb::bench

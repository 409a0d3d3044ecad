// What a stepped-sine campaign runs: arrangements x levels x frequencies, dampers, controller.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "control/options.hpp"
#include "dem/options.hpp"
#include "dem/setup.hpp"

namespace sb::bench {

/// How the specimen is mounted for one series of sweeps (paper 000, Figs. 1-2): the beam
/// oscillating horizontally or vertically, and the damper axis at an angle to the motion.
struct ArrangementSpec {
    enum class Oscillation { horizontal, vertical };
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
};

/// The frequency grid of every sweep: given, or built around the first mode.
struct FrequencyGridSpec {
    std::vector<double> values_hz;  ///< explicit grid; empty: built around the first mode
    double low_ratio = 0.85;        ///< lowest frequency / first natural frequency [-]
    double high_ratio = 1.15;       ///< highest frequency / first natural frequency [-]
    int count = 11;                 ///< points of the built grid
    /// Damping ratio used to place the built grid: points equally spaced in the phase of a
    /// single mode with this damping, hence denser near resonance [-].
    double grid_damping_ratio = 0.03;
    bool descending = false;  ///< step downward instead of upward
};

/// A particle damper attached to the structure.
struct DamperSpec {
    enum class Model { dem, rigid };
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
    /// dem: particles simulated; rigid: particles replaced by an equal rigid mass.
    Model model = Model::dem;
    dem::SolverOptions solver;  ///< particles, enclosure, contact law (gravity set per arrangement)
    /// Automatic stiffness when solver.contact.normal_stiffness is 0: largest overlap as a
    /// fraction of the diameter at the largest expected impact speed [-].
    double max_overlap_fraction = 0.01;
    double time_step_fraction = 1.0 / 20.0;  ///< DEM step / contact time [-]
    dem::SettleOptions settle;
    /// How the bed is filled before it settles: random insertion into the whole cavity
    /// (loose beds, up to a solid fraction of about 0.35) or pouring in batches that settle
    /// under gravity (dense beds such as paper 002's 90 % fill).
    enum class Fill { random, pour } fill = Fill::random;
};

/// What a campaign writes besides points.csv and damping.csv.
struct OutputSpec {
    bool series = false;  ///< time histories of the steady windows in series/
    int series_samples_per_period = 128;
    bool uff = true;    ///< transfer functions as UFF58
    bool plots = true;  ///< SVG plots through gnuplot, when it is installed
};

struct CampaignSpec {
    std::vector<double> levels_g;  ///< target RMS levels at the control point [g]
    std::vector<ArrangementSpec> arrangements;
    FrequencyGridSpec frequencies;
    std::string control_point;                 ///< named point whose acceleration is controlled
    std::vector<std::string> response_points;  ///< other recorded points (acceleration)
    std::vector<DamperSpec> dampers;
    control::ControllerOptions controller;
    OutputSpec output;
    std::uint64_t seed = 1;  ///< particle filling
    /// How the structure starts every point after the first of a sweep (the first always
    /// starts from the linear steady state, the particles from their settled bed; later
    /// points keep the particles' state):
    /// - previous_state (default, design.md): where the previous point left it;
    /// - linear_steady_state: the linear steady state at the new frequency and start
    ///   amplitude, exact for a linear specimen but, with 0.5 % damping, far from a
    ///   particle-damped beam's response near resonance;
    /// - equivalent_steady_state: that state scaled in amplitude and phase to the response
    ///   the previous point's equivalent driven mode predicts (bench/driven_mode.hpp).
    enum class PointStart { previous_state, linear_steady_state, equivalent_steady_state };
    PointStart point_start = PointStart::previous_state;
    /// When the controller changes the amplitude within a point by the ratio r, the
    /// structure's harmonic response is scaled by r about its mean over the last period
    /// (SpecimenPlant): exact for a linear specimen, and it spares a particle-damped beam the
    /// slow transient (several periods per 1/(2 pi zeta)) that the jump would otherwise start.
    bool scale_response_on_update = true;
};

}  // namespace sb::bench

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
    /// dem: particles simulated; rigid: particles replaced by an equal rigid mass.
    Model model = Model::dem;
    dem::SolverOptions solver;  ///< particles, enclosure, contact law (gravity set per arrangement)
    /// Automatic stiffness when solver.contact.normal_stiffness is 0: largest overlap as a
    /// fraction of the diameter at the largest expected impact speed [-].
    double max_overlap_fraction = 0.01;
    double time_step_fraction = 1.0 / 20.0;  ///< DEM step / contact time [-]
    dem::SettleOptions settle;
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
    /// Every point starts the structure from its linear steady state at the new frequency
    /// and start amplitude (particles keep their state); false: from the previous point's
    /// state. A lightly damped beam (0.5 %) needs about 1/(zeta 2 pi) = 30 periods per e-fold
    /// to forget a frequency step: the linear start spares those, and is exact for a linear
    /// specimen.
    bool start_points_linear = true;
};

}  // namespace sb::bench

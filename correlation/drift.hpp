// The parameter-drift test of a diagnosis (research note on mismatch diagnosis; Green,
// Chodora, Zhu and Atamturktur): a value that should not depend on the level (a friction
// coefficient, a background damping ratio) calibrated at each level on its own; a systematic
// trend with the level says the model misses a physics that the value stands in for.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "correlation/calibration.hpp"

namespace sb::correlation {

/// The value calibrated at one arrangement and level.
struct LevelValue {
    std::string arrangement;
    double level_g = 0.0;
    double value = 0.0;
    double lo95 = 0.0;
    double hi95 = 0.0;
    bool identifiable = false;
    int simulations = 0;
};

struct DriftResult {
    FreeParameter parameter;
    std::vector<LevelValue> levels;  ///< in the measurement's order
    /// Weighted least-squares line value = a + b A over the identifiable levels (σ from their
    /// intervals, (hi − lo)/3.92): the slope b, its standard error, and χ² of a constant.
    double slope = 0.0;        ///< [value unit / g]
    double slope_sigma = 0.0;  ///< [value unit / g]
    double constant_chi2 = 0.0;
    int used = 0;  ///< identifiable levels in the fit
    /// The constant's χ² beyond its 99 % quantile (used − 1 degrees of freedom): the value
    /// drifts with the level.
    bool drifts = false;
    std::string sentence;  ///< in words
};

/// Simulates the evaluations of the calibration at sweep `level` of the measurement in other
/// processes (CalibrationOptions::remote, told which level it serves).
using LevelRemote = std::function<std::vector<std::string>(std::size_t level,
                                                           const std::vector<std::string>& inputs)>;

/// Calibrates `parameter` alone at each arrangement and level of `measurement` (the other
/// levels left out), with `options`, and tests the values for a trend. Needs two identifiable
/// levels for a verdict (the sentence says so otherwise). With `level_remote`, each level's
/// evaluations are simulated through it. Throws what calibrate throws.
DriftResult drift_test(const bench::CampaignConfig& config, const Measurement& measurement,
                       const FreeParameter& parameter, const CalibrationOptions& options,
                       const LevelRemote& level_remote = {});

/// The measurement restricted to one arrangement and level: its features and its sweep.
Measurement level_measurement(const Measurement& measurement, const std::string& arrangement,
                              double level_g);

}  // namespace sb::correlation

// Amplitude update rules: ratio target/level and the secant through a widened bracket.
#pragma once

#include <optional>

#include "control/options.hpp"

namespace sb::control {

/// An amplitude and the level it produced.
struct Sample {
    double amplitude = 0.0;  ///< [input unit]
    double level = 0.0;      ///< [channel unit]
};

/// The best sample below and the best sample above the target seen since the last restart.
class Bracket {
  public:
    /// Adds a sample. A sample that improves on neither side means the plant contradicts the
    /// bracket (scatter, hysteresis): both points are forgotten, the sample starts a new
    /// bracket, and false is returned (a restart).
    bool add(const Sample& sample, double target_rms);
    void clear();
    [[nodiscard]] const std::optional<Sample>& lower() const { return lower_; }
    [[nodiscard]] const std::optional<Sample>& upper() const { return upper_; }

    /// Secant ("loosened gradient") through the two points with their levels widened outward
    /// by overshoot * tolerance, aimed at the target. Empty when a side is missing, the two
    /// points are closer than the tolerance can resolve, or the slope is not positive.
    [[nodiscard]] std::optional<double> secant(double target_rms,
                                               const ControllerOptions& options) const;

  private:
    std::optional<Sample> lower_{};
    std::optional<Sample> upper_{};
};

/// Exponents accepted for the power-law gradient: a response growing with less than the 4th
/// root or more than the 4th power of the drive is taken as noise, not as a trend.
inline constexpr double kMinPowerLawExponent = 0.25;
inline constexpr double kMaxPowerLawExponent = 4.0;

/// Gradient step for when the ratio rule stalls (two measured levels on the same side of the
/// target): the local exponent p of level ~ amplitude^p from the two samples (a secant in
/// log-log), then newer.amplitude * (target / newer.level)^(1/p). Empty when the levels are
/// closer than 2 * overshoot * tolerance (relative) or the response does not grow with the drive.
[[nodiscard]] std::optional<double> power_law_amplitude(const Sample& older, const Sample& newer,
                                                        double target_rms,
                                                        const ControllerOptions& options);

/// Ratio rule amplitude * target / level (infinite for a zero level).
[[nodiscard]] double ratio_amplitude(double amplitude, double level, double target_rms);

/// `proposed` limited to a factor max_step_factor away from `current` and to the bounds; a
/// non-finite or non-positive proposal counts as a step to the nearer limit.
[[nodiscard]] double limit_step(double current, double proposed, const ControllerOptions& options);

/// The warm start after a point driven at `amplitude` that gave `level`: the drive it would
/// still have needed for `target_rms` (the ratio rule), limited by limit_step. A point
/// accepted within the tolerance but off target does not hand its miss on to the next.
[[nodiscard]] double warm_start_amplitude(double amplitude, double level, double target_rms,
                                          const ControllerOptions& options);

}  // namespace sb::control

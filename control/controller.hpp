// The RMS amplitude controller of paper 000, section 3.2, against an abstract plant.
#pragma once

#include "control/options.hpp"
#include "control/plant.hpp"
#include "control/result.hpp"

namespace sb::control {

/// Drives a plant, one stepped-sine point at a time, until the per-period RMS of its control
/// channel settles within tolerance of a target (docs/control.md gives the algorithm). Keeps
/// the warm start between points of a sweep.
class AmplitudeController {
  public:
    /// Throws std::invalid_argument listing every violation of options.validate().
    explicit AmplitudeController(const ControllerOptions& options);

    /// Controls one point at `frequency_hz` [Hz] to `target_rms` [channel unit], starting
    /// from start_amplitude(target_rms). Throws std::invalid_argument for a non-positive
    /// frequency or target and std::runtime_error if the plant reports a negative or
    /// non-finite RMS.
    PointResult run_point(Plant& plant, double frequency_hz, double target_rms);

    /// Amplitude the next point starts from: the previous point's amplitude times
    /// target_rms / its recorded RMS (limited to max_step_factor and the bounds), or
    /// initial_amplitude before the first point or after reset() (std::logic_error when it is
    /// absent and no start was set).
    [[nodiscard]] double start_amplitude(double target_rms) const;

    /// Overrides the warm start: the next point starts exactly at `amplitude`.
    void set_start_amplitude(double amplitude);

    /// Forgets the warm start (a new sweep starts at initial_amplitude).
    void reset();

    [[nodiscard]] const ControllerOptions& options() const { return options_; }

  private:
    ControllerOptions options_;
    double previous_amplitude_ = 0.0;  ///< 0 = no previous point
    double previous_rms_ = 0.0;
    double forced_start_ = 0.0;  ///< 0 = none
};

}  // namespace sb::control

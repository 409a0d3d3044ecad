// One stepped-sine point at a fixed drive amplitude: no controller, run until steady.
#pragma once

#include "control/options.hpp"
#include "control/plant.hpp"
#include "control/result.hpp"

namespace sb::control {

/// Drives `plant` at `frequency_hz` [Hz] with the fixed `amplitude` [input unit] (an
/// open-loop test: a signal generator at a set voltage, an eccentric of set throw) until the
/// control channel is steady by the controller's own test (assess_steady: a window of
/// window_periods values within the tolerance, its drift and phase too, a value being a period
/// or the mean of average_periods of them) or a two-period cycle, after transient_periods;
/// status `converged` or `limit-cycle-2`, the window recorded. Within max_periods neither:
/// status `unsettled`, the newest half of the periods after the transient (at least a
/// window's) recorded, whose mean is the best estimate of a response that scatters from
/// period to period (a chaotic bed). target_rms is 0.
/// Throws std::invalid_argument for invalid options or a non-positive frequency or amplitude,
/// std::runtime_error if the plant reports a negative or non-finite RMS.
PointResult run_fixed_point(Plant& plant, double frequency_hz, double amplitude,
                            const ControllerOptions& options);

}  // namespace sb::control

// Judging a window of per-period RMS values: settled, two-period cycle, or early decision.
#pragma once

#include <span>

#include "control/options.hpp"

namespace sb::control {

/// State of the values measured since the last amplitude or frequency change.
enum class WindowState {
    kFilling,      ///< fewer than window_periods values and no early decision
    kUnsettled,    ///< a full window that is neither settled nor beyond the target
    kSettled,      ///< a full window within tolerance
    kLimitCycle2,  ///< limit_cycle_periods values alternating period to period
    kEarlyLow,     ///< every value below target / (1 + tolerance), not drifting up
    kEarlyHigh,    ///< every value above target / (1 - tolerance), not drifting down
};

struct WindowVerdict {
    WindowState state = WindowState::kFilling;
    double level = 0.0;  ///< level to act on [channel unit]; 0 when nothing to act on
    int count = 0;       ///< newest values the level stands for (length of the window)
};

/// Judges `values` (per-period RMS since the last change, transient already skipped, oldest
/// first; only the newest window_periods count; no unfilled slot votes) against `target_rms`.
[[nodiscard]] WindowVerdict assess_window(std::span<const double> values, double target_rms,
                                          const ControllerOptions& options);

}  // namespace sb::control

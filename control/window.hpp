// Judging a window of per-period RMS values: settled, two-period cycle, or early decision.
#pragma once

#include <complex>
#include <optional>
#include <span>

#include "control/options.hpp"

namespace sb::control {

/// State of the values measured since the last amplitude or frequency change.
enum class WindowState {
    kFilling,      ///< fewer than window_periods values and no early decision
    kUnsettled,    ///< a full window that is neither settled nor beyond the target
    kSettled,      ///< a full window within tolerance, not drifting beyond half of it
    kLimitCycle2,  ///< limit_cycle_periods values alternating period to period
    kEarlyLow,     ///< every value below target / (1 + tolerance), and so is where it drifts to
    kEarlyHigh,    ///< every value above target / (1 - tolerance), and so is where it drifts to
};

struct WindowVerdict {
    WindowState state = WindowState::kFilling;
    /// Level to act on [channel unit]; 0 when nothing to act on. Settled: the steady value
    /// the window approaches (its mean when it does not drift).
    double level = 0.0;
    int count = 0;      ///< newest values the level stands for (length of the window)
    double mean = 0.0;  ///< mean of those values [channel unit]
    /// The level is the steady value a geometric decay heads for, not a value seen.
    bool extrapolated = false;
};

/// What a monotone window says about the value it approaches, modelled as the geometric
/// decay of a transient: successive differences d_k = d_0 r^k, so the change still to come
/// is d_last r / (1 - r) (Aitken). A linearised structure's per-period RMS approaches its
/// steady state so, with r = exp(-2 pi zeta f_n / f).
struct Drift {
    bool monotone = false;  ///< every difference of one sign
    /// Geometric decay (0 < r < 1, at least four values whose two or more successive ratios
    /// agree within a factor 2) whose extrapolation reaches no further than
    /// drift_horizon_periods: `remaining` is then the model's estimate.
    bool decaying = false;
    double ratio = 0.0;      ///< least-squares r of d_{k+1} = r d_k [-]
    double remaining = 0.0;  ///< change still to come [channel unit], capped at the horizon
};

/// The drift of `values` (oldest first, at least 3); a horizon of 0 disables it (never
/// monotone).
[[nodiscard]] Drift assess_drift(std::span<const double> values, int horizon_periods);

/// The steady part of assess_window, without a target: a settled window or a two-period
/// cycle among `values` (oldest first, transient already skipped), or nothing. A fixed drive
/// (no controller) records a point once this holds.
[[nodiscard]] std::optional<WindowVerdict> assess_steady(
    std::span<const double> values, const ControllerOptions& options,
    std::span<const std::complex<double>> fundamentals = {});

/// Judges `values` (per-period RMS since the last change, transient already skipped, oldest
/// first; only the newest window_periods count; no unfilled slot votes) against `target_rms`.
/// With `fundamentals` (the control channel's complex fundamental of the same periods), a
/// window is only settled when they agree too: a transient at the structure's own frequency
/// beats against the drive and turns the period's phasor while the RMS may hardly change.
[[nodiscard]] WindowVerdict assess_window(std::span<const double> values, double target_rms,
                                          const ControllerOptions& options,
                                          std::span<const std::complex<double>> fundamentals = {});

/// True when every two of the newest `count` phasors are apart by at most `tolerance` times
/// the largest of their magnitudes (the RMS spread test of the window, for complex values).
[[nodiscard]] bool phasors_within(std::span<const std::complex<double>> phasors, std::size_t count,
                                  double tolerance);

}  // namespace sb::control

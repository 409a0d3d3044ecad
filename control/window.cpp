// Settling, two-period cycle and early-decision tests on the per-period RMS window.
#include "control/window.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>

namespace sb::control {
namespace {

double mean(std::span<const double> v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

/// True when max - min <= tolerance * max over every stride-th value from `first`.
bool within(std::span<const double> v, std::size_t first, std::size_t stride, double tolerance) {
    double lo = v[first];
    double hi = v[first];
    for (std::size_t i = first; i < v.size(); i += stride) {
        lo = std::min(lo, v[i]);
        hi = std::max(hi, v[i]);
    }
    return hi - lo <= tolerance * hi;
}

/// Newest value strictly beyond all others on one side and oldest strictly beyond all others
/// on the other: a monotonic drift (HFelem's veto). `rising` selects the direction.
bool drifts(std::span<const double> v, bool rising) {
    const double newest = v.back();
    const double oldest = v.front();
    const auto inner = v.subspan(1, v.size() - 2);
    const double inner_lo = *std::min_element(inner.begin(), inner.end());
    const double inner_hi = *std::max_element(inner.begin(), inner.end());
    if (rising) {
        return newest > std::max(inner_hi, oldest) && oldest < std::min(inner_lo, newest);
    }
    return newest < std::min(inner_lo, oldest) && oldest > std::max(inner_hi, newest);
}

}  // namespace

WindowVerdict assess_window(std::span<const double> values, double target_rms,
                            const ControllerOptions& options) {
    const auto n = static_cast<std::size_t>(options.window_periods);
    const double tol = options.tolerance;
    const std::size_t m = std::min(values.size(), n);
    const auto w = values.subspan(values.size() - m, m);  // newest m values, oldest first

    // Settled: the whole window within the tolerance (paper 000: "does not vary
    // significantly for a certain number of periods").
    if (m == n && within(w, 0, 1, tol)) {
        return {WindowState::kSettled, mean(w), static_cast<int>(m)};
    }
    // Two-period limit cycle: consecutive values clearly apart and every other value within
    // the tolerance over limit_cycle_periods values (HFelem's alternation test, with more
    // repetitions so that scatter does not pass it). Level = the two-period mean.
    const auto l = static_cast<std::size_t>(options.limit_cycle_periods);
    if (values.size() >= l) {
        const auto c = values.subspan(values.size() - l, l);
        const double a = c[l - 1];
        const double b = c[l - 2];
        const double jump = std::abs(a - b) / std::max(a, b);
        if (jump >= options.limit_cycle_jump * tol && within(c, 0, 2, tol) &&
            within(c, 1, 2, tol)) {
            return {WindowState::kLimitCycle2, mean(c), static_cast<int>(l)};
        }
    }

    if (m >= static_cast<std::size_t>(options.early_periods)) {
        // Early decision: every value beyond the target by more than the tolerance, unless
        // the window is still drifting toward the target (then it may yet get there). The
        // level acted on is the value nearest the target, so the update cannot overshoot.
        const bool low =
            std::all_of(w.begin(), w.end(), [&](double v) { return (1.0 + tol) * v < target_rms; });
        const bool high =
            std::all_of(w.begin(), w.end(), [&](double v) { return (1.0 - tol) * v > target_rms; });
        if (low && !drifts(w, true)) {
            return {WindowState::kEarlyLow, *std::max_element(w.begin(), w.end()),
                    static_cast<int>(m)};
        }
        if (high && !drifts(w, false)) {
            return {WindowState::kEarlyHigh, *std::min_element(w.begin(), w.end()),
                    static_cast<int>(m)};
        }
    }
    return {m == n ? WindowState::kUnsettled : WindowState::kFilling, 0.0, 0};
}

}  // namespace sb::control

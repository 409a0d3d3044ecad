// Settling, two-period cycle and early-decision tests on the per-period RMS window.
#include "control/window.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <optional>

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

/// Largest share of the tolerance a settled window may still be drifting by: then a level
/// accepted within the tolerance has its steady state within 1.5 tolerances at worst, and
/// within one for a geometric approach, whose steady value is the level acted on.
constexpr double kSettledDriftShare = 0.5;

/// Successive ratios of a decaying transient agree; scatter gives ratios all over the place.
/// Two ratios further apart than this factor are not one geometric decay [-].
constexpr double kRatioSpread = 2.0;

/// The drift horizon in the window's values: drift_horizon_periods is in periods, and a
/// value stands for average_periods of them.
int horizon_values(const ControllerOptions& options) {
    const int a = std::max(options.average_periods, 1);
    return (options.drift_horizon_periods + a - 1) / a;
}

}  // namespace

Drift assess_drift(std::span<const double> v, int horizon_periods) {
    Drift drift;
    if (horizon_periods <= 0 || v.size() < 3) return drift;
    double sign = 0.0;
    double num = 0.0;
    double den = 0.0;
    double lo_ratio = std::numeric_limits<double>::infinity();
    double hi_ratio = 0.0;
    for (std::size_t i = 1; i < v.size(); ++i) {
        const double d = v[i] - v[i - 1];
        const double s = d > 0.0 ? 1.0 : (d < 0.0 ? -1.0 : 0.0);
        if (s == 0.0 || (sign != 0.0 && s != sign)) return drift;  // not monotone
        sign = s;
        if (i >= 2) {
            const double previous = v[i - 1] - v[i - 2];
            num += d * previous;
            den += previous * previous;
            lo_ratio = std::min(lo_ratio, d / previous);
            hi_ratio = std::max(hi_ratio, d / previous);
        }
    }
    drift.monotone = true;
    drift.ratio = num / den;
    const double last = v[v.size() - 1] - v[v.size() - 2];
    const double horizon = static_cast<double>(horizon_periods);
    const double factor = drift.ratio < 1.0 ? drift.ratio / (1.0 - drift.ratio) : horizon;
    // Three values always fit one ratio; a decay is only believed when two ratios agree.
    drift.decaying = v.size() >= 4 && drift.ratio < 1.0 && factor <= horizon &&
                     hi_ratio <= kRatioSpread * lo_ratio;
    drift.remaining = last * std::min(factor, horizon);
    return drift;
}

bool phasors_within(std::span<const std::complex<double>> phasors, std::size_t count,
                    double tolerance) {
    if (phasors.size() < count || count == 0) return false;
    const auto w = phasors.subspan(phasors.size() - count, count);
    double largest = 0.0;
    double spread = 0.0;
    for (std::size_t i = 0; i < w.size(); ++i) {
        largest = std::max(largest, std::abs(w[i]));
        for (std::size_t j = i + 1; j < w.size(); ++j)
            spread = std::max(spread, std::abs(w[i] - w[j]));
    }
    return spread <= tolerance * largest;
}

namespace {

/// assess_steady on the newest window `w` of `values`, whose drift is already assessed.
std::optional<WindowVerdict> steady_verdict(std::span<const double> values,
                                            std::span<const double> w, const Drift& drift,
                                            const ControllerOptions& options,
                                            std::span<const std::complex<double>> fundamentals) {
    const auto n = static_cast<std::size_t>(options.window_periods);
    const double tol = options.tolerance;
    const std::size_t m = w.size();

    // Settled: the whole window within the tolerance (paper 000: "does not vary
    // significantly for a certain number of periods"), and not a transient still on its way:
    // a lightly damped mode approaches its steady state by a few percent per period, which
    // fits inside the spread long before it has arrived.
    const bool phase_steady = fundamentals.empty() || phasors_within(fundamentals, m, tol);
    if (m == n && within(w, 0, 1, tol) && phase_steady) {
        const double level = mean(w);
        if (!drift.monotone) {
            return WindowVerdict{WindowState::kSettled, level, static_cast<int>(m), level};
        }
        if (std::abs(drift.remaining) <= kSettledDriftShare * tol * level) {
            const double steady = drift.decaying ? w.back() + drift.remaining : level;
            return WindowVerdict{WindowState::kSettled, steady, static_cast<int>(m), level,
                                 drift.decaying};
        }
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
            return WindowVerdict{WindowState::kLimitCycle2, mean(c), static_cast<int>(l), mean(c)};
        }
    }
    return std::nullopt;
}

}  // namespace

std::optional<WindowVerdict> assess_steady(std::span<const double> values,
                                           const ControllerOptions& options,
                                           std::span<const std::complex<double>> fundamentals) {
    const std::size_t m = std::min(values.size(), static_cast<std::size_t>(options.window_periods));
    const auto w = values.subspan(values.size() - m, m);  // newest m values, oldest first
    return steady_verdict(values, w, assess_drift(w, horizon_values(options)), options,
                          fundamentals);
}

WindowVerdict assess_window(std::span<const double> values, double target_rms,
                            const ControllerOptions& options,
                            std::span<const std::complex<double>> fundamentals) {
    const auto n = static_cast<std::size_t>(options.window_periods);
    const double tol = options.tolerance;
    const std::size_t m = std::min(values.size(), n);
    const auto w = values.subspan(values.size() - m, m);  // newest m values, oldest first
    const Drift drift = assess_drift(w, horizon_values(options));
    if (auto steady = steady_verdict(values, w, drift, options, fundamentals)) return *steady;

    if (m >= static_cast<std::size_t>(options.early_periods)) {
        // Early decision: every value beyond the target by more than the tolerance, unless
        // the window is still drifting toward the target (then it may yet get there). The
        // level acted on is the value nearest the target, so the update cannot overshoot.
        // A drift that is the geometric decay of a transient tells where it is going: if
        // that too is beyond the target, decide on it (a 0.5 %-damped mode would otherwise
        // hold every decision for a hundred periods).
        const bool low =
            std::all_of(w.begin(), w.end(), [&](double v) { return (1.0 + tol) * v < target_rms; });
        const bool high =
            std::all_of(w.begin(), w.end(), [&](double v) { return (1.0 - tol) * v > target_rms; });
        const double heading = w.back() + drift.remaining;
        const int count = static_cast<int>(m);
        if (low) {
            if (!drifts(w, true)) {
                return {WindowState::kEarlyLow, *std::max_element(w.begin(), w.end()), count,
                        mean(w)};
            }
            if (drift.decaying && (1.0 + tol) * heading < target_rms) {
                return {WindowState::kEarlyLow, heading, count, mean(w), true};
            }
        }
        if (high) {
            if (!drifts(w, false)) {
                return {WindowState::kEarlyHigh, *std::min_element(w.begin(), w.end()), count,
                        mean(w)};
            }
            if (drift.decaying && (1.0 - tol) * heading > target_rms) {
                return {WindowState::kEarlyHigh, heading, count, mean(w), true};
            }
        }
    }
    return {m == n ? WindowState::kUnsettled : WindowState::kFilling, 0.0, 0, 0.0};
}

}  // namespace sb::control

// Checks of the controller options.
#include "control/options.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace sb::control {
namespace {

void require_at_least(Violations& out, const char* key, int value, int lo, const char* meaning) {
    if (value < lo) {
        out.push_back({key, std::to_string(value), "must be >= " + std::to_string(lo), meaning});
    }
}

}  // namespace

Violations ControllerOptions::validate() const {
    Violations out;
    require_in_range(out, "tolerance", tolerance, 1e-6, 0.5,
                     "relative tolerance on the per-period RMS [-]");
    require_at_least(out, "window_periods", window_periods, 3,
                     "periods that must agree to call the response settled");
    if (early_periods < 3 || early_periods > window_periods) {
        out.push_back({"early_periods", std::to_string(early_periods),
                       "must be in [3, window_periods = " + std::to_string(window_periods) + "]",
                       "fewest values for an early too-low/too-high decision"});
    }
    require_at_least(out, "average_periods", average_periods, 1,
                     "periods averaged into each value the window judges");
    require_at_least(out, "transient_periods", transient_periods, 0,
                     "periods skipped after an amplitude or frequency change");
    if (limit_cycle_periods < 4 || limit_cycle_periods % 2 != 0) {
        out.push_back({"limit_cycle_periods", std::to_string(limit_cycle_periods),
                       "must be even and >= 4", "periods that must alternate for a 2-cycle"});
    }
    // In 64 bits: a config may give any two ints.
    const long long needed =
        static_cast<long long>(std::max(transient_periods, 0)) +
        static_cast<long long>(std::max(average_periods, 1)) *
            static_cast<long long>(std::max(window_periods, limit_cycle_periods));
    if (max_periods < needed) {
        out.push_back({"max_periods", std::to_string(max_periods),
                       "must be >= transient_periods + average_periods * max(window_periods, "
                       "limit_cycle_periods) = " +
                           std::to_string(needed),
                       "budget of periods per point"});
    }
    require_at_least(out, "closest_rerun_periods", closest_rerun_periods, 1,
                     "periods re-run at the closest amplitude after a failure");
    require_non_negative(out, "min_amplitude", min_amplitude, "lower amplitude bound");
    if (!(max_amplitude > min_amplitude) || std::isnan(max_amplitude)) {
        out.push_back({"max_amplitude", format_value(max_amplitude),
                       "must be > min_amplitude = " + format_value(min_amplitude),
                       "upper amplitude bound"});
    }
    if (initial_amplitude) {
        const double a = *initial_amplitude;
        require_positive(out, "initial_amplitude", a, "amplitude of the first point");
        if (std::isfinite(a) && a > 0.0 && (a < min_amplitude || a > max_amplitude)) {
            out.push_back({"initial_amplitude", format_value(a),
                           "must be in [min_amplitude, max_amplitude] = [" +
                               format_value(min_amplitude) + ", " + format_value(max_amplitude) +
                               "]",
                           "amplitude of the first point"});
        }
    }
    if (!(std::isfinite(max_step_factor) && max_step_factor > 1.0)) {
        out.push_back({"max_step_factor", format_value(max_step_factor), "must be > 1",
                       "largest amplitude factor per update [-]"});
    }
    require_non_negative(out, "overshoot", overshoot, "widening of the bracket levels [-]");
    if (std::isfinite(overshoot) && std::isfinite(tolerance) && overshoot * tolerance >= 0.5) {
        out.push_back({"overshoot", format_value(overshoot), "overshoot * tolerance must be < 0.5",
                       "widening of the bracket levels [-]"});
    }
    if (!(std::isfinite(limit_cycle_jump) && limit_cycle_jump >= 1.0)) {
        out.push_back({"limit_cycle_jump", format_value(limit_cycle_jump), "must be >= 1",
                       "alternation of a two-period cycle, in tolerances [-]"});
    }
    require_at_least(out, "max_restarts", max_restarts, 0,
                     "bracket restarts before the ratio rule alone is used");
    require_at_least(out, "drift_horizon_periods", drift_horizon_periods, 0,
                     "periods a drift in the window is extrapolated over");
    return out;
}

}  // namespace sb::control

// The fixed-drive point: periods at one amplitude until the response is steady.
#include "control/fixed_drive.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "control/block_average.hpp"
#include "control/point_recorder.hpp"
#include "control/window.hpp"

namespace sb::control {

PointResult run_fixed_point(Plant& plant, double frequency_hz, double amplitude,
                            const ControllerOptions& options) {
    throw_if_invalid(options);
    if (!(std::isfinite(frequency_hz) && frequency_hz > 0.0)) {
        throw std::invalid_argument("run_fixed_point: frequency_hz must be > 0, got " +
                                    format_value(frequency_hz));
    }
    if (!(std::isfinite(amplitude) && amplitude > 0.0)) {
        throw std::invalid_argument("run_fixed_point: amplitude must be > 0, got " +
                                    format_value(amplitude));
    }
    PointResult result;
    PointRecorder recorder(plant, frequency_hz, 0.0, result);
    result.amplitude_final = amplitude;
    WindowValues window(options.average_periods);  // after the transient
    while (result.periods_simulated < options.max_periods) {
        const double rms = recorder.run(amplitude);
        if (result.periods_simulated <= options.transient_periods) continue;
        const auto& harmonics = result.periods.back().harmonics;
        const bool phase = options.phase_test && !harmonics.empty();
        if (!window.add(rms, phase ? &harmonics.front() : nullptr)) continue;
        const auto verdict = assess_steady(window.values(), options, window.phasors());
        if (!verdict) continue;
        Decision decision;
        decision.period = result.periods_simulated - 1;
        decision.amplitude = amplitude;
        decision.level = verdict->level;
        decision.kind = verdict->state == WindowState::kSettled ? DecisionKind::kSettled
                                                                : DecisionKind::kLimitCycle2;
        decision.next_amplitude = amplitude;
        result.decisions.push_back(decision);
        result.status = verdict->state == WindowState::kSettled ? PointStatus::kConverged
                                                                : PointStatus::kLimitCycle2;
        result.rms_final = verdict->mean;
        result.window_end = result.periods_simulated;
        result.window_begin = result.window_end - verdict->count * options.average_periods;
        return result;
    }
    // Never steady: the long mean is the estimate (a chaotic response scatters about it).
    const int after_transient =
        std::max(result.periods_simulated - std::max(options.transient_periods, 0), 0);
    const int recorded =
        std::min(after_transient,
                 std::max(options.window_periods * options.average_periods, after_transient / 2));
    result.status = PointStatus::kUnsettled;
    result.window_end = result.periods_simulated;
    result.window_begin = result.window_end - std::max(recorded, 1);
    double sum = 0.0;
    for (int p = result.window_begin; p < result.window_end; ++p) {
        sum += result.rms_per_period[static_cast<std::size_t>(p)];
    }
    result.rms_final = sum / static_cast<double>(result.window_end - result.window_begin);
    return result;
}

}  // namespace sb::control

// The RMS amplitude controller loop: settle, decide, update, fall back (paper 000 §3.2).
#include "control/controller.hpp"

#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "control/block_average.hpp"
#include "control/point_recorder.hpp"
#include "control/update.hpp"
#include "control/window.hpp"

namespace sb::control {
namespace {

bool closer(const std::optional<Sample>& best, const Sample& s, double target) {
    return !best || std::abs(s.level - target) < std::abs(best->level - target);
}

}  // namespace

std::string_view to_string(PointStatus status) {
    switch (status) {
        case PointStatus::kConverged:
            return "converged";
        case PointStatus::kLimitCycle2:
            return "limit-cycle-2";
        case PointStatus::kClosest:
            return "closest";
        case PointStatus::kUnsettled:
            return "unsettled";
    }
    return "unknown";
}

std::string_view to_string(DecisionKind kind) {
    switch (kind) {
        case DecisionKind::kSettled:
            return "settled";
        case DecisionKind::kLimitCycle2:
            return "limit-cycle-2";
        case DecisionKind::kEarlyLow:
            return "early-low";
        case DecisionKind::kEarlyHigh:
            return "early-high";
    }
    return "unknown";
}

std::string_view to_string(UpdateRule rule) {
    switch (rule) {
        case UpdateRule::kNone:
            return "none";
        case UpdateRule::kRatio:
            return "ratio";
        case UpdateRule::kSecant:
            return "secant";
        case UpdateRule::kGradient:
            return "gradient";
    }
    return "unknown";
}

std::vector<std::complex<double>> PointResult::window_harmonics() const {
    std::vector<std::complex<double>> sum;
    if (window_end <= window_begin) return sum;
    for (int i = window_begin; i < window_end; ++i) {
        const auto& h = periods[static_cast<std::size_t>(i)].harmonics;
        if (sum.size() < h.size()) sum.resize(h.size());
        for (std::size_t k = 0; k < h.size(); ++k) sum[k] += h[k];
    }
    const double count = static_cast<double>(window_end - window_begin);
    for (auto& value : sum) value /= count;
    return sum;
}

AmplitudeController::AmplitudeController(const ControllerOptions& options) : options_(options) {
    throw_if_invalid(options_);
}

double AmplitudeController::start_amplitude(double target_rms) const {
    if (forced_start_ > 0.0) return forced_start_;
    if (previous_amplitude_ <= 0.0) {
        if (!options_.initial_amplitude) {
            throw std::logic_error(
                "AmplitudeController: no start amplitude: give initial_amplitude or call "
                "set_start_amplitude() before the first point of a sweep");
        }
        return *options_.initial_amplitude;
    }
    // Warm start: the previous amplitude scaled by the ratio the previous point would still
    // have needed to reach this target.
    return warm_start_amplitude(previous_amplitude_, previous_rms_, target_rms, options_);
}

void AmplitudeController::set_start_amplitude(double amplitude) {
    if (!(std::isfinite(amplitude) && amplitude > 0.0)) {
        throw std::invalid_argument("set_start_amplitude: amplitude must be > 0, got " +
                                    format_value(amplitude));
    }
    forced_start_ = amplitude;
}

void AmplitudeController::reset() {
    previous_amplitude_ = 0.0;
    previous_rms_ = 0.0;
    forced_start_ = 0.0;
}

PointResult AmplitudeController::run_point(Plant& plant, double frequency_hz, double target_rms) {
    if (!(std::isfinite(frequency_hz) && frequency_hz > 0.0)) {
        throw std::invalid_argument("run_point: frequency_hz must be > 0, got " +
                                    format_value(frequency_hz));
    }
    if (!(std::isfinite(target_rms) && target_rms > 0.0)) {
        throw std::invalid_argument("run_point: target_rms must be > 0, got " +
                                    format_value(target_rms));
    }
    const ControllerOptions& o = options_;
    PointResult result;
    PointRecorder recorder(plant, frequency_hz, target_rms, result);

    double amplitude = start_amplitude(target_rms);
    forced_start_ = 0.0;
    // Since the last change, transient skipped; cleared at every change so no stale or
    // unfilled value votes.
    WindowValues window(o.average_periods);
    int since_change = 0;  // periods at this amplitude (this frequency)
    Bracket bracket;
    std::optional<Sample> best;           // amplitude whose level came closest to the target
    std::optional<Sample> last_measured;  // previous settled or two-period level
    UpdateRule last_rule = UpdateRule::kNone;
    bool accepted = false;

    while (result.periods_simulated < o.max_periods) {
        const double rms = recorder.run(amplitude);
        if (++since_change <= o.transient_periods) continue;
        const auto& harmonics = result.periods.back().harmonics;
        const bool phase = o.phase_test && !harmonics.empty();
        if (!window.add(rms, phase ? &harmonics.front() : nullptr)) continue;

        const WindowVerdict verdict =
            assess_window(window.values(), target_rms, o, window.phasors());
        if (verdict.state == WindowState::kFilling) continue;
        if (verdict.state == WindowState::kUnsettled) {
            // Neither settled nor clearly off: its mean still ranks the amplitude for the
            // closest fallback (a chaotic response never settles).
            const std::size_t n = static_cast<std::size_t>(o.window_periods);
            const auto& values = window.values();
            double sum = 0.0;
            for (std::size_t i = values.size() - n; i < values.size(); ++i) sum += values[i];
            const Sample s{amplitude, sum / static_cast<double>(n)};
            if (closer(best, s, target_rms)) best = s;
            continue;
        }

        Decision decision;
        decision.period = result.periods_simulated - 1;
        decision.amplitude = amplitude;
        decision.level = verdict.level;
        switch (verdict.state) {
            case WindowState::kSettled:
                decision.kind = DecisionKind::kSettled;
                break;
            case WindowState::kLimitCycle2:
                decision.kind = DecisionKind::kLimitCycle2;
                break;
            case WindowState::kEarlyLow:
                decision.kind = DecisionKind::kEarlyLow;
                break;
            default:
                decision.kind = DecisionKind::kEarlyHigh;
                break;
        }
        const Sample sample{amplitude, verdict.level};
        if (closer(best, sample, target_rms)) best = sample;

        const bool measured =
            decision.kind == DecisionKind::kSettled || decision.kind == DecisionKind::kLimitCycle2;
        // Both the window's mean (what is recorded) and the steady value it approaches (what
        // the structure does at this amplitude) must be on target.
        const double band = o.tolerance * target_rms;
        if (measured && std::abs(verdict.level - target_rms) <= band &&
            std::abs(verdict.mean - target_rms) <= band) {
            // Accepted, with or without an update at this point (a warm start already on
            // target costs no extra settling cycle).
            decision.rule = UpdateRule::kNone;
            decision.next_amplitude = amplitude;
            result.decisions.push_back(decision);
            result.status = decision.kind == DecisionKind::kSettled ? PointStatus::kConverged
                                                                    : PointStatus::kLimitCycle2;
            result.amplitude_final = amplitude;
            result.rms_final = verdict.mean;
            result.window_end = result.periods_simulated;
            result.window_begin = result.window_end - verdict.count * o.average_periods;
            accepted = true;
            break;
        }

        // Update: the secant through the widened bracket while the bracket holds, the ratio
        // rule otherwise; a stalled secant (a sample improving neither side) restarts the
        // bracket, and after max_restarts of those only the ratio rule is used.
        if (!bracket.add(sample, target_rms)) ++result.restarts;
        std::optional<double> proposed;
        decision.rule = UpdateRule::kRatio;
        if (result.restarts <= o.max_restarts) {
            proposed = bracket.secant(target_rms, o);
            if (proposed) decision.rule = UpdateRule::kSecant;
        }
        // The ratio rule stalls when the gain changes with the drive (a hardening response
        // grows less than the drive): two measured levels on the same side, the newer one not
        // even halfway closer (in log) than the older. Then follow the measured gradient.
        // A level extrapolated from a geometric decay estimates the steady state as well as
        // a settled one does, and serves the gradient alike.
        const bool steady_estimate = measured || verdict.extrapolated;
        if (!proposed && steady_estimate && last_measured && last_rule == UpdateRule::kRatio &&
            (last_measured->level < target_rms) == (sample.level < target_rms) &&
            std::abs(std::log(target_rms / sample.level)) >
                0.5 * std::abs(std::log(target_rms / last_measured->level))) {
            proposed = power_law_amplitude(*last_measured, sample, target_rms, o);
            if (proposed) decision.rule = UpdateRule::kGradient;
        }
        if (!proposed) proposed = ratio_amplitude(amplitude, verdict.level, target_rms);
        if (steady_estimate) last_measured = sample;
        last_rule = decision.rule;
        decision.next_amplitude = limit_step(amplitude, *proposed, o);
        result.decisions.push_back(decision);
        ++result.updates;

        amplitude = decision.next_amplitude;
        window.clear();
        since_change = 0;
    }

    if (!accepted) {
        // Budget spent: re-run the amplitude closest to the target and record those periods,
        // not the last ones (HFelem printed the last period beside the best amplitude).
        const double closest = best ? best->amplitude : amplitude;
        if (closest != amplitude) {
            for (int i = 0; i < o.transient_periods; ++i) recorder.run(closest);
        }
        result.window_begin = result.periods_simulated;
        const int rerun = o.closest_rerun_periods * o.average_periods;
        double sum = 0.0;
        for (int i = 0; i < rerun; ++i) sum += recorder.run(closest);
        result.window_end = result.periods_simulated;
        result.status = PointStatus::kClosest;
        result.amplitude_final = closest;
        result.rms_final = sum / static_cast<double>(rerun);
    }

    previous_amplitude_ = result.amplitude_final;
    previous_rms_ = result.rms_final;
    return result;
}

}  // namespace sb::control

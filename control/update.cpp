// Amplitude update rules of paper 000, section 3.2 (ratio and "loosened gradient").
#include "control/update.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sb::control {

bool Bracket::add(const Sample& sample, double target_rms) {
    if (sample.level < target_rms && (!lower_ || sample.level >= lower_->level)) {
        lower_ = sample;
        return true;
    }
    if (sample.level > target_rms && (!upper_ || sample.level <= upper_->level)) {
        upper_ = sample;
        return true;
    }
    // No improvement on its own side: the plant contradicts the bracket. Start afresh.
    clear();
    (sample.level < target_rms ? lower_ : upper_) = sample;
    return false;
}

void Bracket::clear() {
    lower_.reset();
    upper_.reset();
}

std::optional<double> Bracket::secant(double target_rms, const ControllerOptions& options) const {
    if (!lower_ || !upper_) return std::nullopt;
    const Sample& lo = *lower_;
    const Sample& hi = *upper_;
    const double tol = options.tolerance;
    const double widen = options.overshoot * tol;
    // Points the tolerance cannot tell apart give no usable slope (HFelem: RMS gap below
    // 2 o tol, amplitude gap below tol^2).
    if (hi.level - lo.level < 2.0 * widen * hi.level) return std::nullopt;
    if (std::abs(hi.amplitude - lo.amplitude) < tol * tol * std::max(hi.amplitude, lo.amplitude)) {
        return std::nullopt;
    }
    // A response that falls as the drive rises (a jump, hysteresis) has no secant to follow.
    if (!(hi.amplitude > lo.amplitude)) return std::nullopt;
    // Paper 000 §3.2 "loosened gradient": the stored levels are widened outward by o tol
    // (HFelem `overshoot`), so the slope is steeper and the new amplitude is pulled toward
    // the middle of the bracket, robust to scatter of the order of the tolerance.
    const double lo_level = (1.0 - widen) * lo.level;
    const double hi_level = (1.0 + widen) * hi.level;
    return lo.amplitude +
           (target_rms - lo_level) * (hi.amplitude - lo.amplitude) / (hi_level - lo_level);
}

std::optional<double> power_law_amplitude(const Sample& older, const Sample& newer,
                                          double target_rms, const ControllerOptions& options) {
    if (!(older.level > 0.0 && newer.level > 0.0)) return std::nullopt;
    const double dlog_level = std::log(newer.level / older.level);
    const double dlog_amplitude = std::log(newer.amplitude / older.amplitude);
    // Levels the tolerance cannot separate give no usable gradient.
    if (std::abs(dlog_level) < 2.0 * options.overshoot * options.tolerance) return std::nullopt;
    if (std::abs(dlog_amplitude) < options.tolerance * options.tolerance) return std::nullopt;
    const double p = dlog_level / dlog_amplitude;  // local exponent of level ~ amplitude^p
    if (!(p > 0.0)) return std::nullopt;
    const double exponent = std::clamp(p, kMinPowerLawExponent, kMaxPowerLawExponent);
    return newer.amplitude * std::pow(target_rms / newer.level, 1.0 / exponent);
}

double ratio_amplitude(double amplitude, double level, double target_rms) {
    // Paper 000 §3.2: previous amplitude times target / converged RMS.
    if (!(level > 0.0)) return std::numeric_limits<double>::infinity();
    return amplitude * target_rms / level;
}

double limit_step(double current, double proposed, const ControllerOptions& options) {
    if (std::isnan(proposed)) return current;
    const double down = current / options.max_step_factor;
    const double up = current * options.max_step_factor;
    const double stepped = proposed <= 0.0 ? down : std::clamp(proposed, down, up);
    const double bounded = std::clamp(stepped, options.min_amplitude, options.max_amplitude);
    // The amplitude stays > 0 even with min_amplitude = 0.
    return bounded > 0.0 ? bounded : down;
}

double warm_start_amplitude(double amplitude, double level, double target_rms,
                            const ControllerOptions& options) {
    return limit_step(amplitude, ratio_amplitude(amplitude, level, target_rms), options);
}

}  // namespace sb::control

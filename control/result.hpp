// What the amplitude controller records for one stepped-sine point.
#pragma once

#include <complex>
#include <string_view>
#include <vector>

#include "control/plant.hpp"

namespace sb::control {

/// How a point ended (formats.md `status`).
enum class PointStatus {
    kConverged,    ///< a single settled level within tolerance of the target
    kLimitCycle2,  ///< a two-period limit cycle whose two-period mean is within tolerance
    kClosest,      ///< budget spent; the amplitude closest to the target was re-run
    kUnsettled,    ///< fixed drive: budget spent before the response was steady
};

/// "converged", "limit-cycle-2", "closest" or "unsettled".
std::string_view to_string(PointStatus status);

/// What a window of per-period RMS values was judged to be when the controller acted on it.
enum class DecisionKind {
    kSettled,      ///< n values within tolerance; level = their mean
    kLimitCycle2,  ///< values alternate period to period; level = two-period mean
    kEarlyLow,     ///< every value too low beyond doubt; level = the highest of them
    kEarlyHigh,    ///< every value too high beyond doubt; level = the lowest of them
};

/// "settled", "limit-cycle-2", "early-low" or "early-high".
std::string_view to_string(DecisionKind kind);

/// How the next amplitude was computed.
enum class UpdateRule {
    kNone,      ///< no update: the level was accepted
    kRatio,     ///< amplitude * target / level
    kSecant,    ///< secant through the widened bracket (the "loosened gradient")
    kGradient,  ///< power-law gradient through two same-side levels, when the ratio stalls
};

/// "none", "ratio", "secant" or "gradient".
std::string_view to_string(UpdateRule rule);

/// One decision of the controller on a window of periods.
struct Decision {
    int period = 0;          ///< index in rms_per_period of the newest period used
    double amplitude = 0.0;  ///< amplitude the window was driven at [input unit]
    double level = 0.0;      ///< level acted on [channel unit]
    DecisionKind kind = DecisionKind::kSettled;
    UpdateRule rule = UpdateRule::kNone;
    double next_amplitude = 0.0;  ///< amplitude driven next (== amplitude when accepted)
};

/// Everything recorded about one controlled stepped-sine point.
struct PointResult {
    double frequency_hz = 0.0;     ///< excitation frequency [Hz]
    double target_rms = 0.0;       ///< target RMS of the control channel [channel unit]
    double amplitude_final = 0.0;  ///< amplitude of the recorded window [input unit]
    /// Mean RMS over the recorded window (the two-period mean for a limit cycle; the mean of
    /// the re-run periods for `closest`) [channel unit].
    double rms_final = 0.0;
    PointStatus status = PointStatus::kClosest;
    /// The amplitude of each stretch of periods driven at one amplitude, in order.
    std::vector<double> amplitudes_tried{};
    /// Every period simulated, in order: the amplitude driven and what the plant reported.
    std::vector<double> amplitude_per_period{};
    std::vector<double> rms_per_period{};
    std::vector<PeriodResult> periods{};
    int periods_simulated = 0;  ///< == rms_per_period.size()
    int updates = 0;            ///< amplitude updates made
    int restarts = 0;           ///< bracket restarts (secant stalls)
    /// Recorded window [window_begin, window_end) as indices into rms_per_period.
    int window_begin = 0;
    int window_end = 0;
    std::vector<Decision> decisions{};

    /// Mean of the plant's harmonics over the recorded window, index as in PeriodResult. For
    /// a two-period cycle this is the component at the excitation frequency over 2T.
    [[nodiscard]] std::vector<std::complex<double>> window_harmonics() const;
};

}  // namespace sb::control

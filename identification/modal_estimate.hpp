// The result of one modal estimator: natural frequency and damping, or a status saying why not.
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace sb::identification {

/// Why an estimator did or did not return numbers. std::expected is not available in g++ 12,
/// so every estimator returns a ModalEstimate carrying one of these and a message.
enum class EstimateStatus {
    ok,                      ///< numbers are valid
    too_few_points,          ///< fewer points near the peak than the method needs
    peak_at_grid_edge,       ///< the largest |FRF| is the first or last grid point
    no_lower_crossing,       ///< no point below the half-power level under the peak
    no_upper_crossing,       ///< no point below the half-power level above the peak
    too_few_points_in_band,  ///< fewer than 2 grid points inside the half-power band
    fit_failed,              ///< the fit gave no physical answer (negative, complex, outside)
    residual_dominates,      ///< other modes' residual exceeds the mode's own response at f_n
};

/// Which estimator produced a result.
enum class Method { half_power, circle_fit, rational_fraction };

/// Natural frequency and damping of one mode by one method.
struct ModalEstimate {
    EstimateStatus status = EstimateStatus::fit_failed;
    std::string message;  ///< empty when ok; otherwise why, in words, with the numbers
    double natural_frequency_hz = std::numeric_limits<double>::quiet_NaN();  ///< f_n [Hz]
    double damping_ratio = std::numeric_limits<double>::quiet_NaN();         ///< viscous ζ [-]
    /// Standard deviation of the per-pair damping ratios (circle fit) [-]; 0 for other methods.
    double damping_spread = 0.0;
    int points_used = 0;  ///< grid points entering the estimate [-]
    /// Frequencies of those grid points, ascending [Hz] (points_used of them): which points an
    /// estimate rests on, so that a reader can see whether a doubtful point took part. The
    /// residual fit of residual.hpp, when on, rests on a wider run (ResidualFit::points_used).
    std::vector<double> frequencies_used_hz{};
    /// Residual of the other modes at f_n over this mode's response there [-], as fitted and
    /// subtracted before the estimate (residual.hpp); 0 when no residual was subtracted.
    double residual_ratio = 0.0;

    bool ok() const noexcept { return status == EstimateStatus::ok; }
    /// Loss factor η = 2ζ [-] (equivalent at resonance, Ewins).
    double loss_factor() const noexcept { return 2.0 * damping_ratio; }
};

/// A failed estimate with status and message.
ModalEstimate failed_estimate(EstimateStatus status, std::string message);

/// Lower-case name of a status as printed and documented (e.g. "no-lower-crossing").
std::string_view to_string(EstimateStatus status);
/// Name of a method as written in damping.csv ("half-power", "circle-fit", "rational-fraction").
std::string_view to_string(Method method);

}  // namespace sb::identification

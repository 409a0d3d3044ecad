// Names of estimator statuses and methods.
#include "identification/modal_estimate.hpp"

#include <utility>

namespace sb::identification {

ModalEstimate failed_estimate(EstimateStatus status, std::string message) {
    ModalEstimate e;
    e.status = status;
    e.message = std::move(message);
    return e;
}

std::string_view to_string(EstimateStatus status) {
    switch (status) {
        case EstimateStatus::ok:
            return "ok";
        case EstimateStatus::too_few_points:
            return "too-few-points";
        case EstimateStatus::peak_at_grid_edge:
            return "peak-at-grid-edge";
        case EstimateStatus::no_lower_crossing:
            return "no-lower-crossing";
        case EstimateStatus::no_upper_crossing:
            return "no-upper-crossing";
        case EstimateStatus::too_few_points_in_band:
            return "too-few-points-in-band";
        case EstimateStatus::fit_failed:
            return "fit-failed";
        case EstimateStatus::residual_dominates:
            return "residual-dominates";
    }
    return "unknown";
}

std::string_view to_string(Method method) {
    switch (method) {
        case Method::half_power:
            return "half-power";
        case Method::circle_fit:
            return "circle-fit";
        case Method::rational_fraction:
            return "rational-fraction";
    }
    return "unknown";
}

}  // namespace sb::identification

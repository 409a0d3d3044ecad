// What the linear structure alone says about the response: amplitude guesses for the
// controller's first point and the expected ratio for warm starts.
#pragma once

#include <string>

#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// Peak acceleration [m/s^2] along the excitation direction at `point` per unit excitation
/// amplitude (1 N, or 1 m/s^2 of base acceleration) at frequency_hz, in the linear steady
/// state of the reduced modal model.
double linear_response_per_unit_input(const structure::LinearModel& model,
                                      const structure::ModalBasis& basis,
                                      const structure::ExcitationSpec& excitation,
                                      const std::string& point, double frequency_hz);

}  // namespace sb::bench

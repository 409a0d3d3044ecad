// Linear response estimates from the reduced modal model's steady state.
#include "bench/linear_estimate.hpp"

#include <cmath>

#include "structure/reduced_modal_model.hpp"

namespace sb::bench {

double linear_response_per_unit_input(const structure::LinearModel& model,
                                      const structure::ModalBasis& basis,
                                      const structure::ExcitationSpec& excitation,
                                      const std::string& point, double frequency_hz) {
    // a(t) = Re{X e^{iwt}}: a(0) = Re X and a(T/4) = -Im X, so two steady states give |X|.
    const Eigen::Vector3d direction = excitation.direction.normalized();
    const double period_s = 1.0 / frequency_hz;
    structure::ReducedModalModel reduced(model, basis, period_s / 64.0);
    const int p = reduced.point_index(point);
    double components[2] = {0.0, 0.0};
    const double times[2] = {0.0, 0.25 * period_s};
    for (int k = 0; k < 2; ++k) {
        if (excitation.kind == structure::ExcitationSpec::Kind::force) {
            reduced.set_harmonic_steady_state(excitation.point, direction, 1.0, frequency_hz,
                                              times[k]);
        } else {
            reduced.set_harmonic_base_steady_state(1.0, frequency_hz, times[k]);
        }
        components[k] = reduced.acceleration(p).dot(direction);
    }
    return std::hypot(components[0], components[1]);
}

}  // namespace sb::bench

// Analytic modal frequency response functions between named points.
#include "structure/frf.hpp"

#include <algorithm>

#include "core/units.hpp"

namespace sb::structure {

std::complex<double> modal_accelerance(const LinearModel& model, const ModalBasis& basis,
                                       std::string_view out_point,
                                       const Eigen::Vector3d& out_direction,
                                       std::string_view in_point,
                                       const Eigen::Vector3d& in_direction, double frequency_hz,
                                       int modes) {
    using namespace std::complex_literals;
    const int available = static_cast<int>(basis.modes.size());
    const int kept = modes < 0 ? available : std::min(modes, available);
    const Eigen::VectorXd out = (out_direction.normalized().transpose() *
                                 point_shapes(model, basis, out_point).topRows<3>())
                                    .transpose();
    const Eigen::VectorXd in =
        (in_direction.normalized().transpose() * point_shapes(model, basis, in_point).topRows<3>())
            .transpose();
    const double w = kTwoPi * frequency_hz;
    std::complex<double> h = 0.0;
    for (int r = 0; r < kept; ++r) {
        const Mode& mode = basis.modes[static_cast<std::size_t>(r)];
        const double wr = kTwoPi * mode.frequency_hz;
        h += out(r) * in(r) * (-w * w) / (wr * wr - w * w + 2i * mode.damping_ratio * wr * w);
    }
    return h;
}

}  // namespace sb::structure

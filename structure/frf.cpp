// Analytic modal frequency response functions between named points.
#include "structure/frf.hpp"

#include <algorithm>
#include <stdexcept>

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

std::complex<double> modal_base_transmissibility(const LinearModel& model, const ModalBasis& basis,
                                                 std::string_view out_point,
                                                 const Eigen::Vector3d& out_direction,
                                                 double frequency_hz, int modes) {
    using namespace std::complex_literals;
    if (!model.base_influence()) {
        throw std::invalid_argument(
            "base transmissibility: the model is not driven through a base");
    }
    const int available = static_cast<int>(basis.modes.size());
    const int kept = modes < 0 ? available : std::min(modes, available);
    const Eigen::Vector3d d = out_direction.normalized();
    const Eigen::VectorXd out =
        (d.transpose() * point_shapes(model, basis, out_point).topRows<3>()).transpose();
    const Eigen::VectorXd participation =
        basis.shapes.leftCols(kept).transpose() * (model.mass() * *model.base_influence());
    const double w = kTwoPi * frequency_hz;
    std::complex<double> t = d.dot(model.point(out_point).base_motion.head<3>());
    for (int r = 0; r < kept; ++r) {
        const Mode& mode = basis.modes[static_cast<std::size_t>(r)];
        const double wr = kTwoPi * mode.frequency_hz;
        t += out(r) * participation(r) * w * w /
             (wr * wr - w * w + 2i * mode.damping_ratio * wr * w);
    }
    return t;
}

}  // namespace sb::structure

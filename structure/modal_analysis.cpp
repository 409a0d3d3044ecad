// Natural frequencies, mass-normalised mode shapes, modal damping and effective masses.
#include "structure/modal_analysis.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/units.hpp"
#include "structure/lowest_modes.hpp"

namespace sb::structure {
namespace {

/// Below this many DOFs the dense solver costs less than setting up Lanczos.
constexpr int kLanczosFromDofs = 60;

}  // namespace

ModalBasis compute_modes(const LinearModel& model, const DampingSpec& damping, int count) {
    const int n = model.dofs();
    if (count < 1) throw std::invalid_argument("compute_modes: count must be >= 1");
    const int kept = std::min(count, n);
    // K phi = lambda M phi, eigenvectors M-normalised. A model with many more DOFs than modes
    // kept (a meshed beam: 360 DOFs for 6 modes) by Lanczos on its sparse factors, the rest and
    // whatever Lanczos cannot vouch for by the dense solver (Eigen's Ax_lBx mode).
    auto pairs = 4 * kept <= n && n >= kLanczosFromDofs
                     ? lowest_eigenpairs(model.stiffness(), model.mass(), kept)
                     : std::nullopt;
    if (!pairs) {
        const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(model.stiffness(),
                                                                               model.mass());
        if (solver.info() != Eigen::Success) {
            throw std::runtime_error(
                "compute_modes: eigen solver failed (is M positive definite?)");
        }
        pairs = Eigenpairs{solver.eigenvalues().head(kept), solver.eigenvectors().leftCols(kept)};
    }
    ModalBasis basis;
    basis.shapes = std::move(pairs->vectors);
    basis.modes.resize(static_cast<std::size_t>(kept));
    const Eigen::MatrixXd& t = model.sample_translation();
    const Eigen::MatrixXd participation =
        basis.shapes.transpose() * model.mass() * model.rigid_translation();  // modes x 3
    for (int r = 0; r < kept; ++r) {
        Mode& mode = basis.modes[static_cast<std::size_t>(r)];
        const double omega = std::sqrt(std::max(0.0, pairs->values(r)));
        mode.frequency_hz = omega / kTwoPi;
        double u_max = 0.0;
        if (t.rows() > 0) {
            const Eigen::VectorXd u = t * basis.shapes.col(r);
            Eigen::Index at = 0;
            u_max = u.cwiseAbs().maxCoeff(&at);
            if (u(at) < 0.0) basis.shapes.col(r) *= -1.0;
        }
        mode.modal_mass_kg =
            u_max > 0.0 ? 1.0 / (u_max * u_max) : std::numeric_limits<double>::infinity();
        mode.effective_mass_kg =
            model.rigid_translation_known()
                ? Eigen::Vector3d(participation.row(r).transpose().cwiseAbs2())
                : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
        if (model.damping()) {
            const Eigen::VectorXd phi = basis.shapes.col(r);
            mode.damping_ratio =
                omega > 0.0 ? phi.dot(*model.damping() * phi) / (2.0 * omega) : 0.0;
        } else {
            mode.damping_ratio = omega > 0.0 ? damping.ratio(r + 1, omega) : 0.0;
        }
    }
    return basis;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> point_shapes(const LinearModel& model,
                                                      const ModalBasis& basis,
                                                      std::string_view point) {
    return model.point(point).op * basis.shapes;
}

Eigen::VectorXd circular_frequencies(const ModalBasis& basis) {
    Eigen::VectorXd w(static_cast<Eigen::Index>(basis.modes.size()));
    for (std::size_t r = 0; r < basis.modes.size(); ++r) {
        w(static_cast<Eigen::Index>(r)) = kTwoPi * basis.modes[r].frequency_hz;
    }
    return w;
}

Eigen::VectorXd damping_ratios(const ModalBasis& basis) {
    Eigen::VectorXd z(static_cast<Eigen::Index>(basis.modes.size()));
    for (std::size_t r = 0; r < basis.modes.size(); ++r) {
        z(static_cast<Eigen::Index>(r)) = basis.modes[r].damping_ratio;
    }
    return z;
}

}  // namespace sb::structure

// Shift-invert Lanczos (Spectra) on sparse LDL^T factors, with an inertia check.
#include "structure/lowest_modes.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace sb::structure {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Factors = Eigen::SimplicialLDLT<SparseMatrix>;

/// y = (K - sigma M)^{-1} x: the operator Spectra's shift-invert mode asks for (its own
/// SymShiftInvert factorises sparse matrices by LU; LDL^T is half the work for a symmetric
/// pencil).
class ShiftedSolve {
  public:
    using Scalar = double;
    ShiftedSolve(const SparseMatrix& stiffness, const SparseMatrix& mass)
        : stiffness_(stiffness), mass_(mass) {}
    [[nodiscard]] Eigen::Index rows() const { return stiffness_.rows(); }
    [[nodiscard]] Eigen::Index cols() const { return stiffness_.cols(); }
    void set_shift(double sigma) {
        factors_.compute(stiffness_ - sigma * mass_);
        if (factors_.info() != Eigen::Success) {
            throw std::runtime_error("lowest_eigenpairs: K - sigma M not factorised");
        }
    }
    void perform_op(const double* x_in, double* y_out) const {
        Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
        Eigen::Map<Eigen::VectorXd> y(y_out, rows());
        y.noalias() = factors_.solve(x);
    }

  private:
    const SparseMatrix& stiffness_;
    const SparseMatrix& mass_;
    Factors factors_;
};

/// Eigenvalues of (K, M) below tau: the negative pivots of LDL^T(K - tau M), a congruence of
/// it (Sylvester's law of inertia; the fill-reducing permutation is one too). -1 when the
/// factorisation fails or meets a zero pivot.
int eigenvalues_below(const SparseMatrix& stiffness, const SparseMatrix& mass, double tau) {
    const Factors factors(stiffness - tau * mass);
    if (factors.info() != Eigen::Success) return -1;
    const Eigen::VectorXd d = factors.vectorD();
    if ((d.array() == 0.0).any() || !d.allFinite()) return -1;
    return static_cast<int>((d.array() < 0.0).count());
}

}  // namespace

std::optional<Eigenpairs> lowest_eigenpairs(const Eigen::MatrixXd& stiffness,
                                            const Eigen::MatrixXd& mass, int count) {
    const auto n = stiffness.rows();
    if (count < 1 || count >= n) return std::nullopt;
    const SparseMatrix k = stiffness.sparseView();
    const SparseMatrix m = mass.sparseView();
    // A shift below the spectrum, small against its scale (the mean of K_ii / M_ii), so that
    // K - sigma M is positive definite even for a free structure (K singular) and the lowest
    // eigenvalues stay the best separated ones of the transformed problem.
    const double scale = stiffness.diagonal().sum() / mass.diagonal().sum();
    if (!(scale > 0.0) || !std::isfinite(scale)) return std::nullopt;
    const double sigma = -1e-6 * scale;
    const Eigen::Index ncv = std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * count + 1, 20));
    try {
        ShiftedSolve op(k, m);
        Spectra::SparseSymMatProd<double> mass_product(m);
        Spectra::SymGEigsShiftSolver<ShiftedSolve, Spectra::SparseSymMatProd<double>,
                                     Spectra::GEigsMode::ShiftInvert>
            solver(op, mass_product, count, ncv, sigma);
        solver.init();
        const Eigen::Index converged = solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12,
                                                      Spectra::SortRule::SmallestAlge);
        if (solver.info() != Spectra::CompInfo::Successful || converged != count) {
            return std::nullopt;
        }
        // Ascending (the sort rule SmallestAlge), M-normalised.
        Eigenpairs pairs{solver.eigenvalues(), solver.eigenvectors()};
        for (int r = 0; r < count; ++r) {
            const double norm2 = pairs.vectors.col(r).dot(m * pairs.vectors.col(r));
            if (!(norm2 > 0.0)) return std::nullopt;
            pairs.vectors.col(r) /= std::sqrt(norm2);
        }
        // Every eigenvalue up to the last one found, and no other: count of them below tau.
        const double last = pairs.values(count - 1);
        const double tau = last + 1e-7 * std::abs(last - sigma);
        if (eigenvalues_below(k, m, tau) != count) return std::nullopt;
        return pairs;
    } catch (const std::exception&) {
        return std::nullopt;  // the dense solver answers
    }
}

}  // namespace sb::structure

// The lowest eigenpairs of K phi = lambda M phi for a model much larger than the modes it
// keeps: shift-invert Lanczos on sparse factors, each answer checked by the inertia of K - tau M.
#pragma once

#include <Eigen/Core>
#include <optional>

namespace sb::structure {

struct Eigenpairs {
    Eigen::VectorXd values;   ///< lambda = omega^2, ascending
    Eigen::MatrixXd vectors;  ///< columns M-normalised (phi^T M phi = 1)
};

/// The `count` lowest eigenpairs of the symmetric pencil (K, M), M positive definite, by
/// Spectra's implicitly restarted Lanczos in shift-invert mode about a shift just below the
/// spectrum, with sparse LDL^T factors of K - sigma M (a beam's matrices are banded, so a
/// solve costs O(n) where the dense eigensolver costs O(n^3) for every mode). Lanczos can
/// miss one of two nearly equal eigenvalues; Sylvester's law of inertia counts the
/// eigenvalues below tau = just above the last one found as the negative pivots of
/// LDL^T(K - tau M): when that count is not `count`, or anything fails, the answer is none and
/// the caller takes the dense solver.
std::optional<Eigenpairs> lowest_eigenpairs(const Eigen::MatrixXd& stiffness,
                                            const Eigen::MatrixXd& mass, int count);

}  // namespace sb::structure

// The Lanczos path of the modal analysis against the dense generalised eigensolver, and its
// inertia check on the cases Lanczos handles badly (equal eigenvalues, a free structure).
#include "structure/lowest_modes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iostream>

#include "beam_fixtures.hpp"
#include "structure/beam_model.hpp"
#include "structure/linear_model.hpp"

namespace sb::structure {
namespace {

/// The dense solver's `count` lowest pairs, the reference.
Eigenpairs dense_pairs(const LinearModel& model, int count) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(model.stiffness(),
                                                                           model.mass());
    return {solver.eigenvalues().head(count), solver.eigenvectors().leftCols(count)};
}

/// ||K phi - lambda M phi|| / ||lambda M phi|| of the worst pair: how exact the pairs are.
double worst_residual(const LinearModel& model, const Eigenpairs& pairs) {
    double worst = 0.0;
    for (Eigen::Index r = 0; r < pairs.values.size(); ++r) {
        const Eigen::VectorXd m_phi = model.mass() * pairs.vectors.col(r);
        const Eigen::VectorXd residual =
            model.stiffness() * pairs.vectors.col(r) - pairs.values(r) * m_phi;
        worst = std::max(worst, residual.norm() / (std::abs(pairs.values(r)) * m_phi.norm()));
    }
    return worst;
}

/// Both answers hold the same modes: eigenvalues within `relative`, each Lanczos vector in
/// the span of the dense vectors, M-orthonormal, and at least as exact as the dense ones.
void expect_same_modes(const LinearModel& model, const Eigenpairs& fast, const Eigenpairs& dense,
                       double relative) {
    ASSERT_EQ(fast.values.size(), dense.values.size());
    for (Eigen::Index r = 0; r < fast.values.size(); ++r) {
        EXPECT_NEAR(fast.values(r), dense.values(r), relative * dense.values(r)) << r;
    }
    const Eigen::MatrixXd& m = model.mass();
    const auto count = fast.values.size();
    const Eigen::MatrixXd gram = fast.vectors.transpose() * m * fast.vectors;
    EXPECT_LT((gram - Eigen::MatrixXd::Identity(count, count)).norm(), 1e-9);
    // M-projections on the dense basis: each Lanczos vector lies in it (|coefficients| = 1).
    const Eigen::MatrixXd overlap = dense.vectors.transpose() * m * fast.vectors;
    for (Eigen::Index r = 0; r < count; ++r) {
        EXPECT_NEAR(overlap.col(r).norm(), 1.0, 1e-8) << r;
    }
    EXPECT_LE(worst_residual(model, fast), worst_residual(model, dense));
}

TEST(LowestModes, TheLoadedPaper000BeamsModesAreTheDenseSolversAndMoreExact) {
    // The dense solver's eigenvalues carry an absolute error of about eps times the largest
    // eigenvalue of the mesh (2e-5 here, 1e-8 of the first mode's); shift-invert Lanczos is
    // exact relative to each eigenvalue, so it is the dense one that is checked to 1e-7.
    const StructureSpec spec = testing::paper000_loaded();
    const LinearModel model = build_linear_model(spec, {});
    ASSERT_GE(model.dofs(), 200);
    const auto fast = lowest_eigenpairs(model.stiffness(), model.mass(), 8);
    ASSERT_TRUE(fast);
    expect_same_modes(model, *fast, dense_pairs(model, 8), 1e-7);
}

TEST(LowestModes, ASquareBeamsEqualBendingPairsAreBothFoundOrLeftToTheDenseSolver) {
    // A square section bends alike in y and z: every bending frequency is a pair. Lanczos from
    // one start vector can return one of a pair; the inertia count then says so and the answer
    // is none. Either way, no mode may be missing from an answer given.
    BeamSpec b = testing::paper000_bare_beam();
    b.width_m = b.thickness_m;
    const LinearModel model = build_beam_model(b, ExcitationSpec{});
    const Eigenpairs dense = dense_pairs(model, 6);
    ASSERT_NEAR(dense.values(1), dense.values(0), 1e-7 * dense.values(0));  // the pair
    const auto fast = lowest_eigenpairs(model.stiffness(), model.mass(), 6);
    if (fast) expect_same_modes(model, *fast, dense, 1e-7);
    std::cout << "square beam, six modes: "
              << (fast ? "Lanczos found both of each pair" : "left to the dense solver") << "\n";
    // Cut through a pair (one of the two asked for): never an answer.
    EXPECT_FALSE(lowest_eigenpairs(model.stiffness(), model.mass(), 1));
}

TEST(LowestModes, AFreeBeamsRigidBodyModesComeFirst) {
    // No support: six zero eigenvalues (K singular), then the free-free bending modes. The
    // shift below zero keeps K - sigma M definite.
    BeamSpec b = testing::paper000_bare_beam();
    b.supports.clear();
    const LinearModel model = build_beam_model(b, ExcitationSpec{});
    const Eigenpairs dense = dense_pairs(model, 8);
    const auto fast = lowest_eigenpairs(model.stiffness(), model.mass(), 8);
    if (!fast) GTEST_SKIP() << "left to the dense solver";
    const double bending = dense.values(6);
    for (int r = 0; r < 6; ++r) EXPECT_LT(std::abs(fast->values(r)), 1e-8 * bending) << r;
    for (int r = 6; r < 8; ++r) EXPECT_NEAR(fast->values(r), dense.values(r), 1e-7 * bending);
}

}  // namespace
}  // namespace sb::structure

// Element matrices, section properties, rigid lumped masses and the mesh.
#include "structure/beam_element.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "structure/beam_mesh.hpp"
#include "structure/rigid_mass.hpp"
#include "structure/section.hpp"

namespace sb::structure {
namespace {

// Round-off of sums of O(1e6..1e9) entries in double precision.
constexpr double kRelativeRoundOff = 1e-12;

BeamElementProperties aluminium(bool timoshenko) {
    BeamElementProperties p;
    p.section = rectangular_section(0.05, 0.003);
    p.density_kg_m3 = 2695.0;
    p.youngs_modulus_pa = 72e9;
    p.shear_modulus_pa = 27e9;
    p.timoshenko = timoshenko;
    return p;
}

/// Rigid motion of a two-node element: translation t and small rotation w about the origin.
Eigen::Matrix<double, 12, 1> rigid_motion(const Eigen::Vector3d& t, const Eigen::Vector3d& w,
                                          double length) {
    Eigen::Matrix<double, 12, 1> x;
    x << t, w, t + w.cross(Eigen::Vector3d(length, 0.0, 0.0)), w;
    return x;
}

TEST(BeamElement, RigidMotionsStoreNoStrainEnergy) {
    for (const bool timoshenko : {false, true}) {
        const double length = 0.02;
        const ElementMatrix k = beam_element_stiffness(aluminium(timoshenko), length);
        EXPECT_LT((k - k.transpose()).norm(), kRelativeRoundOff * k.norm());
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int trial = 0; trial < 5; ++trial) {
            const auto x = rigid_motion({u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, length);
            EXPECT_LT((k * x).norm(), kRelativeRoundOff * k.norm()) << timoshenko;
        }
    }
}

TEST(BeamElement, ConsistentMassCarriesTheElementMassInEveryTranslation) {
    for (const bool timoshenko : {false, true}) {
        const auto p = aluminium(timoshenko);
        const double length = 0.03;
        const ElementMatrix m = beam_element_mass(p, length);
        const double mass = p.density_kg_m3 * p.section.area_m2 * length;
        for (int d = 0; d < 3; ++d) {
            const auto x = rigid_motion(Eigen::Vector3d::Unit(d), Eigen::Vector3d::Zero(), length);
            EXPECT_NEAR(x.dot(m * x), mass, kRelativeRoundOff * mass) << d;
        }
    }
}

TEST(Section, RoarkTorsionConstantOfASquareIsPoint1406A4) {
    // Roark Table 10.7: J = 0.1406 a^4 for a square of side a (2a x 2a form: 2.25 a^4).
    constexpr double kTableDigits = 1e-3;  // the table gives four digits
    const auto s = rectangular_section(0.01, 0.01);
    EXPECT_NEAR(s.torsion_constant_m4 / 1e-8, 0.1406, kTableDigits);
}

TEST(RigidMass, KineticEnergyOfARigidMotionIsThatOfTheMassAboutItsCentreOfGravity) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int trial = 0; trial < 10; ++trial) {
        const double m = 0.5 + std::abs(u(rng));
        const Eigen::Vector3d j(1e-3 + std::abs(u(rng)) * 1e-3, 2e-3, 3e-3 * std::abs(u(rng)));
        const Eigen::Vector3d r(u(rng) * 0.05, u(rng) * 0.05, u(rng) * 0.05);
        const Eigen::Vector3d v(u(rng), u(rng), u(rng));
        const Eigen::Vector3d w(u(rng) * 10, u(rng) * 10, u(rng) * 10);
        Eigen::Matrix<double, 6, 1> x;
        x << v, w;
        const Eigen::Vector3d v_cg = v + w.cross(r);
        const double expected = 0.5 * m * v_cg.squaredNorm() + 0.5 * w.dot(j.asDiagonal() * w);
        EXPECT_NEAR(0.5 * x.dot(rigid_body_mass(m, j, r) * x), expected, 1e-12 * expected);
    }
}

TEST(BeamMesh, HasANodeAtEveryFeatureAndAtLeastTheMinimumElements) {
    BeamSpec b;
    b.length_m = 0.543;
    b.min_elements = 10;
    b.supports = {{"root", 0.0, SupportKind::clamped, {}, {}}};
    b.points = {{"p", 0.16}, {"q", 0.16 + 1e-12}};
    b.masses = {{"m", "", 0.533, 0.01, {}, {}}};
    const auto nodes = beam_mesh_nodes(b);
    EXPECT_GE(nodes.size(), 11u);
    EXPECT_DOUBLE_EQ(nodes.front(), 0.0);
    EXPECT_DOUBLE_EQ(nodes.back(), 0.543);
    EXPECT_DOUBLE_EQ(nodes[static_cast<std::size_t>(nearest_node(nodes, 0.16))], 0.16);
    EXPECT_DOUBLE_EQ(nodes[static_cast<std::size_t>(nearest_node(nodes, 0.533))], 0.533);
    for (std::size_t i = 1; i < nodes.size(); ++i) {
        EXPECT_GT(nodes[i] - nodes[i - 1], kNodeMergeDistanceM);
        EXPECT_LE(nodes[i] - nodes[i - 1], 0.0543 + 1e-12);
    }
}

}  // namespace
}  // namespace sb::structure

// Enclosure queries: containment with obstacles, the outside and non-finite guards, horizontal
// layers.
#include "dem/enclosure.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

#include "dem/solver.hpp"
#include "test_helpers.hpp"

namespace sb::dem {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Paper 002 cavity with its obstacle grid (1 mm rods, 5 mm cells) and one partition plate.
EnclosureOptions grid_box() {
    EnclosureOptions o;
    o.shape = EnclosureShape::box;
    o.height_m = 50e-3;
    o.rods.enabled = true;
    o.rods.rod_diameter_m = 1e-3;
    o.rods.cell_size_m = 5e-3;
    o.plates.push_back({{-15e-3, -1e-3, 30e-3}, {15e-3, 1e-3, 32e-3}});
    return o;
}

TEST(Enclosure, ContainsRejectsCentresInsideRodsAndPlates) {
    const Enclosure enc(grid_box());
    // free cell centre
    EXPECT_TRUE(enc.contains({2.5e-3, 2.5e-3, 2.5e-3}));
    // inside the rod along z at (5 mm, 5 mm), 0.3 mm off its axis
    EXPECT_FALSE(enc.contains({5.3e-3, 5e-3, 12.5e-3}));
    // inside the rod along x at (y, z) = (-5 mm, 10 mm)
    EXPECT_FALSE(enc.contains({7.7e-3, -5.2e-3, 10.1e-3}));
    // just outside that rod's surface (0.6 mm from its axis, rod radius 0.5 mm)
    EXPECT_TRUE(enc.contains({7.7e-3, -5.6e-3, 10e-3}));
    // inside the plate
    EXPECT_FALSE(enc.contains({2.5e-3, 0.5e-3, 31e-3}));
    // and every rejected point is inside the walls: the obstacles alone reject it
    EXPECT_TRUE(enc.inside_walls({2.5e-3, 0.5e-3, 31e-3}));
    EXPECT_TRUE(enc.inside_obstacle({5.3e-3, 5e-3, 12.5e-3}));
    // outside the walls and non-finite
    EXPECT_FALSE(enc.contains({16e-3, 2.5e-3, 2.5e-3}));
    EXPECT_FALSE(enc.contains({kNaN, 0.0, 1e-3}));
}

TEST(Enclosure, ContactsAndContainsIsForEachContactAndContains) {
    // The sweep's fused query against the two it replaces, over centres all through the
    // grid's cavity: inside rods and plates, on the walls, outside and not finite.
    const Enclosure enclosure(grid_box());
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> across(-16e-3, 16e-3), up(-1e-3, 51e-3);
    using Emitted = std::vector<std::tuple<std::uint32_t, double, double, double, double>>;
    int inside = 0, outside = 0, touching = 0;
    for (int k = 0; k < 20000; ++k) {
        const Eigen::Vector3d xl = k == 0 ? Eigen::Vector3d(kNaN, 0.0, 1e-3)
                                          : Eigen::Vector3d(across(rng), across(rng), up(rng));
        const double r = 1e-3;
        Emitted expected, got;
        enclosure.for_each_contact(xl, r,
                                   [&](std::uint32_t id, const Eigen::Vector3d& n, double d) {
                                       expected.emplace_back(id, n.x(), n.y(), n.z(), d);
                                   });
        const bool in = enclosure.contacts_and_contains(
            xl, r, [&](std::uint32_t id, const Eigen::Vector3d& n, double d) {
                got.emplace_back(id, n.x(), n.y(), n.z(), d);
            });
        ASSERT_EQ(in, enclosure.contains(xl)) << xl.transpose();
        ASSERT_EQ(got, expected) << xl.transpose();
        (in ? inside : outside) += 1;
        touching += expected.empty() ? 0 : 1;
    }
    // every branch taken: spheres inside and outside, most of them touching a rod or a wall
    EXPECT_GT(inside, 10000);
    EXPECT_GT(outside, 1000);
    EXPECT_GT(touching, 10000);
}

TEST(Enclosure, RodsLyingOnTheWallsAreNotObstacles) {
    const Enclosure enc(grid_box());
    // x = +-15 mm and z = 0 lattice lines coincide with walls and are dropped
    EXPECT_FALSE(enc.inside_obstacle({14.9e-3, 5e-3, 12.5e-3}));
    EXPECT_FALSE(enc.inside_obstacle({2.5e-3, 5e-3, 0.1e-3}));
}

SolverOptions guarded_box(int count) {
    SolverOptions o = test::free_box_options(count, NormalLaw::hooke);
    o.particles.diameter_m = 2e-3;
    o.enclosure = grid_box();
    o.max_overlap_fraction = 1.0;  // let the outside guard speak first
    return o;
}

TEST(SolverGuard, ParticleInsideARodIsReportedOutsideTheEnclosure) {
    const SolverOptions o = guarded_box(2);
    // particle 1 sits on the axis region of the z rod at (5 mm, 5 mm)
    Solver s(o, test::particles_at({{2.5e-3, 2.5e-3, 2.5e-3}, {5.2e-3, 5e-3, 22.5e-3}}, 1e-3));
    try {
        s.step(1e-6);
        FAIL() << "no guard fired";
    } catch (const SimulationError& e) {
        EXPECT_EQ(e.kind, SimulationError::Kind::outside);
        EXPECT_EQ(e.particle_id, 1);
        EXPECT_EQ(e.step, 0);
    }
}

TEST(SolverGuard, ParticleTunnellingIntoAPlateIsCaughtTheNextStep) {
    const SolverOptions o = guarded_box(1);
    // 1.2 mm above the plate top (no contact), falling 1.5 mm in one step: the centre ends
    // 0.3 mm inside the 2 mm thick plate
    const double dt = 1e-4;
    Solver s(o, test::particles_at({{2.5e-3, 0.0, 33.2e-3}}, 1e-3, {{0.0, 0.0, -15.0}}));
    s.step(dt);
    try {
        s.step(dt);
        FAIL() << "no guard fired";
    } catch (const SimulationError& e) {
        EXPECT_EQ(e.kind, SimulationError::Kind::outside);
        EXPECT_EQ(e.particle_id, 0);
        EXPECT_EQ(e.step, 1);
    }
}

TEST(SolverGuard, NonFiniteEnclosurePoseIsReportedAsNotFinite) {
    const SolverOptions o = guarded_box(1);
    Solver s(o, test::particles_at({{2.5e-3, 2.5e-3, 2.5e-3}}, 1e-3));
    s.step(1e-6);
    EnclosureState bad;
    bad.position_m.z() = kNaN;
    try {
        s.set_enclosure_state(bad);
        FAIL() << "no guard fired";
    } catch (const SimulationError& e) {
        EXPECT_EQ(e.kind, SimulationError::Kind::not_finite);
        EXPECT_EQ(e.particle_id, -1);  // the enclosure, not a particle
        EXPECT_EQ(e.step, 1);
    }
    bad = EnclosureState{};
    bad.angular_velocity_rad_s.x() = std::numeric_limits<double>::infinity();
    EXPECT_THROW(s.set_enclosure_state(bad), SimulationError);
    bad = EnclosureState{};
    bad.rotation(1, 2) = kNaN;
    EXPECT_THROW(Solver(o, test::particles_at({{2.5e-3, 2.5e-3, 2.5e-3}}, 1e-3), bad),
                 std::invalid_argument);
}

TEST(SolverGuard, NonFiniteVelocityIsReportedInTheStepItAppears) {
    // The guard sums x and the spin only: a non-finite v must still stop the step in which it
    // appears, through x = x + dt v, and name its particle.
    const SolverOptions o = guarded_box(2);
    for (const double bad : {kNaN, std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()}) {
        Solver s(o, test::particles_at({{2.5e-3, 2.5e-3, 2.5e-3}, {7.5e-3, 7.5e-3, 2.5e-3}}, 1e-3,
                                       {{0.0, 0.0, 0.0}, {0.0, bad, 0.0}}));
        try {
            s.step(1e-6);
            FAIL() << "no guard fired for v = " << bad;
        } catch (const SimulationError& e) {
            EXPECT_EQ(e.kind, SimulationError::Kind::not_finite);
            EXPECT_EQ(e.particle_id, 1);
            EXPECT_EQ(e.step, 0);
        }
    }
}

TEST(HorizontalLayers, WithTheAxisVerticalTheLayersAreSlabsAlongLocalZ) {
    EnclosureOptions o = grid_box();
    const Enclosure enc(o);
    const auto layers =
        HorizontalLayers::for_gravity(enc, EnclosureState{}, {0, 0, -kStandardGravity}, 10);
    EXPECT_EQ(layers.lowest(), 0.0);
    EXPECT_EQ(layers.highest(), 50e-3);
    EXPECT_EQ(layers.index({0, 0, 0.1e-3}), 0);
    EXPECT_EQ(layers.index({14e-3, -14e-3, 4.9e-3}), 0);
    EXPECT_EQ(layers.index({0, 0, 5.1e-3}), 1);
    EXPECT_EQ(layers.index({0, 0, 49.9e-3}), 9);
    EXPECT_EQ(layers.index({0, 0, -1.0}), 0);  // beyond the range: clamped
    EXPECT_EQ(layers.index({0, 0, 1.0}), 9);
}

TEST(HorizontalLayers, WithTheAxisHorizontalTheLayersStillStackAlongGravity) {
    const Eigen::Matrix3d r_y = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitY()).matrix();
    for (EnclosureShape shape : {EnclosureShape::box, EnclosureShape::cylinder}) {
        EnclosureOptions o = grid_box();
        o.shape = shape;
        o.inner_diameter_m = 30e-3;
        const Enclosure enc(o);
        EnclosureState pose;
        pose.rotation = r_y;  // local z -> world x, local x -> world -z
        const auto layers = HorizontalLayers::for_gravity(enc, pose, {0, 0, -kStandardGravity}, 6);
        // up is local -x: the span is the 30 mm width, not the 50 mm axis
        EXPECT_NEAR(layers.up().x(), -1.0, 1e-15);
        EXPECT_NEAR(layers.highest() - layers.lowest(), 30e-3, 1e-15);
        // points at the same world height share a layer wherever they are along the axis
        for (double world_z : {-14e-3, -7e-3, 0.5e-3, 9e-3, 14e-3}) {
            const int first =
                layers.index(pose.rotation.transpose() * Eigen::Vector3d(1e-3, 0, world_z));
            for (double along : {2e-3, 25e-3, 48e-3}) {
                const Eigen::Vector3d world(along, 3e-3, world_z);
                EXPECT_EQ(layers.index(pose.rotation.transpose() * world), first) << world_z;
            }
        }
        // bottom (world z = -14 mm, i.e. local x = +14 mm) is layer 0, top the last one
        EXPECT_EQ(layers.index({14e-3, 0, 25e-3}), 0);
        EXPECT_EQ(layers.index({-14e-3, 0, 25e-3}), 5);
    }
}

TEST(HorizontalLayers, TiltedCylinderSpansItsProjectedHeight) {
    EnclosureOptions o;  // 19 mm x 25 mm cylinder
    const Enclosure enc(o);
    const double tilt = 0.3;
    const Eigen::Vector3d up(std::sin(tilt), 0.0, std::cos(tilt));
    const HorizontalLayers layers(enc, up, 4);
    // support function: the axis segment projected, widened by R sin(tilt) each side
    const double r = 9.5e-3;
    EXPECT_NEAR(layers.lowest(), -r * std::sin(tilt), 1e-15);
    EXPECT_NEAR(layers.highest(), 25e-3 * std::cos(tilt) + r * std::sin(tilt), 1e-15);
}

}  // namespace
}  // namespace sb::dem

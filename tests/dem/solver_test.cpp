// Solver: validation, guards, wall force and moment, impulse balance, determinism, locking.
#include "dem/solver.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "dem/setup.hpp"
#include "test_helpers.hpp"

namespace sb::dem {
namespace {

using test::free_box_options;
using test::particles_at;

TEST(SolverOptions, ValidateCollectsEveryViolationWithRelativeKeys) {
    SolverOptions o;
    o.particles.count = 0;
    o.particles.material.density_kg_m3 = -1.0;
    o.enclosure.height_m = 0.0;
    o.max_overlap_fraction = 2.0;
    const Violations v = o.validate();
    std::vector<std::string> keys;
    for (const auto& x : v) keys.push_back(x.key);
    EXPECT_NE(std::find(keys.begin(), keys.end(), "particles.count"), keys.end());
    EXPECT_NE(std::find(keys.begin(), keys.end(), "particles.material.density_kg_m3"), keys.end());
    EXPECT_NE(std::find(keys.begin(), keys.end(), "enclosure.height_m"), keys.end());
    EXPECT_NE(std::find(keys.begin(), keys.end(), "contact.normal_stiffness"), keys.end());
    EXPECT_NE(std::find(keys.begin(), keys.end(), "max_overlap_fraction"), keys.end());
}

TEST(Solver, ConstructorRejectsInvalidOptionsNamingEachViolationOnce) {
    SolverOptions o = free_box_options(1, NormalLaw::hooke);
    o.contact.normal_stiffness = 0.0;
    o.contact.particle_wall.sliding_friction = -1.0;
    try {
        Solver solver(o, particles_at({{0, 0, 0.05}}, 1.5e-3));
        FAIL() << "invalid options were accepted";
    } catch (const std::invalid_argument& e) {
        const std::string message = e.what();
        for (const std::string key :
             {"contact.normal_stiffness", "contact.particle_wall.sliding_friction"}) {
            const auto first = message.find(key + " =");
            ASSERT_NE(first, std::string::npos) << message;
            EXPECT_EQ(message.find(key + " =", first + 1), std::string::npos)
                << key << " is reported twice:\n"
                << message;
        }
    }
}

TEST(SolverOptions, ElementsOfListsAreKeyedByIndexInBrackets) {
    SolverOptions o;
    o.particles.size_distribution = {{3e-3, 0.5}, {-1.0, 0.5}};
    o.enclosure.plates = {{{0, 0, 0}, {-1, 1, 1}}};
    std::vector<std::string> keys;
    for (const auto& x : o.validate()) keys.push_back(x.key);
    EXPECT_NE(std::find(keys.begin(), keys.end(), "particles.size_distribution[1].diameter_m"),
              keys.end());
    EXPECT_NE(std::find(keys.begin(), keys.end(), "enclosure.plates[0]"), keys.end());
}

TEST(Solver, ParticleLeavingTheEnclosureThrowsWithItsId) {
    SolverOptions o = free_box_options(2, NormalLaw::hooke);
    Solver s(o, particles_at({{0, 0, 0.05}, {0.02, 0, 0.05}}, 1.5e-3));
    EnclosureState e;
    e.position_m = Eigen::Vector3d(-0.035, 0, 0);  // jump: particle 1 is now outside
    s.set_enclosure_state(e);
    try {
        s.step(1e-6);
        FAIL() << "expected SimulationError";
    } catch (const SimulationError& err) {
        EXPECT_EQ(err.kind, SimulationError::Kind::outside);
        EXPECT_EQ(err.particle_id, 1);
        EXPECT_EQ(err.step, 0);
    }
}

TEST(Solver, ExcessiveOverlapThrowsWithStepTimeAndId) {
    SolverOptions o = free_box_options(3, NormalLaw::hooke);
    o.max_overlap_fraction = 0.1;
    Solver s(o, particles_at({{-0.02, 0, 0.05}, {0, 0, 0.05}, {0.0025, 0, 0.05}}, 1.5e-3));
    try {
        s.step(1e-6);
        FAIL() << "expected SimulationError";
    } catch (const SimulationError& err) {
        EXPECT_EQ(err.kind, SimulationError::Kind::overlap);
        EXPECT_EQ(err.particle_id, 1);
        EXPECT_NE(std::string(err.what()).find("step 0"), std::string::npos);
    }
}

TEST(Solver, NonFiniteStateThrows) {
    SolverOptions o = free_box_options(1, NormalLaw::hooke);
    Solver s(o, particles_at({{0, 0, 0.05}}, 1.5e-3, {{std::nan(""), 0, 0}}));
    EXPECT_THROW(s.step(1e-6), SimulationError);
}

/// Resting spheres: wall force = total weight, wall moment = r x weight.
TEST(Solver, ParticlesAtRestGiveTheirWeightAndItsMoment) {
    SolverOptions o = free_box_options(3, NormalLaw::hooke);
    o.gravity_m_s2 = Eigen::Vector3d(0, 0, -9.80665);
    o.contact.particle_wall.restitution = 0.3;
    const double r = 1.5e-3;
    const std::vector<Eigen::Vector3d> x{{0.01, 0.02, r}, {-0.03, 0.0, r}, {0.0, -0.01, r}};
    Solver s(o, particles_at(x, r));
    for (int k = 0; k < 40000; ++k) s.step(2e-6);
    const double m = 7800.0 * 4.0 / 3.0 * kPi * r * r * r;
    const Eigen::Vector3d weight = 3.0 * m * o.gravity_m_s2;
    EXPECT_LT((s.wall_force() - weight).norm(), 1e-6 * weight.norm());
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (const auto& xi : x)
        moment += Eigen::Vector3d(xi.x(), xi.y(), 0.0).cross(m * o.gravity_m_s2);
    EXPECT_LT((s.wall_moment() - moment).norm(), 1e-5 * moment.norm());
}

SolverOptions shaken_options(int count) {
    SolverOptions o;
    o.particles.count = count;
    o.particles.diameter_m = 2e-3;
    o.enclosure.shape = EnclosureShape::box;
    o.enclosure.length_x_m = 20e-3;
    o.enclosure.length_y_m = 20e-3;
    o.enclosure.height_m = 30e-3;
    o.contact.normal_stiffness = 5e3;
    return o;
}

EnclosureState shaken_state(double t, double amp, double w) {
    EnclosureState e;
    e.position_m = Eigen::Vector3d(0.3 * amp * std::sin(w * t), 0, amp * std::sin(w * t));
    e.velocity_m_s = Eigen::Vector3d(0.3 * amp * w * std::cos(w * t), 0, amp * w * std::cos(w * t));
    const double th = 0.05 * std::sin(w * t);
    e.rotation = Eigen::AngleAxisd(th, Eigen::Vector3d::UnitY()).toRotationMatrix();
    e.angular_velocity_rad_s = Eigen::Vector3d(0, 0.05 * w * std::cos(w * t), 0);
    return e;
}

TEST(Solver, ImpulseExchangedWithTheWallsEqualsMomentumChange) {
    SolverOptions o = shaken_options(60);
    o.contact.tangential = TangentialLaw::coulomb_spring;
    const ParticleSet p = fill_random(o, 3);
    Solver s(o, p, shaken_state(0.0, 2e-3, 2 * kPi * 30));
    auto momentum = [&] {
        Eigen::Vector3d q = Eigen::Vector3d::Zero();
        for (std::size_t i = 0; i < s.particles().size(); ++i) {
            q += s.particles().v[i] / s.particles().inv_mass[i];
        }
        return q;
    };
    double mass = 0.0;
    for (double im : s.particles().inv_mass) mass += 1.0 / im;
    const Eigen::Vector3d q0 = momentum();
    Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
    const double dt = 2e-6;
    for (int k = 0; k < 5000; ++k) {
        s.set_enclosure_state(shaken_state(k * dt, 2e-3, 2 * kPi * 30));
        s.step(dt);
        impulse -= s.wall_force() * dt;  // force on the particles
    }
    const Eigen::Vector3d expected = impulse + mass * o.gravity_m_s2 * (5000 * dt);
    EXPECT_LT((momentum() - q0 - expected).norm(), 1e-9 * (impulse.norm() + 1e-12));
    EXPECT_GT(impulse.norm(), 0.0);
}

TEST(Solver, OneTwoAndThreeThreadsGiveBitwiseIdenticalResultsOnADenseBed) {
    constexpr int kPerSide = 8;
    constexpr double kSpacing = 1.998e-3;  // 2 um overlap between lattice neighbours
    SolverOptions o = shaken_options(kPerSide * kPerSide * kPerSide);
    o.enclosure.length_x_m = kPerSide * kSpacing - 2e-6;  // outer spheres press the side walls
    o.enclosure.length_y_m = o.enclosure.length_x_m;
    o.contact.normal_stiffness = 1e5;
    o.contact.tangential = TangentialLaw::coulomb_spring;
    o.contact.rolling = RollingLaw::constant_torque;
    o.energy_layers = 4;
    // Small grain so that every loop is split across all threads (the default keeps a bed this
    // size on one thread).
    o.parallel_grain = 16;
    const ParticleSet p = test::pressed_lattice(kPerSide, kSpacing);
    const double dt = 2e-6;
    auto run = [&](int threads) {
        SolverOptions oo = o;
        oo.threads = threads;
        Solver s(oo, p, shaken_state(0.0, 1e-4, 2 * kPi * 50));
        for (int k = 0; k < 100; ++k) {
            s.set_enclosure_state(shaken_state(k * dt, 1e-4, 2 * kPi * 50));
            s.step(dt);
        }
        return s;
    };
    const Solver a = run(1);
    // Every loop must really be split three ways (3 * grain particles), and the contacts
    // must cross the thread chunks (> 4 per sphere in a lattice: many pairs straddle them).
    const auto grain = static_cast<std::size_t>(o.parallel_grain);
    ASSERT_GE(a.particles().size(), 3 * grain);
    ASSERT_GT(a.contact_count(), 2 * a.particles().size());
    for (int threads : {2, 3}) {
        const Solver b = run(threads);
        SCOPED_TRACE(threads);
        ASSERT_EQ(a.contact_count(), b.contact_count());
        for (std::size_t i = 0; i < a.particles().size(); ++i) {
            ASSERT_EQ(a.particles().x[i], b.particles().x[i]) << i;
            ASSERT_EQ(a.particles().v[i], b.particles().v[i]) << i;
            ASSERT_EQ(a.particles().w[i], b.particles().w[i]) << i;
        }
        EXPECT_EQ(a.wall_force(), b.wall_force());
        EXPECT_EQ(a.wall_moment(), b.wall_moment());
        const EnergyLedger ea = a.energy(), eb = b.energy();
        EXPECT_EQ(ea.wall_work, eb.wall_work);
        EXPECT_EQ(ea.normal_damping, eb.normal_damping);
        EXPECT_EQ(ea.friction, eb.friction);
        EXPECT_EQ(ea.rolling, eb.rolling);
        EXPECT_EQ(ea.kinetic_translational, eb.kinetic_translational);
        EXPECT_EQ(ea.kinetic_rotational, eb.kinetic_rotational);
        EXPECT_EQ(ea.potential, eb.potential);
        EXPECT_EQ(ea.elastic, eb.elastic);
        EXPECT_EQ(ea.initial_total, eb.initial_total);
        EXPECT_EQ(ea.layer_dissipation, eb.layer_dissipation);
    }
}

TEST(SolverOptions, ParallelGrainMustBePositive) {
    SolverOptions o;
    o.contact.normal_stiffness = 1e5;
    o.parallel_grain = 0;
    const Violations v = o.validate();
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].key, "parallel_grain");
}

TEST(Solver, LockedParticlesMoveWithTheEnclosureUntilRelease) {
    SolverOptions o = shaken_options(20);
    o.lock.fraction = 0.5;
    o.lock.release_time_s = 0.01;
    const ParticleSet p = fill_random(o, 5);
    Solver s(o, p, shaken_state(0.0, 2e-3, 2 * kPi * 30));
    EXPECT_EQ(s.locked_count(), 10);
    const double dt = 2e-6;
    for (int k = 0; k < 4000; ++k) {
        s.set_enclosure_state(shaken_state(k * dt, 2e-3, 2 * kPi * 30));
        s.step(dt);
    }
    const ParticleSet now = s.local_snapshot();
    int frozen = 0;
    for (std::size_t i = 0; i < now.positions_m.size(); ++i) {
        // a locked particle's local position is frozen up to one free step of drift
        if ((now.positions_m[i] - p.positions_m[i]).norm() < 1e-6) ++frozen;
    }
    EXPECT_GE(frozen, 10);
    for (int k = 4000; k < 6000; ++k) {
        s.set_enclosure_state(shaken_state(k * dt, 2e-3, 2 * kPi * 30));
        s.step(dt);
    }
    EXPECT_EQ(s.locked_count(), 0);
}

TEST(Solver, LayerDissipationAddsUpToTheTotal) {
    SolverOptions o = shaken_options(60);
    o.energy_layers = 5;
    Solver s(o, fill_random(o, 9));
    for (int k = 0; k < 5000; ++k) {
        s.set_enclosure_state(shaken_state(k * 2e-6, 2e-3, 2 * kPi * 30));
        s.step(2e-6);
    }
    const EnergyLedger e = s.energy();
    double sum = 0.0;
    for (double d : e.layer_dissipation) sum += d;
    EXPECT_GT(e.dissipated(), 0.0);
    EXPECT_NEAR(sum, e.dissipated(), 1e-9 * e.dissipated());
}

/// A box lying on its side (local z horizontal, local +x down) with a row of spheres on its
/// floor along the whole axis, shaken vertically at about 1.8 g: every contact is on the floor,
/// so all the dissipation is in the bottom layer along gravity. Slabs along local z would
/// share it out over all four layers.
TEST(Solver, LayersStackAlongGravityWhenTheEnclosureLiesOnItsSide) {
    SolverOptions o = shaken_options(12);
    o.energy_layers = 4;
    const Eigen::Matrix3d lying =
        Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitY()).toRotationMatrix();
    ASSERT_LT((lying * Eigen::Vector3d::UnitX() - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
    const double r = 1e-3;
    ParticleSet p;
    {
        const Enclosure enc(o.enclosure);
        for (int k = 0; k < 4; ++k) {
            const double z =
                enc.lower().z() + (k + 0.5) / 4.0 * (enc.upper().z() - enc.lower().z());
            for (double y : {-5e-3, 0.0, 5e-3}) {
                p.positions_m.emplace_back(enc.upper().x() - r, y, z);
                p.radii_m.push_back(r);
            }
        }
    }
    const double amp = 0.5e-3, w = 2 * kPi * 30;
    auto pose = [&](double t) {
        EnclosureState e;
        e.rotation = lying;
        e.position_m = Eigen::Vector3d(0, 0, amp * std::sin(w * t));
        e.velocity_m_s = Eigen::Vector3d(0, 0, amp * w * std::cos(w * t));
        return e;
    };
    Solver s(o, p, pose(0.0));
    EXPECT_LT((s.layers().up() - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-12);
    const double dt = 2e-6;
    for (int k = 0; k < 25000; ++k) {
        s.set_enclosure_state(pose(k * dt));
        s.step(dt);
    }
    const EnergyLedger e = s.energy();
    ASSERT_EQ(e.layer_dissipation.size(), 4u);
    ASSERT_GT(e.dissipated(), 0.0);
    EXPECT_NEAR(e.layer_dissipation[0], e.dissipated(), 1e-9 * e.dissipated());
    for (int l = 1; l < 4; ++l) EXPECT_EQ(e.layer_dissipation[static_cast<std::size_t>(l)], 0.0);
}

}  // namespace
}  // namespace sb::dem

namespace sb::dem {
namespace {

/// A sphere resting on a partition plate of a rotated enclosure, gravity rotated with it: the
/// wall force and moment rotate with the set-up (objectivity through the whole solver).
TEST(Solver, RotatedRestingContactGivesRotatedWallForce) {
    auto run = [](const Eigen::Matrix3d& q) {
        SolverOptions o = test::free_box_options(1, NormalLaw::hooke);
        o.gravity_m_s2 = q * Eigen::Vector3d(0, 0, -kStandardGravity);
        o.contact.tangential = TangentialLaw::coulomb_spring;
        o.contact.rolling = RollingLaw::constant_torque;
        o.contact.particle_wall.restitution = 0.3;
        o.enclosure.plates.push_back({{-0.01, -0.01, 0.02}, {0.01, 0.01, 0.022}});
        EnclosureState e;
        e.rotation = q;
        Solver s(o, test::particles_at({{0.004, 0.002, 0.022 + 1.5e-3}}, 1.5e-3), e);
        for (int k = 0; k < 20000; ++k) s.step(2e-6);
        return std::make_pair(s.wall_force(), s.wall_moment());
    };
    const auto [f0, m0] = run(Eigen::Matrix3d::Identity());
    const Eigen::Matrix3d q =
        Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
    const auto [f1, m1] = run(q);
    const double m = 7800.0 * 4.0 / 3.0 * kPi * std::pow(1.5e-3, 3);
    EXPECT_NEAR(f0.z(), -m * kStandardGravity, 1e-6 * m * kStandardGravity);
    EXPECT_LT((f1 - q * f0).norm(), 1e-9 * f0.norm());
    EXPECT_LT((m1 - q * m0).norm(), 1e-9 * m0.norm());
}

TEST(Enclosure, ObstacleGridRodsAreFoundNearestPerAxis) {
    EnclosureOptions o;
    o.shape = EnclosureShape::box;
    o.rods.enabled = true;
    o.rods.rod_diameter_m = 1e-3;
    o.rods.cell_size_m = 5e-3;
    const Enclosure enc(o);
    // a sphere of radius 1 mm centred 1.2 mm from the z-rod at (5 mm, 5 mm) and far from others
    int hits = 0;
    enc.for_each_contact(Eigen::Vector3d(5e-3 + 1.2e-3, 5e-3, 12.5e-3), 1e-3,
                         [&](std::uint32_t id, const Eigen::Vector3d& n, double delta) {
                             ++hits;
                             EXPECT_GE(id, kRodBase);
                             EXPECT_NEAR(n.x(), 1.0, 1e-12);
                             EXPECT_NEAR(delta, 1e-3 + 0.5e-3 - 1.2e-3, 1e-12);
                         });
    EXPECT_EQ(hits, 1);
    // rods on the walls themselves are not obstacles: x = +-15 mm lines are skipped
    EXPECT_GT(enc.clearance(Eigen::Vector3d(14e-3, 2.5e-3, 2.5e-3)), 0.0);
}

}  // namespace
}  // namespace sb::dem

namespace sb::dem {
namespace {

TEST(Solver, VerletSkinFixedOrAdaptedGivesTheSameResultsAsRebuildingEveryStep) {
    SolverOptions o = test::paper000_options();
    o.contact.tangential = TangentialLaw::coulomb_spring;
    const ParticleSet p = fill_random(o, 17);
    auto run = [&](double skin, bool adapt) {
        SolverOptions oo = o;
        oo.neighbor_skin_fraction = skin;
        oo.adapt_neighbor_skin = adapt;
        const double w = kTwoPi * 30.0, amp = 3.0 * kStandardGravity / (w * w);
        auto state = [&](double t) {
            EnclosureState e;
            e.position_m = Eigen::Vector3d(0, 0, amp * std::sin(w * t));
            e.velocity_m_s = Eigen::Vector3d(0, 0, amp * w * std::cos(w * t));
            return e;
        };
        Solver s(oo, p, state(0.0));
        for (int k = 0; k < 8000; ++k) {
            s.set_enclosure_state(state(k * 5e-6));
            s.step(5e-6);
        }
        return s;
    };
    const Solver a = run(0.0, false), b = run(0.1, false), c = run(0.1, true);
    EXPECT_EQ(a.neighbor_builds(), 8000);
    EXPECT_LT(b.neighbor_builds(), 800);
    // The adapted skin stays within its bounds, and on this bed (3 g at 30 Hz: the spheres
    // move little per step, many candidates lie in a skin of a tenth of a diameter) it left the
    // configured one: fewer candidate tests for more rebuilds, still far fewer than every step.
    const double d = o.particles.largest_diameter_m();
    EXPECT_EQ(b.neighbor_skin(), 0.1 * d);
    EXPECT_GE(c.neighbor_skin(), kMinSkinShare * 0.1 * d);
    EXPECT_LT(c.neighbor_skin(), 0.1 * d);
    EXPECT_GT(c.neighbor_builds(), b.neighbor_builds());
    EXPECT_LT(c.neighbor_builds(), 8000 / 4);
    for (std::size_t i = 0; i < a.particles().size(); ++i) {
        ASSERT_EQ(a.particles().x[i], b.particles().x[i]) << i;
        ASSERT_EQ(a.particles().w[i], b.particles().w[i]) << i;
        ASSERT_EQ(a.particles().x[i], c.particles().x[i]) << i;
        ASSERT_EQ(a.particles().v[i], c.particles().v[i]) << i;
        ASSERT_EQ(a.particles().w[i], c.particles().w[i]) << i;
    }
    EXPECT_EQ(a.wall_force(), c.wall_force());
}

}  // namespace
}  // namespace sb::dem

// SolverState: a solver continued from its saved state (bitwise at the same pose, moved
// rigidly at another), tangential springs, lock and clock carried across the restore.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "dem/solver.hpp"
#include "test_helpers.hpp"

namespace sb::dem {
namespace {

constexpr int kCount = 150;
constexpr double kDt = 5e-6;  // 1/18 of the pair contact time at k = 2e4 N/m

/// 150 steel spheres of 2 mm in a 12 mm x 12 mm box, k = 2e4 N/m, history-spring friction.
SolverOptions bed_options(TangentialLaw tangential) {
    SolverOptions o;
    o.particles.count = kCount;
    o.particles.diameter_m = 2e-3;
    o.enclosure.shape = EnclosureShape::box;
    o.enclosure.length_x_m = 12e-3;
    o.enclosure.length_y_m = 12e-3;
    o.enclosure.height_m = 20e-3;
    o.contact.normal_stiffness = 2e4;
    o.contact.tangential = tangential;
    o.contact.rolling = RollingLaw::constant_torque;
    o.energy_layers = 3;
    return o;
}

/// The bed poured under gravity along -z and settled to rest (about 7 layers deep): every
/// sphere rests on several others or on the walls.
const ParticleSet& poured_bed() {
    static const ParticleSet bed = [] {
        SettleOptions settle;
        settle.dt_s = kDt;
        return pour(bed_options(TangentialLaw::coulomb_spring), 7, settle);
    }();
    return bed;
}

/// 100 Hz: vertical at 0.5 g peak with a sideways part and a rocking of 0.5 mrad about an
/// oblique axis (about 0.2 g at the walls), about an origin away from the world's (so that
/// the enclosure frame and the world frame differ in every component). The bed stays down:
/// its contacts persist, loaded and unloaded every cycle, some slipping.
EnclosureState shaking(double t) {
    const double w = kTwoPi * 100.0, a = 0.5 * kStandardGravity / (w * w);
    const double s = std::sin(w * t), c = std::cos(w * t);
    const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, 0.5).normalized();
    EnclosureState e;
    e.position_m = Eigen::Vector3d(0.1, -0.05, 0.2) + Eigen::Vector3d(0.4 * a * s, 0.0, a * s);
    e.velocity_m_s = Eigen::Vector3d(0.4 * a * w * c, 0.0, a * w * c);
    e.rotation = Eigen::AngleAxisd(5e-4 * s, axis).toRotationMatrix();
    e.angular_velocity_rad_s = 5e-4 * w * c * axis;
    return e;
}

void shake(Solver& s, int from, int to) {
    for (int k = from; k < to; ++k) {
        s.set_enclosure_state(shaking(k * kDt));
        s.step(kDt);
    }
}

void expect_same_particles(const Solver& a, const Solver& b) {
    ASSERT_EQ(a.particles().size(), b.particles().size());
    for (std::size_t i = 0; i < a.particles().size(); ++i) {
        ASSERT_EQ(a.particles().x[i], b.particles().x[i]) << "particle " << i;
        ASSERT_EQ(a.particles().v[i], b.particles().v[i]) << "particle " << i;
        ASSERT_EQ(a.particles().w[i], b.particles().w[i]) << "particle " << i;
    }
}

void expect_same_springs(const SolverState& a, const SolverState& b) {
    ASSERT_EQ(a.pair_histories.size(), b.pair_histories.size());
    for (std::size_t k = 0; k < a.pair_histories.size(); ++k) {
        EXPECT_EQ(a.pair_histories[k].i, b.pair_histories[k].i);
        EXPECT_EQ(a.pair_histories[k].j, b.pair_histories[k].j);
        EXPECT_EQ(a.pair_histories[k].history_m, b.pair_histories[k].history_m);
    }
    ASSERT_EQ(a.wall_histories.size(), b.wall_histories.size());
    for (std::size_t k = 0; k < a.wall_histories.size(); ++k) {
        EXPECT_EQ(a.wall_histories[k].particle, b.wall_histories[k].particle);
        EXPECT_EQ(a.wall_histories[k].wall, b.wall_histories[k].wall);
        EXPECT_EQ(a.wall_histories[k].history_m, b.wall_histories[k].history_m);
    }
}

std::size_t nonzero_springs(const SolverState& s) {
    std::size_t n = 0;
    for (const auto& h : s.pair_histories) n += h.history_m != Eigen::Vector3d::Zero();
    for (const auto& h : s.wall_histories) n += h.history_m != Eigen::Vector3d::Zero();
    return n;
}

/// Runs `a` (already at step `from`) and `b`, restored from a's state at `from`, side by side
/// to `to`: bitwise equal wall force and moment at every step, particles at the end. The
/// restored solver builds its neighbour list at its first step; the original must not (it
/// keeps the list of an earlier step), so that the two lists differ.
void continue_side_by_side(Solver& a, Solver& b, int from, int to) {
    const std::int64_t builds = a.neighbor_builds();
    shake(a, from, from + 1);
    shake(b, from, from + 1);
    ASSERT_EQ(a.neighbor_builds(), builds) << "capture at a step where the original keeps its list";
    for (int k = from + 1; k <= to; ++k) {
        ASSERT_EQ(a.wall_force(), b.wall_force()) << "step " << k;
        ASSERT_EQ(a.wall_moment(), b.wall_moment()) << "step " << k;
        ASSERT_EQ(a.contact_count(), b.contact_count()) << "step " << k;
        if (k < to) {
            shake(a, k, k + 1);
            shake(b, k, k + 1);
        }
    }
    expect_same_particles(a, b);
    EXPECT_EQ(a.time(), b.time());
    EXPECT_EQ(a.step_count(), b.step_count());
}

constexpr int kCapture = 2000;  // one period of shaking
constexpr int kEnd = 5000;

TEST(SolverState, RestoredAtTheSamePoseContinuesBitwiseWithTheHistorySprings) {
    const SolverOptions o = bed_options(TangentialLaw::coulomb_spring);
    Solver a(o, poured_bed(), shaking(0.0));
    shake(a, 0, kCapture);
    const SolverState s = a.state();
    // Many persistent contacts, nearly all holding a spring: a dense bed.
    ASSERT_GT(s.pair_histories.size(), static_cast<std::size_t>(kCount));
    ASSERT_GT(s.wall_histories.size(), static_cast<std::size_t>(kCount) / 3);
    ASSERT_GT(nonzero_springs(s), (s.pair_histories.size() + s.wall_histories.size()) * 9 / 10);
    Solver b(o, s, s.enclosure);
    // Saving the restored solver gives the same state back (nothing lost or altered).
    const SolverState again = b.state();
    expect_same_springs(s, again);
    EXPECT_EQ(again.positions_m, s.positions_m);
    EXPECT_EQ(again.velocities_m_s, s.velocities_m_s);
    EXPECT_EQ(again.angular_velocities_rad_s, s.angular_velocities_rad_s);
    EXPECT_EQ(again.time_s, s.time_s);
    EXPECT_EQ(again.step, s.step);
    EXPECT_EQ(again.layers_up, s.layers_up);
    continue_side_by_side(a, b, kCapture, kEnd);
    expect_same_springs(a.state(), b.state());
    EXPECT_EQ(a.layers().up(), b.layers().up());
}

TEST(SolverState, ARestoredSolverGivenItsLedgerContinuesTheEnergyLedgerBitwise) {
    // The state carries the particles, not the ledger's sums: a restored solver starts them
    // afresh, unless it continues the saved ledger (a characterisation run resumed from its
    // progress needs the sums, not only their changes, to add up to the same numbers).
    const SolverOptions o = bed_options(TangentialLaw::coulomb_spring);
    ASSERT_TRUE(o.track_energy);
    Solver a(o, poured_bed(), shaking(0.0));
    shake(a, 0, kCapture);
    const SolverState s = a.state();
    const EnergyLedger saved = a.energy();
    ASSERT_GT(saved.wall_work, 0.0);
    ASSERT_GT(saved.dissipated(), 0.0);
    Solver b(o, s, s.enclosure);
    EXPECT_EQ(b.energy().wall_work, 0.0);  // afresh
    b.continue_energy(saved);
    shake(a, kCapture, kEnd);
    shake(b, kCapture, kEnd);
    const EnergyLedger ea = a.energy();
    const EnergyLedger eb = b.energy();
    EXPECT_EQ(eb.wall_work, ea.wall_work);
    EXPECT_EQ(eb.normal_damping, ea.normal_damping);
    EXPECT_EQ(eb.friction, ea.friction);
    EXPECT_EQ(eb.rolling, ea.rolling);
    EXPECT_EQ(eb.initial_total, ea.initial_total);
    EXPECT_EQ(eb.layer_dissipation, ea.layer_dissipation);
    EXPECT_EQ(eb.layer_kinetic_time, ea.layer_kinetic_time);
    EXPECT_EQ(eb.mechanical(), ea.mechanical());
    // A ledger of other layers belongs to another solver.
    EnergyLedger other = saved;
    other.layer_dissipation.push_back(0.0);
    EXPECT_THROW(b.continue_energy(other), std::invalid_argument);
}

TEST(SolverState, WithoutItsHistorySpringsTheRestoredBedRunsDifferently) {
    // The same restore with the springs dropped (all else exact), as a rebuild from the
    // enclosure-frame particles alone would do: the contacts restart without static friction
    // and the wall force departs from the uninterrupted run's by more than 1 % of the bed's
    // weight (not by rounding).
    const SolverOptions o = bed_options(TangentialLaw::coulomb_spring);
    Solver a(o, poured_bed(), shaking(0.0));
    shake(a, 0, kCapture);
    SolverState s = a.state();
    s.pair_histories.clear();
    s.wall_histories.clear();
    Solver b(o, s, s.enclosure);
    double weight = 0.0;
    for (double im : a.particles().inv_mass) weight += kStandardGravity / im;
    double largest = 0.0;
    for (int k = kCapture; k < kEnd; ++k) {
        shake(a, k, k + 1);
        shake(b, k, k + 1);
        largest = std::max(largest, (a.wall_force() - b.wall_force()).norm());
    }
    EXPECT_GT(largest, 0.01 * weight);
}

TEST(SolverState, RestoredAtTheSamePoseContinuesBitwiseWithDirectionalCoulomb) {
    const SolverOptions o = bed_options(TangentialLaw::directional_coulomb);
    Solver a(o, poured_bed(), shaking(0.0));
    shake(a, 0, kCapture);
    const SolverState s = a.state();
    EXPECT_TRUE(s.pair_histories.empty());  // the stateless law keeps no springs
    EXPECT_TRUE(s.wall_histories.empty());
    ASSERT_GT(a.contact_count(), static_cast<std::size_t>(kCount));
    Solver b(o, s, s.enclosure);
    continue_side_by_side(a, b, kCapture, kEnd);
}

TEST(SolverState, LockedParticlesAreReleasedAtTheOriginalTimeAfterARestore) {
    SolverOptions o = bed_options(TangentialLaw::coulomb_spring);
    o.lock.fraction = 0.4;  // the lowest 40 %
    o.lock.release_time_s = 3000.5 * kDt;
    const ParticleSet& bed = poured_bed();
    Solver a(o, bed, shaking(0.0));
    const int locked = a.locked_count();
    ASSERT_EQ(locked, 60);
    shake(a, 0, kCapture);
    const SolverState s = a.state();
    ASSERT_EQ(s.locked.size(), static_cast<std::size_t>(locked));
    EXPECT_FALSE(s.released);
    for (const LockedParticle& l : s.locked) {  // frozen where the bed was
        EXPECT_LT((l.position_m - bed.positions_m[l.id]).norm(), 1e-15) << l.id;
    }
    Solver b(o, s, s.enclosure);
    EXPECT_EQ(b.locked_count(), locked);
    EXPECT_EQ(b.time(), a.time());
    int release_a = -1, release_b = -1;
    for (int k = kCapture; k < kEnd; ++k) {
        shake(a, k, k + 1);
        shake(b, k, k + 1);
        if (release_a < 0 && a.locked_count() == 0) release_a = k;
        if (release_b < 0 && b.locked_count() == 0) release_b = k;
    }
    // The clock went on from the state: freed 1000 steps after the restore, not 3000.
    EXPECT_EQ(release_a, 3001);
    EXPECT_EQ(release_b, release_a);
    expect_same_particles(a, b);
    EXPECT_EQ(a.wall_force(), b.wall_force());

    // A state taken after the release restores no lock, although options.lock would lock.
    const SolverState freed = a.state();
    EXPECT_TRUE(freed.released);
    EXPECT_TRUE(freed.locked.empty());
    const Solver c(o, freed, freed.enclosure);
    EXPECT_EQ(c.locked_count(), 0);
    EXPECT_TRUE(c.released());
}

TEST(SolverState, APartialReleaseFreesItsShareOnceTheHighestFirstAndARestoreKeepsTheRest) {
    // Paper 004's electromagnet: every granule held, then 30 % of them freed at a set time,
    // the rest held on; a restore before the release frees the same ones at the same step,
    // one after it frees no more.
    SolverOptions o = bed_options(TangentialLaw::coulomb_spring);
    o.lock.fraction = 1.0;
    o.lock.release_time_s = 3000.5 * kDt;
    o.lock.release_fraction = 0.3;
    Solver a(o, poured_bed(), shaking(0.0));
    ASSERT_EQ(a.locked_count(), kCount);
    shake(a, 0, kCapture);
    const SolverState before = a.state();
    Solver b(o, before, before.enclosure);
    int release_a = -1, release_b = -1;
    for (int k = kCapture; k < kEnd; ++k) {
        shake(a, k, k + 1);
        shake(b, k, k + 1);
        if (release_a < 0 && a.locked_count() < kCount) release_a = k;
        if (release_b < 0 && b.locked_count() < kCount) release_b = k;
    }
    EXPECT_EQ(release_a, 3001);
    EXPECT_EQ(release_b, release_a);
    const int freed = static_cast<int>(std::llround(0.3 * kCount));
    EXPECT_EQ(a.locked_count(), kCount - freed);
    EXPECT_EQ(b.locked_count(), a.locked_count());
    expect_same_particles(a, b);

    // The freed ones were the highest: every locked particle's frozen height is at most the
    // lowest freed one's.
    const SolverState after = a.state();
    EXPECT_TRUE(after.released);
    std::vector<std::uint8_t> held(static_cast<std::size_t>(kCount), 0);
    double highest_held = -1e300;
    for (const LockedParticle& l : after.locked) {
        held[l.id] = 1;
        highest_held = std::max(highest_held, l.position_m.z());
    }
    double lowest_freed = 1e300;
    for (int i = 0; i < kCount; ++i) {
        if (!held[static_cast<std::size_t>(i)]) {
            lowest_freed = std::min(lowest_freed, poured_bed().positions_m[i].z());
        }
    }
    EXPECT_LE(highest_held, lowest_freed + 1e-12);

    // Restored after the release: the rest stay held, and no second share is freed.
    Solver c(o, after, after.enclosure);
    EXPECT_EQ(c.locked_count(), kCount - freed);
    for (int k = kEnd; k < kEnd + 100; ++k) shake(c, k, k + 1);
    EXPECT_EQ(c.locked_count(), kCount - freed);
}

/// A pose far from the one the state was taken at: moved, turned by 0.7 rad, moving.
EnclosureState elsewhere() {
    EnclosureState e;
    e.position_m = Eigen::Vector3d(-0.3, 0.2, 0.05);
    e.rotation =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
    e.velocity_m_s = Eigen::Vector3d(0.01, -0.02, 0.03);
    e.angular_velocity_rad_s = Eigen::Vector3d(0.5, -0.2, 0.1);
    return e;
}

TEST(SolverState, RestoredAtAnotherPoseKeepsTheEnclosureFrameStateAndTurnsTheSprings) {
    const SolverOptions o = bed_options(TangentialLaw::coulomb_spring);
    Solver a(o, poured_bed(), shaking(0.0));
    shake(a, 0, kCapture);
    const SolverState s = a.state();
    const EnclosureState e1 = elsewhere();
    const Solver b(o, s, e1);
    // Positions, velocities relative to the enclosure and spins in its axes are kept (to
    // rounding of the two frame changes).
    const ParticleSet before = local_particles(s), after = b.local_snapshot();
    for (std::size_t i = 0; i < before.positions_m.size(); ++i) {
        EXPECT_LT((after.positions_m[i] - before.positions_m[i]).norm(), 1e-15) << i;
        EXPECT_LT((after.velocities_m_s[i] - before.velocities_m_s[i]).norm(), 1e-15) << i;
        EXPECT_LT((after.angular_velocities_rad_s[i] - before.angular_velocities_rad_s[i]).norm(),
                  1e-12)
            << i;
    }
    // The particles are placed exactly as a solver built from the enclosure-frame particles.
    const Solver rebuilt(o, before, e1);
    expect_same_particles(rebuilt, b);
    // The springs, seen from the enclosure, are the same: they turned with it.
    const SolverState moved = b.state();
    ASSERT_EQ(moved.pair_histories.size(), s.pair_histories.size());
    ASSERT_EQ(moved.wall_histories.size(), s.wall_histories.size());
    auto local = [](const EnclosureState& e, const Eigen::Vector3d& xi) -> Eigen::Vector3d {
        return e.rotation.transpose() * xi;
    };
    double largest = 0.0;
    for (const auto& h : s.pair_histories) largest = std::max(largest, h.history_m.norm());
    for (const auto& h : s.wall_histories) largest = std::max(largest, h.history_m.norm());
    ASSERT_GT(largest, 0.0);
    for (std::size_t k = 0; k < s.pair_histories.size(); ++k) {
        EXPECT_EQ(moved.pair_histories[k].i, s.pair_histories[k].i);
        EXPECT_EQ(moved.pair_histories[k].j, s.pair_histories[k].j);
        EXPECT_LT((local(e1, moved.pair_histories[k].history_m) -
                   local(s.enclosure, s.pair_histories[k].history_m))
                      .norm(),
                  1e-14 * largest)
            << k;
    }
    for (std::size_t k = 0; k < s.wall_histories.size(); ++k) {
        EXPECT_EQ(moved.wall_histories[k].particle, s.wall_histories[k].particle);
        EXPECT_EQ(moved.wall_histories[k].wall, s.wall_histories[k].wall);
        EXPECT_LT((local(e1, moved.wall_histories[k].history_m) -
                   local(s.enclosure, s.wall_histories[k].history_m))
                      .norm(),
                  1e-14 * largest)
            << k;
    }
    EXPECT_EQ(b.time(), a.time());
}

/// The poured bed at rest in a static enclosure: its contacts hold friction springs (a random
/// packing carries tangential forces). Restored in an enclosure moved and turned by q, gravity
/// turned alike, it gives the same wall force and moment turned by q; without its springs it
/// does not (it starts to settle anew).
TEST(SolverState, RestingBedRestoredInATurnedEnclosureGivesTheTurnedWallForce) {
    SolverOptions o = bed_options(TangentialLaw::coulomb_spring);
    o.contact.particle_particle.restitution = 0.3;  // comes to rest sooner
    o.contact.particle_wall.restitution = 0.3;
    const Eigen::Vector3d g = o.gravity_m_s2;
    Solver a(o, poured_bed());
    for (int k = 0; k < 10000; ++k) a.step(kDt);  // the springs build up, the bed rests
    const SolverState s = a.state();

    const Eigen::Matrix3d q =
        Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
    SolverOptions turned = o;
    turned.gravity_m_s2 = q * g;
    EnclosureState e1;
    e1.rotation = q;
    e1.position_m = Eigen::Vector3d(0.02, -0.01, 0.3);
    Solver b(turned, s, e1);
    SolverState dropped = s;
    dropped.pair_histories.clear();
    dropped.wall_histories.clear();
    Solver c(turned, dropped, e1);
    double weight = 0.0;
    for (double im : a.particles().inv_mass) weight += kStandardGravity / im;
    double off_b = 0.0, off_c = 0.0, moment_off_b = 0.0;
    for (int k = 0; k < 2000; ++k) {
        a.step(kDt);
        b.step(kDt);
        c.step(kDt);
        off_b = std::max(off_b, (b.wall_force() - q * a.wall_force()).norm());
        off_c = std::max(off_c, (c.wall_force() - q * a.wall_force()).norm());
        moment_off_b = std::max(moment_off_b, (b.wall_moment() - q * a.wall_moment()).norm());
    }
    // at rest: the walls carry the bed's weight
    EXPECT_LT((a.wall_force() - weight / kStandardGravity * g).norm(), 1e-6 * weight);
    EXPECT_LT(off_b, 1e-9 * weight);
    EXPECT_LT(moment_off_b, 1e-9 * weight * o.enclosure.length_x_m);
    EXPECT_GT(off_c, 0.01 * weight);
}

TEST(SolverState, StatesThatDoNotFitAreRejected) {
    const SolverOptions o = bed_options(TangentialLaw::coulomb_spring);
    Solver a(o, poured_bed());
    for (int k = 0; k < 10; ++k) a.step(kDt);
    const SolverState good = a.state();
    ASSERT_FALSE(good.pair_histories.empty());
    auto rejected = [&](SolverState s, const std::string& part) {
        try {
            Solver b(o, s, s.enclosure);
            ADD_FAILURE() << "accepted a state with " << part;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    SolverState s = good;
    s.velocities_m_s.pop_back();
    rejected(s, "velocities");
    s = good;
    s.positions_m.pop_back();
    s.velocities_m_s.pop_back();
    s.angular_velocities_rad_s.pop_back();
    s.radii_m.pop_back();
    rejected(s, "particles.count");
    s = good;
    std::swap(s.pair_histories.front().i, s.pair_histories.front().j);
    rejected(s, "needs i < j");
    s = good;
    s.pair_histories.push_back(s.pair_histories.front());
    rejected(s, "given twice");
    s = good;
    s.wall_histories.push_back({kCount, 0, Eigen::Vector3d::Zero()});
    rejected(s, "no such particle");
    s = good;
    s.time_s = -1.0;
    rejected(s, "time_s");
}

}  // namespace
}  // namespace sb::dem

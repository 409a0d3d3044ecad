// Energy balance of a shaken damper: wall work = change of mechanical energy + dissipation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "dem/energy_periods.hpp"
#include "dem/setup.hpp"
#include "dem/solver.hpp"
#include "test_helpers.hpp"

namespace sb::dem {
namespace {

/// The brief's requirement per period.
constexpr double kBalancePerPeriodTolerance = 0.005;

EnclosureState axial_shake(double t, double amplitude_m, double w) {
    EnclosureState e;
    e.position_m = Eigen::Vector3d(0, 0, amplitude_m * std::sin(w * t));
    e.velocity_m_s = Eigen::Vector3d(0, 0, amplitude_m * w * std::cos(w * t));
    return e;
}

class EnergyBalance : public ::testing::TestWithParam<TangentialLaw> {};

TEST_P(EnergyBalance, ClosesWithinHalfAPercentPerPeriod) {
    SolverOptions o = test::paper000_options();
    o.contact.tangential = GetParam();
    o.particles.count = 60;
    const ParticleSet p = fill_random(o, 11);
    const double f = 20.0, w = kTwoPi * f, a = 3.0 * kStandardGravity;
    const double amp = a / (w * w);
    const double dt = 5e-6;
    const int per_period = static_cast<int>(std::lround(1.0 / (f * dt)));
    Solver s(o, p, axial_shake(0.0, amp, w));
    EnergyPeriods periods(s);
    int k = 0;
    double worst = 0.0;
    for (int period = 0; period < 4; ++period) {
        for (int q = 0; q < per_period; ++q, ++k) {
            s.set_enclosure_state(axial_shake(k * dt, amp, w));
            s.step(dt);
        }
        const EnergyInterval e = periods.end_period(s);
        if (period == 0) continue;  // start-up from rest
        EXPECT_GT(e.dissipated(), 0.0);
        worst = std::max(worst, std::abs(e.balance_error()) / e.dissipated());
        EXPECT_LT(std::abs(e.balance_error()), kBalancePerPeriodTolerance * e.dissipated())
            << "period " << period << " work " << e.wall_work << " dissipated " << e.dissipated();
    }
    RecordProperty("worst_relative_balance_error", std::to_string(worst));
}

TEST(WallWork, IsMinusThePowerOfTheWallForceAndMomentOnTheMovingEnclosure) {
    // The ledger adds f.v_wall(x_c) + m_r.omega over every wall contact; the walls move
    // rigidly, so the sum is -(F.v_e + M_e.omega) with the step's wall force and moment about
    // the enclosure origin: one product per step instead of a pass over the contacts
    // (the characterisation's power, bench/characterization.cpp). Shaken along its axis while
    // rocking about x, so that the moment's term counts.
    SolverOptions o = test::paper000_options();
    o.contact.tangential = TangentialLaw::coulomb_spring;
    o.particles.count = 60;
    const double f = 20.0, w = kTwoPi * f, a = 3.0 * kStandardGravity;
    const double amp = a / (w * w), tilt = 0.05;  // rad
    const auto pose = [&](double t) {
        EnclosureState e = axial_shake(t, amp, w);
        e.rotation =
            Eigen::AngleAxisd(tilt * std::sin(w * t), Eigen::Vector3d::UnitX()).toRotationMatrix();
        e.angular_velocity_rad_s = Eigen::Vector3d(tilt * w * std::cos(w * t), 0.0, 0.0);
        return e;
    };
    Solver s(o, fill_random(o, 11), pose(0.0));
    const double dt = 5e-6;
    double from_load = 0.0, moment_part = 0.0;
    for (int k = 0; k < 3 * static_cast<int>(std::lround(1.0 / (f * dt))); ++k) {
        const EnclosureState e = pose(k * dt);
        s.set_enclosure_state(e);
        s.step(dt);
        from_load -=
            (s.wall_force().dot(e.velocity_m_s) + s.wall_moment().dot(e.angular_velocity_rad_s)) *
            dt;
        moment_part -= s.wall_moment().dot(e.angular_velocity_rad_s) * dt;
    }
    const double ledger = s.energy().wall_work;
    ASSERT_GT(std::abs(ledger), 0.0);
    EXPECT_GT(std::abs(moment_part), 1e-3 * std::abs(ledger));  // the rocking does work
    EXPECT_NEAR(from_load, ledger, 1e-9 * std::abs(ledger));    // the same sum, rounding apart
}

/// 40 spheres in paper 000's cavity shaken along its axis at 25 Hz and 3 g, the energy split
/// over `layers` layers.
struct ShakenBed {
    static constexpr double kFrequencyHz = 25.0;
    static constexpr double kDt = 5e-6;
    static constexpr int kStepsPerPeriod = 8000;  // 1 / (f dt)
    static SolverOptions options(int layers) {
        SolverOptions o = test::paper000_options();
        o.particles.count = 40;
        o.energy_layers = layers;
        return o;
    }
    ShakenBed(int layers, std::uint64_t seed)
        : solver(options(layers), fill_random(options(layers), seed),
                 axial_shake(0.0, amplitude_m, w)) {}
    /// Step k of the run: the enclosure at time k dt, then one step.
    void step(int k) {
        solver.set_enclosure_state(axial_shake(k * kDt, amplitude_m, w));
        solver.step(kDt);
    }
    double w = kTwoPi * kFrequencyHz;
    double amplitude_m = 3.0 * kStandardGravity / (w * w);
    Solver solver;
};

TEST(EnergyPeriods, PeriodsAddUpToTheWholeRunPerTermAndPerLayer) {
    ShakenBed bed(3, 12);
    Solver& s = bed.solver;
    const double f = ShakenBed::kFrequencyHz;
    const EnergyLedger start = s.energy();
    EnergyPeriods periods(s);
    int k = 0;
    for (int period = 0; period < 3; ++period) {
        for (int q = 0; q < ShakenBed::kStepsPerPeriod; ++q, ++k) bed.step(k);
        periods.end_period(s);
    }
    const EnergyInterval whole = energy_between(start, s.energy(), s.time());
    EnergyInterval sum;
    sum.layer_dissipation.assign(3, 0.0);
    for (const EnergyInterval& e : periods.periods()) {
        EXPECT_NEAR(e.duration_s, 1.0 / f, 1e-12);
        sum.duration_s += e.duration_s;
        sum.wall_work += e.wall_work;
        sum.normal_damping += e.normal_damping;
        sum.friction += e.friction;
        sum.rolling += e.rolling;
        sum.mechanical_change += e.mechanical_change;
        for (int l = 0; l < 3; ++l) sum.layer_dissipation[l] += e.layer_dissipation[l];
    }
    ASSERT_EQ(periods.periods().size(), 3u);
    EXPECT_GT(whole.dissipated(), 0.0);
    // differences of cumulative sums add up to the whole up to rounding
    const double tol = 1e-12 * (std::abs(whole.wall_work) + whole.dissipated());
    EXPECT_NEAR(sum.wall_work, whole.wall_work, tol);
    EXPECT_NEAR(sum.normal_damping, whole.normal_damping, tol);
    EXPECT_NEAR(sum.friction, whole.friction, tol);
    EXPECT_NEAR(sum.rolling, whole.rolling, tol);
    EXPECT_NEAR(sum.mechanical_change, whole.mechanical_change, tol);
    double layers = 0.0;
    for (int l = 0; l < 3; ++l) {
        EXPECT_NEAR(sum.layer_dissipation[l], whole.layer_dissipation[l], tol);
        layers += whole.layer_dissipation[l];
    }
    EXPECT_NEAR(layers, whole.dissipated(), tol);
    EXPECT_NEAR(whole.dissipated_power_w(), whole.dissipated() / (3.0 / f), 1e-12);
    SolverOptions untracked = ShakenBed::options(3);
    untracked.track_energy = false;
    EXPECT_THROW(EnergyPeriods(Solver(untracked, fill_random(untracked, 12))),
                 std::invalid_argument);
}

// The layers' agitation counts the motion relative to the walls only: a sphere riding a
// moving enclosure adds nothing, one moving and spinning inside it adds its own kinetic energy
// for as long as it moves, in the layer of its centre.
TEST(LayerAgitation, IsTheKineticEnergyRelativeToTheWallsInTheLayerOfTheCentre) {
    SolverOptions o = test::paper000_options();
    o.gravity_m_s2 = Eigen::Vector3d::Zero();
    o.particles.count = 2;
    o.energy_layers = 4;  // along local z (no gravity): 6.25 mm slabs of the 25 mm cavity
    ParticleSet p;
    p.positions_m = {{0.0, 0.0, 3e-3}, {0.0, 0.0, 22e-3}};
    p.radii_m = {1.5e-3, 1.5e-3};
    const Eigen::Vector3d u(0.01, 0.0, 0.0), spin(0.0, 0.0, 50.0);
    p.velocities_m_s = {u, Eigen::Vector3d::Zero()};
    p.angular_velocities_rad_s = {spin, Eigen::Vector3d::Zero()};
    const Eigen::Vector3d velocity(0.2, 0.0, 0.1);
    auto pose = [&](double t) {
        EnclosureState e;
        e.position_m = velocity * t;
        e.velocity_m_s = velocity;
        return e;
    };
    Solver s(o, p, pose(0.0));
    const double dt = 1e-5;
    const int steps = 1000;
    for (int k = 0; k < steps; ++k) {
        s.set_enclosure_state(pose(k * dt));
        s.step(dt);
    }
    ASSERT_EQ(s.contact_count(), 0u);
    const double m = 1.0 / s.particles().inv_mass[0];
    const double inertia = 1.0 / s.particles().inv_inertia[0];
    const double own = 0.5 * m * u.squaredNorm() + 0.5 * inertia * spin.squaredNorm();
    const EnergyLedger e = s.energy();
    ASSERT_EQ(e.layer_kinetic_time.size(), 4u);
    EXPECT_NEAR(e.layer_kinetic_time[0], own * steps * dt, 1e-12 * own * steps * dt);
    for (int l = 1; l < 4; ++l) EXPECT_EQ(e.layer_kinetic_time[static_cast<std::size_t>(l)], 0.0);
    EXPECT_NEAR(s.relative_kinetic_energy(), own, 1e-12 * own);
    // the laboratory's kinetic energy carries both spheres' ride
    EXPECT_GT(e.kinetic_translational, 0.5 * m * velocity.squaredNorm() * 2.0);
    const EnergyInterval interval = energy_between(EnergyLedger{}, e, steps * dt);
    ASSERT_EQ(interval.layer_kinetic_mean.size(), 4u);
    EXPECT_NEAR(interval.layer_kinetic_mean[0], own, 1e-12 * own);
}

// Over a shaken bed the layers' means add up to the mean over the steps of the relative
// kinetic energy, computed here from the particles and the walls' motion after every step.
TEST(LayerAgitation, AddsUpToTheBedsRelativeKineticEnergyAveragedOverTheSteps) {
    ShakenBed bed(5, 13);
    const Solver& s = bed.solver;
    const double dt = ShakenBed::kDt;
    const int steps = 2 * ShakenBed::kStepsPerPeriod;
    const EnergyLedger start = s.energy();
    double integral = 0.0;
    for (int k = 0; k < steps; ++k) {
        bed.step(k);
        const ParticleState& x = s.particles();
        const EnclosureState& walls = s.enclosure_state();
        for (std::size_t i = 0; i < x.size(); ++i) {
            const Eigen::Vector3d v = x.v[i] - walls.velocity_m_s -
                                      walls.angular_velocity_rad_s.cross(x.x[i] - walls.position_m);
            const Eigen::Vector3d spin = x.w[i] - walls.angular_velocity_rad_s;
            integral += (0.5 * v.squaredNorm() / x.inv_mass[i] +
                         0.5 * spin.squaredNorm() / x.inv_inertia[i]) *
                        dt;
        }
    }
    const EnergyInterval whole = energy_between(start, s.energy(), steps * dt);
    double sum = 0.0;
    int moving = 0;
    for (double layer : whole.layer_kinetic_mean) {
        EXPECT_GE(layer, 0.0);
        sum += layer;
        moving += layer > 0.0 ? 1 : 0;
    }
    const double mean = integral / (steps * dt);
    ASSERT_GT(mean, 0.0);
    EXPECT_NEAR(sum, mean, 1e-12 * mean);
    EXPECT_GE(moving, 2);  // at 3 g the bed is spread over several layers
}

INSTANTIATE_TEST_SUITE_P(Friction, EnergyBalance,
                         ::testing::Values(TangentialLaw::directional_coulomb,
                                           TangentialLaw::coulomb_spring),
                         [](const auto& p_info) {
                             return p_info.param == TangentialLaw::directional_coulomb
                                        ? std::string("DirectionalCoulomb")
                                        : std::string("CoulombSpring");
                         });

}  // namespace
}  // namespace sb::dem

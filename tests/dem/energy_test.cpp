// Energy balance of a shaken damper: wall work = change of mechanical energy + dissipation.
#include <gtest/gtest.h>

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

TEST(EnergyPeriods, PeriodsAddUpToTheWholeRunPerTermAndPerLayer) {
    SolverOptions o = test::paper000_options();
    o.particles.count = 40;
    o.energy_layers = 3;
    const ParticleSet p = fill_random(o, 12);
    const double f = 25.0, w = kTwoPi * f, amp = 3.0 * kStandardGravity / (w * w), dt = 5e-6;
    const int per_period = static_cast<int>(std::lround(1.0 / (f * dt)));
    Solver s(o, p, axial_shake(0.0, amp, w));
    const EnergyLedger start = s.energy();
    EnergyPeriods periods(s);
    int k = 0;
    for (int period = 0; period < 3; ++period) {
        for (int q = 0; q < per_period; ++q, ++k) {
            s.set_enclosure_state(axial_shake(k * dt, amp, w));
            s.step(dt);
        }
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
    o.track_energy = false;
    EXPECT_THROW(EnergyPeriods(Solver(o, p)), std::invalid_argument);
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

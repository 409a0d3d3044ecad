// Energy balance of a shaken damper: wall work = change of mechanical energy + dissipation.
#include <gtest/gtest.h>

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
    int k = 0;
    double worst = 0.0;
    for (int period = 0; period < 4; ++period) {
        const EnergyLedger before = s.energy();
        for (int q = 0; q < per_period; ++q, ++k) {
            s.set_enclosure_state(axial_shake(k * dt, amp, w));
            s.step(dt);
        }
        const EnergyLedger after = s.energy();
        const double work = after.wall_work - before.wall_work;
        const double dissipated = after.dissipated() - before.dissipated();
        const double error = after.balance_error() - before.balance_error();
        if (period == 0) continue;  // start-up from rest
        EXPECT_GT(dissipated, 0.0);
        worst = std::max(worst, std::abs(error) / dissipated);
        EXPECT_LT(std::abs(error), kBalancePerPeriodTolerance * dissipated)
            << "period " << period << " work " << work << " dissipated " << dissipated;
    }
    RecordProperty("worst_relative_balance_error", std::to_string(worst));
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

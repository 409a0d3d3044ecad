// With all dissipation off, the total energy of a shaken enclosure drifts < 0.1 % over 1e6 steps.
#include <gtest/gtest.h>

#include "dem/setup.hpp"
#include "dem/solver.hpp"
#include "test_helpers.hpp"

namespace sb::dem {
namespace {

/// The brief's requirement.
constexpr double kDriftTolerance = 1e-3;

TEST(EnergyDrift, ConservativeShakenEnclosureDriftsLessThanATenthOfAPercent) {
    SolverOptions o = test::paper000_options();
    o.particles.count = 20;
    o.contact.damping = DampingLaw::none;
    o.contact.tangential = TangentialLaw::none;
    o.contact.rolling = RollingLaw::none;
    o.contact.particle_particle = {1.0, 0.0, 0.0};
    o.contact.particle_wall = {1.0, 0.0, 0.0};
    const ParticleSet p = fill_random(o, 4);
    const double f = 20.0, w = kTwoPi * f, a = 3.0 * kStandardGravity, amp = a / (w * w);
    auto shake = [&](double t) {
        EnclosureState e;
        e.position_m = Eigen::Vector3d(0, 0, amp * std::sin(w * t));
        e.velocity_m_s = Eigen::Vector3d(0, 0, amp * w * std::cos(w * t));
        return e;
    };
    Solver s(o, p, shake(0.0));
    const double dt = 5e-6;
    double mean_kinetic = 0.0, worst = 0.0;
    const int steps = 1000000;
    for (int k = 0; k < steps; ++k) {
        s.set_enclosure_state(shake(k * dt));
        s.step(dt);
        if (k % 1000 == 999) {
            const EnergyLedger e = s.energy();
            mean_kinetic += e.kinetic_translational + e.kinetic_rotational;
            worst = std::max(worst, std::abs(e.balance_error()));
        }
    }
    mean_kinetic /= steps / 1000;
    const EnergyLedger e = s.energy();
    RecordProperty("wall_work_j", std::to_string(e.wall_work));
    RecordProperty("relative_drift", std::to_string(std::abs(e.balance_error()) / mean_kinetic));
    EXPECT_LT(std::abs(e.balance_error()), kDriftTolerance * mean_kinetic)
        << "balance error " << e.balance_error() << " J, worst " << worst << " J, mean KE "
        << mean_kinetic << " J";
}

}  // namespace
}  // namespace sb::dem

// A sphere launched sliding ends rolling at 5/7 of its speed; with rolling resistance it then
// decelerates at (5/7) mu_r g.
#include <gtest/gtest.h>

#include "dem/solver.hpp"
#include "test_helpers.hpp"

namespace sb::dem {
namespace {

using test::free_box_options;
using test::particles_at;

/// Slip ends within the regularisation speed (1e-4 m/s) of a 0.5 m/s launch: 0.02 % plus
/// the normal bounce transient.
constexpr double kFiveSevenTolerance = 0.003;
/// The fitted deceleration averages out the small normal vibration of the contact.
constexpr double kDecelerationTolerance = 0.01;

constexpr double kR = 1.5e-3;

SolverOptions plane_options(TangentialLaw t, double mu_r) {
    SolverOptions o = free_box_options(1, NormalLaw::hooke);
    o.gravity_m_s2 = Eigen::Vector3d(0, 0, -kStandardGravity);
    o.contact.tangential = t;
    o.contact.rolling = mu_r > 0 ? RollingLaw::constant_torque : RollingLaw::none;
    o.contact.particle_wall = {0.3, 0.3, mu_r};
    return o;
}

class SlidingSphere : public ::testing::TestWithParam<TangentialLaw> {};

TEST_P(SlidingSphere, EndsRollingAtFiveSeventhsOfItsSpeed) {
    const double v0 = 0.5, m = 7800.0 * 4.0 / 3.0 * kPi * kR * kR * kR;
    const double delta = m * kStandardGravity / 1e5;
    Solver s(plane_options(GetParam(), 0.0),
             particles_at({{-0.045, 0, kR - delta}}, kR, {{v0, 0, 0}}));
    for (int k = 0; k < 50000; ++k) s.step(2e-6);  // 0.1 s, slip ends at about 0.05 s
    const auto& p = s.particles();
    EXPECT_NEAR(p.v[0].x(), 5.0 / 7.0 * v0, kFiveSevenTolerance * v0);
    // rolling without slip, up to the undamped oscillation of a tangential spring
    EXPECT_NEAR(p.w[0].y() * kR, p.v[0].x(), 1e-3 * v0);
}

TEST_P(SlidingSphere, RollingResistanceDeceleratesAtFiveSeventhsMuRG) {
    const double mu_r = 0.05, v0 = 0.5, m = 7800.0 * 4.0 / 3.0 * kPi * kR * kR * kR;
    const double delta = m * kStandardGravity / 1e5;
    // launched rolling, so the sliding phase does not blur the fit
    ParticleSet ps = particles_at({{-0.045, 0, kR - delta}}, kR, {{v0, 0, 0}});
    ps.angular_velocities_rad_s = {{0, v0 / kR, 0}};
    Solver s(plane_options(GetParam(), mu_r), ps);
    const double dt = 2e-6;
    for (int k = 0; k < 10000; ++k) s.step(dt);
    const double v1 = s.particles().v[0].x(), t1 = s.time();
    for (int k = 0; k < 50000; ++k) s.step(dt);
    const double v2 = s.particles().v[0].x(), t2 = s.time();
    const double decel = (v1 - v2) / (t2 - t1);
    const double expected = 5.0 / 7.0 * mu_r * kStandardGravity;
    EXPECT_NEAR(decel, expected, kDecelerationTolerance * expected);
}

/// The whole sequence in one run: launched sliding without spin with rolling resistance on,
/// the sphere decelerates at mu g while friction spins it up against the rolling torque, rolls
/// from t1 = v0 / (g (mu + 5/2 (mu - mu_r))) at v1 = 5 (mu - mu_r) / (7 mu - 5 mu_r) v0 (5/7 v0
/// for mu_r = 0), and then decelerates at (5/7) mu_r g.
TEST_P(SlidingSphere, LaunchedSlidingEndsRollingThenDeceleratesAtFiveSeventhsMuRG) {
    const double mu = 0.3, mu_r = 0.05, v0 = 0.5, g = kStandardGravity;
    const double m = 7800.0 * 4.0 / 3.0 * kPi * kR * kR * kR;
    const double delta = m * g / 1e5;
    Solver s(plane_options(GetParam(), mu_r),
             particles_at({{-0.045, 0, kR - delta}}, kR, {{v0, 0, 0}}));
    // sliding: m dv/dt = -mu m g; I dw/dt = (mu - mu_r) m g R with I = 2/5 m R^2
    const double t1 = v0 / (g * (mu + 2.5 * (mu - mu_r)));
    const double v1 = 5.0 * (mu - mu_r) / (7.0 * mu - 5.0 * mu_r) * v0;
    const double rolling_decel = 5.0 / 7.0 * mu_r * g;
    const double dt = 2e-6;
    auto run_to = [&](double t) {
        while (s.time() < t - 0.5 * dt) s.step(dt);
    };
    // mid-slide: still slipping, speed v0 - mu g t
    const double ts = 0.5 * t1;
    run_to(ts);
    const auto& p = s.particles();
    EXPECT_NEAR(p.v[0].x(), v0 - mu * g * ts, kFiveSevenTolerance * v0);
    EXPECT_GT(p.v[0].x() - p.w[0].y() * kR, 0.1 * v0);
    // rolling: no slip, on the line v1 - (5/7) mu_r g (t - t1)
    const double ta = t1 + 0.02, tb = t1 + 0.12;
    run_to(ta);
    const double va = p.v[0].x();
    EXPECT_NEAR(p.w[0].y() * kR, va, 1e-3 * v0);
    EXPECT_NEAR(va, v1 - rolling_decel * (ta - t1), kFiveSevenTolerance * v0);
    run_to(tb);
    const double vb = p.v[0].x();
    EXPECT_NEAR(p.w[0].y() * kR, vb, 1e-3 * v0);
    EXPECT_NEAR((va - vb) / (tb - ta), rolling_decel, kDecelerationTolerance * rolling_decel);
    RecordProperty("transition_speed_ratio", std::to_string((va + rolling_decel * (ta - t1)) / v0));
}

INSTANTIATE_TEST_SUITE_P(Friction, SlidingSphere,
                         ::testing::Values(TangentialLaw::directional_coulomb,
                                           TangentialLaw::coulomb_spring),
                         [](const auto& p_info) {
                             return p_info.param == TangentialLaw::directional_coulomb
                                        ? std::string("DirectionalCoulomb")
                                        : std::string("CoulombSpring");
                         });

}  // namespace
}  // namespace sb::dem

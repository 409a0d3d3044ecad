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

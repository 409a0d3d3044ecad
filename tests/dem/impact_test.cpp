// Normal impacts against closed forms: restitution and contact duration, Hooke and Hertz,
// particle-wall and particle-particle; the viscoelastic restitution against its speed.
#include <gtest/gtest.h>

#include "dem/setup.hpp"
#include "dem/solver.hpp"
#include "test_helpers.hpp"

namespace sb::dem {
namespace {

using test::free_box_options;
using test::particles_at;

/// The brief's requirement for the measured restitution.
constexpr double kRestitutionTolerance = 0.01;
/// The contact time is resolved to dt = t_c / 400 plus the explicit integrator's phase error.
constexpr double kContactTimeTolerance = 0.01;

struct ImpactResult {
    double restitution = 0.0;
    double contact_time_s = 0.0;
};

constexpr double kRadius = 1.5e-3;
constexpr double kSpeed = 0.5;

double sphere_mass() { return 7800.0 * 4.0 / 3.0 * kPi * kRadius * kRadius * kRadius; }

/// One impact at `speed` with the contact law of `o` (wall = true: one sphere onto the bottom;
/// else two spheres head-on), stepped at dt until the contact ends.
ImpactResult impact(const SolverOptions& o, bool wall, double speed, double dt,
                    double gap_m = 1e-6) {
    const ParticleSet p = wall ? particles_at({{0, 0, kRadius + gap_m}}, kRadius, {{0, 0, -speed}})
                               : particles_at({{0, 0, 0.05}, {0, 0, 0.05 + 2 * kRadius + gap_m}},
                                              kRadius, {{0, 0, 0.5 * speed}, {0, 0, -0.5 * speed}});
    Solver s(o, p);
    ImpactResult r;
    bool touched = false;
    for (int k = 0; k < 10000000; ++k) {
        s.step(dt);
        if (s.contact_count() > 0) {
            touched = true;
            r.contact_time_s += dt;
        } else if (touched) {
            break;
        }
    }
    EXPECT_TRUE(touched);
    const auto& v = s.particles().v;
    r.restitution = wall ? v[0].z() / speed : (v[1].z() - v[0].z()) / speed;
    return r;
}

/// The impact at kSpeed with restitution e (e = 1: no damping) and the normal law `law`.
ImpactResult run_impact(NormalLaw law, double e, bool wall, double dt) {
    SolverOptions o = free_box_options(wall ? 1 : 2, law);
    o.contact.particle_particle.restitution = e;
    o.contact.particle_wall.restitution = e;
    if (e >= 1.0) o.contact.damping = DampingLaw::none;
    return impact(o, wall, kSpeed, dt);
}

struct Case {
    NormalLaw law;
    bool wall;
};

class NormalImpact : public ::testing::TestWithParam<Case> {};

TEST_P(NormalImpact, MeasuredRestitutionEqualsTheSetOne) {
    const auto c = GetParam();
    for (double e : {0.5, 0.9}) {
        const double tc = 1e-4;  // coarse guess; the step is far below any t_c here
        const ImpactResult r = run_impact(c.law, e, c.wall, tc / 400.0);
        EXPECT_NEAR(r.restitution, e, kRestitutionTolerance * e) << "e = " << e;
    }
}

TEST_P(NormalImpact, ContactDurationFollowsTheory) {
    const auto c = GetParam();
    const double m_eff = c.wall ? sphere_mass() : 0.5 * sphere_mass();
    double expected = 0.0;
    double e = 0.9;
    if (c.law == NormalLaw::hooke) {
        expected = hooke_contact_time(m_eff, 1e5, e);  // pi / sqrt(k/m - (c/2m)^2)
    } else {
        e = 1.0;  // Hertz: the undamped closed form
        const double r_eff = c.wall ? kRadius : 0.5 * kRadius;
        const double nu = 0.3, young = 210e9;
        const double e_star = c.wall ? young / (2 * (1 - nu * nu)) : young / (2 * (1 - nu * nu));
        // paper-style approximation 2.87 (m*^2 / (R* E*^2 v))^{1/5}
        const double approx =
            2.87 * std::pow(m_eff * m_eff / (r_eff * e_star * e_star * kSpeed), 0.2);
        expected = hertz_contact_time(m_eff, 4.0 / 3.0 * e_star * std::sqrt(r_eff), kSpeed);
        EXPECT_NEAR(expected, approx, 0.005 * approx);
    }
    const ImpactResult r = run_impact(c.law, e, c.wall, expected / 400.0);
    EXPECT_NEAR(r.contact_time_s, expected, kContactTimeTolerance * expected);
}

INSTANTIATE_TEST_SUITE_P(
    HookeAndHertz, NormalImpact,
    ::testing::Values(Case{NormalLaw::hooke, true}, Case{NormalLaw::hooke, false},
                      Case{NormalLaw::hertz, true}, Case{NormalLaw::hertz, false}),
    [](const auto& p_info) {
        return std::string(p_info.param.law == NormalLaw::hooke ? "Hooke" : "Hertz") +
               (p_info.param.wall ? "ParticleWall" : "ParticleParticle");
    });

/// The viscoelastic dashpot's restitution to first order in its dissipation: the energy lost on
/// the undamped Hertz path, 1 - e = dE / (m* v^2) with dE = 2 int 3/2 A k sqrt(delta) ddelta_dt
/// ddelta = 3 A k delta_max^(3/2) v (2/5) B(3/5, 3/2), delta_max = (5 m* v^2 / 4 k)^(2/5); that
/// is 1 - e = 1.73018 A (k/m*)^(2/5) v^(1/5) = 1.15344 beta v^(1/5), beta = 3/2 A (k/m*)^(2/5)
/// (the first coefficient of Ramirez, Poeschel, Brilliantov & Schwager, PRE 60, 1999). The
/// next term, of relative size about 0.7 beta v^(1/5), is the order of what is left.
double viscoelastic_first_order_loss(double a_s, double k, double m_eff, double speed) {
    const double beta_function =
        std::tgamma(0.6) * std::tgamma(1.5) / std::tgamma(2.1);  // B(3/5, 3/2)
    const double c1 = 3.0 * 0.4 * beta_function * std::pow(1.25, 0.6);
    return c1 * a_s * std::pow(k / m_eff, 0.4) * std::pow(speed, 0.2);
}

TEST(ViscoelasticImpact, TheRestitutionFallsWithTheImpactSpeedAsTheFifthRoot) {
    const double nu = 0.3, young = 210e9;
    const double e_star = young / (2 * (1 - nu * nu));
    for (const bool wall : {true, false}) {
        const double m_eff = wall ? sphere_mass() : 0.5 * sphere_mass();
        const double r_eff = wall ? kRadius : 0.5 * kRadius;
        const double k = 4.0 / 3.0 * e_star * std::sqrt(r_eff);
        const double a_s = 2e-8;  // beta v^(1/5) about 0.01 at 1 m/s
        double loss[2];
        const double speeds[2] = {0.1, 3.2};
        for (int i = 0; i < 2; ++i) {
            SolverOptions o = free_box_options(wall ? 1 : 2, NormalLaw::hertz);
            o.contact.damping = DampingLaw::viscoelastic;
            o.contact.particle_particle.dissipative_constant_s = a_s;
            o.contact.particle_wall.dissipative_constant_s = a_s;
            const double v = speeds[i];
            const double dt = hertz_contact_time(m_eff, k, v) / 2000.0;
            loss[i] = 1.0 - impact(o, wall, v, dt, 1e-7).restitution;
            const double expected = viscoelastic_first_order_loss(a_s, k, m_eff, v);
            EXPECT_NEAR(loss[i], expected, 0.02 * expected) << (wall ? "wall " : "pair ") << v;
        }
        // 32 times the speed, twice the loss: v^(1/5).
        EXPECT_NEAR(loss[1] / loss[0], 2.0, 0.04) << (wall ? "wall" : "pair");
    }
}

TEST(ViscousImpact, ADashpotGivenDirectlyRestitutesAsTheSpringDashpotOfItsDampingRatio) {
    // Hooke, k = 1e5 N/m, a dashpot c given directly: zeta = c / (2 sqrt(k m*)), so a sphere
    // on a wall (m* = m) and two spheres head-on (m* = m / 2) rebound differently, each as
    // the spring-dashpot without tensile force of its own zeta (Schwager & Poeschel 2007).
    const double k = 1e5;
    const double c = 0.2 * std::sqrt(k * sphere_mass());  // zeta 0.1 on the wall
    for (const bool wall : {true, false}) {
        SolverOptions o = free_box_options(wall ? 1 : 2, NormalLaw::hooke);
        o.contact.damping = DampingLaw::viscous;
        o.contact.particle_particle.dashpot_n_s_per_m = c;
        o.contact.particle_wall.dashpot_n_s_per_m = c;
        const double m_eff = wall ? sphere_mass() : 0.5 * sphere_mass();
        const double zeta = c / (2.0 * std::sqrt(k * m_eff));
        const double tc = kPi * std::sqrt(m_eff / k);
        const double e = impact(o, wall, kSpeed, tc / 400.0).restitution;
        EXPECT_NEAR(e, linear_restitution_from_zeta(zeta), 2e-3) << (wall ? "wall" : "pair");
    }
}

/// One sphere launched along +x (direction 1) or -x (-1) at kSpeed from x0 into a wall or a
/// rod: its restitution and contact time.
ImpactResult launched_impact(const SolverOptions& o, const Eigen::Vector3d& x0, double direction,
                             double dt) {
    Solver s(o, particles_at({x0}, kRadius, {{direction * kSpeed, 0, 0}}));
    ImpactResult r;
    bool touched = false;
    for (int k = 0; k < 1000000; ++k) {
        s.step(dt);
        if (s.contact_count() > 0) {
            touched = true;
            r.contact_time_s += dt;
        } else if (touched) {
            break;
        }
    }
    EXPECT_TRUE(touched);
    r.restitution = -s.particles().v[0].x() / (direction * kSpeed);
    return r;
}

/// Contact time of one sphere launched along +x or -x at kSpeed into an undamped curved wall.
double curved_wall_contact_time(const SolverOptions& o, const Eigen::Vector3d& x0, double direction,
                                double dt) {
    const ImpactResult r = launched_impact(o, x0, direction, dt);
    EXPECT_NEAR(r.restitution, 1.0, kRestitutionTolerance);
    return r.contact_time_s;
}

/// Hertz against curved walls (undamped): the contact time follows Hertz theory with the
/// equivalent radius of the elliptical contact, 1/r_y = 1/R + 1/R_rod across a rod (convex)
/// and 1/R - 1/R_cyl across the cylinder side (concave), r_x = R along their axes; with the
/// sphere's own radius (a flat wall) it would fall outside the tolerance.
TEST(CurvedWallImpact, HertzContactTimeFollowsTheEquivalentRadiusOfRodAndCylinder) {
    const double nu = 0.3, young = 210e9;
    const double e_star = young / (2 * (1 - nu * nu));
    const double m = sphere_mass();
    auto theory = [&](double r_e) {
        return hertz_contact_time(m, 4.0 / 3.0 * e_star * std::sqrt(r_e), kSpeed);
    };
    const double t_flat = theory(kRadius);

    SolverOptions rod = free_box_options(1, NormalLaw::hertz);
    rod.contact.damping = DampingLaw::none;
    rod.enclosure.rods.enabled = true;
    rod.enclosure.rods.rod_diameter_m = 1e-3;
    rod.enclosure.rods.cell_size_m = 5e-3;
    const double r_rod = 0.5e-3;
    const double expected_rod =
        theory(hertz_equivalent_radius(kRadius, 1.0 / (1.0 / kRadius + 1.0 / r_rod)));
    ASSERT_GT(std::abs(t_flat - expected_rod), 5 * kContactTimeTolerance * expected_rod);
    // 2.5 mm from the x- and y-rods (out of reach), approaching the z-rod through (0, 0)
    const double t_rod = curved_wall_contact_time(rod, {kRadius + r_rod + 1e-6, 0.0, 52.5e-3}, -1.0,
                                                  expected_rod / 400.0);
    EXPECT_NEAR(t_rod, expected_rod, kContactTimeTolerance * expected_rod);

    SolverOptions cyl = free_box_options(1, NormalLaw::hertz);
    cyl.contact.damping = DampingLaw::none;
    cyl.enclosure.shape = EnclosureShape::cylinder;
    cyl.enclosure.inner_diameter_m = 19e-3;
    cyl.enclosure.height_m = 25e-3;
    const double r_cyl = 9.5e-3;
    const double expected_cyl =
        theory(hertz_equivalent_radius(kRadius, 1.0 / (1.0 / kRadius - 1.0 / r_cyl)));
    ASSERT_GT(std::abs(t_flat - expected_cyl), 1.5 * kContactTimeTolerance * expected_cyl);
    const double t_cyl = curved_wall_contact_time(cyl, {r_cyl - kRadius - 1e-6, 0.0, 12.5e-3}, 1.0,
                                                  expected_cyl / 400.0);
    EXPECT_NEAR(t_cyl, expected_cyl, kContactTimeTolerance * expected_cyl);
}

/// An obstacle grid of its own material (paper 002's printed lattice in a metal shell): a
/// sphere striking a rod restitutes with the rod's coefficient and stays in contact for the
/// Hertz time of the rod's modulus, one striking the wall with the wall's.
TEST(RodMaterial, ARodOfItsOwnMaterialRestitutesAndLastsAsItsOwnTheWallAsTheWall) {
    SolverOptions o = free_box_options(1, NormalLaw::hertz);
    o.contact.damping = DampingLaw::hertz_dashpot;
    o.contact.particle_wall.restitution = 0.9;
    o.contact.particle_rod = o.contact.particle_wall;
    o.contact.particle_rod->restitution = 0.5;
    o.contact.rod_material = Material{};
    o.contact.rod_material->youngs_modulus_pa = 3e9;  // a resin
    o.contact.rod_material->poisson_ratio = 0.35;
    o.enclosure.rods.enabled = true;
    o.enclosure.rods.rod_diameter_m = 1e-3;
    o.enclosure.rods.cell_size_m = 5e-3;
    const double r_rod = 0.5e-3;
    // Hertz theory of the sphere on the resin rod: E* of steel on resin, the equivalent
    // radius across the rod (the test above checks the geometry alone).
    const Material steel = o.particles.material;
    const double e_star =
        1.0 / ((1.0 - steel.poisson_ratio * steel.poisson_ratio) / steel.youngs_modulus_pa +
               (1.0 - 0.35 * 0.35) / 3e9);
    const double r_e = hertz_equivalent_radius(kRadius, 1.0 / (1.0 / kRadius + 1.0 / r_rod));
    const double undamped =
        hertz_contact_time(sphere_mass(), 4.0 / 3.0 * e_star * std::sqrt(r_e), kSpeed);
    // Approaching the z-rod through (0, 0) from 2.5 mm beside the x- and y-rods.
    const ImpactResult rod =
        launched_impact(o, {kRadius + r_rod + 1e-6, 0.0, 52.5e-3}, -1.0, undamped / 400.0);
    EXPECT_NEAR(rod.restitution, 0.5, kRestitutionTolerance * 0.5);
    // The dashpot lengthens the contact (by 10.5 % here at e = 0.5); steel on steel would last
    // a quarter of the resin's undamped time ((E*_resin / E*_steel)^(2/5)).
    EXPECT_GT(rod.contact_time_s, undamped);
    EXPECT_LT(rod.contact_time_s, 1.15 * undamped);
    // The -x wall of the box: the wall's restitution (x0 mid-cell, no rod within reach).
    const ImpactResult wall =
        launched_impact(o, {-0.05 + kRadius + 1e-6, 2.5e-3, 52.5e-3}, -1.0, undamped / 4000.0);
    EXPECT_NEAR(wall.restitution, 0.9, kRestitutionTolerance * 0.9);
}

/// A lateral surface of its own material (paper 000: a PMMA tube between aluminium ends): a
/// sphere striking a side face of the box restitutes with the side's coefficient and stays in
/// contact for the Hertz time of PMMA on steel, one falling onto the bottom with the ends'
/// coefficient and the Hertz time of aluminium.
TEST(SideMaterial, TheLateralSurfaceRestitutesAndLastsAsItsOwnMaterialTheEndsAsTheWall) {
    SolverOptions o = free_box_options(1, NormalLaw::hertz);
    o.contact.damping = DampingLaw::hertz_dashpot;
    o.contact.particle_wall.restitution = 0.9;
    o.contact.wall_material.youngs_modulus_pa = 70e9;  // aluminium
    o.contact.wall_material.poisson_ratio = 0.33;
    o.contact.particle_side = o.contact.particle_wall;
    o.contact.particle_side->restitution = 0.6;
    o.contact.side_material = Material{};
    o.contact.side_material->youngs_modulus_pa = 3e9;  // PMMA
    o.contact.side_material->poisson_ratio = 0.35;
    const Material steel = o.particles.material;
    auto flat_contact_time = [&](double young, double nu) {
        const double e_star =
            1.0 / ((1.0 - steel.poisson_ratio * steel.poisson_ratio) / steel.youngs_modulus_pa +
                   (1.0 - nu * nu) / young);
        return hertz_contact_time(sphere_mass(), 4.0 / 3.0 * e_star * std::sqrt(kRadius), kSpeed);
    };
    const double pmma = flat_contact_time(3e9, 0.35), aluminium = flat_contact_time(70e9, 0.33);
    ASSERT_GT(pmma, 3.0 * aluminium);
    // The -x face, then the +x face: the side's restitution, a contact a little longer than
    // the undamped Hertz time of PMMA (the dashpot lengthens it, by 6 % at e = 0.6).
    for (const double direction : {-1.0, 1.0}) {
        const ImpactResult side = launched_impact(
            o, {direction * (0.05 - kRadius - 1e-6), 0.0, 52.5e-3}, direction, pmma / 400.0);
        EXPECT_NEAR(side.restitution, 0.6, kRestitutionTolerance * 0.6) << direction;
        EXPECT_GT(side.contact_time_s, pmma);
        EXPECT_LT(side.contact_time_s, 1.15 * pmma);
    }
    // The bottom: the ends' restitution and aluminium's time.
    const ImpactResult bottom = impact(o, true, kSpeed, aluminium / 400.0);
    EXPECT_NEAR(bottom.restitution, 0.9, kRestitutionTolerance * 0.9);
    EXPECT_GT(bottom.contact_time_s, aluminium);
    EXPECT_LT(bottom.contact_time_s, 1.1 * aluminium);
}

}  // namespace
}  // namespace sb::dem

// Contact law pieces: restitution relations, composition rules, objectivity of the force.
#include "dem/contact_law.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace sb::dem {
namespace {

/// The dimensionless Hertz impact is integrated with RK4 at h = 2e-4: far tighter than this.
constexpr double kAlphaRoundTripTolerance = 1e-6;

TEST(HertzDashpot, AlphaFromRestitutionRoundTrips) {
    for (double e : {0.3, 0.5, 0.7, 0.9, 0.99}) {
        const double alpha = hertz_alpha_from_restitution(e);
        EXPECT_GT(alpha, 0.0);
        EXPECT_NEAR(hertz_restitution_from_alpha(alpha), e, kAlphaRoundTripTolerance) << e;
    }
    EXPECT_EQ(hertz_alpha_from_restitution(1.0), 0.0);
}

TEST(LinearDashpot, ZetaInvertsTheClampedClosedForm) {
    for (double e : {0.3, 0.5, 0.9}) {
        EXPECT_NEAR(linear_restitution_from_zeta(linear_zeta_from_restitution(e)), e, 1e-12);
    }
    // weak damping: the clamp hardly matters, e ~ exp(-zeta pi / sqrt(1 - zeta^2))
    const double zeta = linear_zeta_from_restitution(0.99);
    EXPECT_NEAR(std::exp(-zeta * kPi / std::sqrt(1.0 - zeta * zeta)), 0.99, 1e-4);
}

TEST(ContactLaw, IncompatibleDampingIsRejectedNamingBothPieces) {
    ContactOptions o;
    o.normal = NormalLaw::hertz;
    o.damping = DampingLaw::linear_dashpot;
    const Violations v = o.validate();
    ASSERT_FALSE(v.empty());
    bool found = false;
    for (const auto& x : v) {
        if (x.key == "damping" && x.constraint.find("hertz") != std::string::npos) found = true;
    }
    EXPECT_TRUE(found);
}

TEST(ContactLaw, RestitutionPicksTheMatchingDashpot) {
    ContactOptions o;
    o.normal_stiffness = 1e5;
    EXPECT_TRUE(std::holds_alternative<LinearDashpot>(make_contact_law(o).damping));
    o.normal = NormalLaw::hertz;
    o.normal_stiffness = 0.0;
    EXPECT_TRUE(std::holds_alternative<HertzDashpot>(make_contact_law(o).damping));
    EXPECT_TRUE(o.validate().empty());
    EXPECT_NE(make_contact_law(o).describe().find("hertz_dashpot"), std::string::npos);
}

TEST(ContactOptions, ValidateCollectsEveryViolation) {
    ContactOptions o;
    o.normal_stiffness = -1.0;
    o.particle_wall.restitution = 1.5;
    o.particle_particle.sliding_friction = -0.1;
    const Violations v = o.validate();
    ASSERT_EQ(v.size(), 3u);
    EXPECT_EQ(v[0].key, "normal_stiffness");
    EXPECT_EQ(v[1].key, "particle_particle.sliding_friction");
    EXPECT_EQ(v[2].key, "particle_wall.restitution");
}

/// Evaluates the full composed law the way the solver does.
Eigen::Vector3d law_force(const ContactKinematics& k, const PairCoefficients& p,
                          Eigen::Vector3d& hist) {
    const NormalResult nr = Hooke{}.evaluate(k, p);
    const double fn = std::max(0.0, nr.f_spring + LinearDashpot{}.evaluate(k, p, nr));
    return fn * k.n + CoulombSpring{}.evaluate(k, p, fn, nr, hist);
}

TEST(CoulombSpring, LoadedContactRotatedRigidlyGivesRotatedForce) {
    PairCoefficients p;
    p.k_n = 1e5;
    p.damping = 0.05;
    p.mu = 0.5;
    ContactKinematics k;
    k.delta = 1e-5;
    k.delta_dot = 1e-3;
    k.n = Eigen::Vector3d(0, 0, 1);
    k.v_t = Eigen::Vector3d(2e-3, -1e-3, 0);
    k.m_eff = 1e-4;
    k.dt = 1e-6;
    Eigen::Vector3d hist(3e-7, 1e-7, 0);
    Eigen::Vector3d h0 = hist;
    const Eigen::Vector3d f0 = law_force(k, p, h0);

    const Eigen::Matrix3d q =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    ContactKinematics kr = k;
    kr.n = q * k.n;
    kr.v_t = q * k.v_t;
    Eigen::Vector3d hr = q * hist;
    const Eigen::Vector3d fr = law_force(kr, p, hr);
    EXPECT_LT((fr - q * f0).norm(), 1e-12 * f0.norm());
    EXPECT_LT((hr - q * h0).norm(), 1e-12 * h0.norm());
}

TEST(CoulombSpring, HistoryIsProjectedOntoTheNewTangentPlaneKeepingItsLength) {
    PairCoefficients p;
    p.k_n = 1e5;
    p.mu = 10.0;
    ContactKinematics k;
    k.n = Eigen::Vector3d(0, 1, 1).normalized();
    k.dt = 1e-6;
    Eigen::Vector3d hist(0, 1e-6, 0);
    NormalResult nr{1.0, 1e5, 1e5};
    CoulombSpring{}.evaluate(k, p, 1.0, nr, hist);
    EXPECT_NEAR(hist.dot(k.n), 0.0, 1e-18);
    EXPECT_NEAR(hist.norm(), 1e-6, 1e-18);
}

TEST(DirectionalCoulomb, GivesMuTimesNormalForceAgainstTheSlip) {
    PairCoefficients p;
    p.mu = 0.6;
    p.slip_reg = 1e-4;
    ContactKinematics k;
    k.v_t = Eigen::Vector3d(0.1, 0, 0);
    k.m_t = 1.0;
    k.dt = 1e-6;
    Eigen::Vector3d h = Eigen::Vector3d::Zero();
    const Eigen::Vector3d f = DirectionalCoulomb{}.evaluate(k, p, 2.0, NormalResult{}, h);
    EXPECT_NEAR(f.x(), -1.2, 1e-12);
    k.v_t = Eigen::Vector3d(0.5e-4, 0, 0);  // inside the regularisation ramp
    EXPECT_NEAR(DirectionalCoulomb{}.evaluate(k, p, 2.0, NormalResult{}, h).x(), -0.6, 1e-12);
}

TEST(ConstantRollingTorque, OpposesTheRelativeRollingAndIgnoresTwist) {
    PairCoefficients p;
    p.mu_r = 0.01;
    ContactKinematics k;
    k.n = Eigen::Vector3d(0, 0, 1);
    k.omega_rel = Eigen::Vector3d(5, 0, 7);
    k.r_eff = 1e-3;
    k.i_eff = 1.0;
    k.dt = 1e-6;
    const Eigen::Vector3d m = ConstantRollingTorque{}.evaluate(k, p, 3.0);
    EXPECT_NEAR(m.x(), -0.01 * 1e-3 * 3.0, 1e-15);
    EXPECT_EQ(m.z(), 0.0);
}

}  // namespace
}  // namespace sb::dem

namespace sb::dem {
namespace {

/// Bisection to 200 halvings of ln(b/a) and std::comp_ellint_*: far below this.
constexpr double kEquivalentRadiusTolerance = 1e-9;

TEST(HertzEquivalentRadius, IsTheSphereRadiusForEqualCurvatures) {
    EXPECT_DOUBLE_EQ(hertz_equivalent_radius(1.5e-3, 1.5e-3), 1.5e-3);
    EXPECT_NEAR(hertz_equivalent_radius(1.5e-3, 1.5e-3 * (1 + 1e-5)), 1.5e-3 * (1 + 0.5e-5), 1e-12);
    EXPECT_DOUBLE_EQ(hertz_equivalent_radius(1e-3, 3e-3), hertz_equivalent_radius(3e-3, 1e-3));
}

/// Forward Hertz solution for an ellipse of semi-axes a >= b and peak pressure p0 (Johnson
/// 1985, eqs. 3.42 and 3.46): relative curvatures A, B, load F and approach delta. The
/// equivalent radius computed from the curvatures must reproduce F = 4/3 E* sqrt(R_e) d^1.5.
TEST(HertzEquivalentRadius, ReproducesTheEllipticalHertzLoadApproachRelation) {
    const double e_star = 115e9, p0 = 2e9;
    for (double b_over_a : {0.9, 0.6, 0.4, 0.2}) {
        const double a = 1e-4, b = b_over_a * a;
        const double ecc = std::sqrt(1.0 - b_over_a * b_over_a);
        const double kk = std::comp_ellint_1(ecc), ee = std::comp_ellint_2(ecc);
        const double scale = p0 * b / (e_star * ecc * ecc * a * a);
        const double curv_a = scale * (kk - ee);                    // along a
        const double curv_b = scale * (a * a / (b * b) * ee - kk);  // along b
        const double force = 2.0 / 3.0 * kPi * a * b * p0;
        const double delta = p0 * b * kk / e_star;
        const double r_e = hertz_equivalent_radius(0.5 / curv_a, 0.5 / curv_b);
        const double force_law = 4.0 / 3.0 * e_star * std::sqrt(r_e) * std::pow(delta, 1.5);
        EXPECT_NEAR(force_law, force, kEquivalentRadiusTolerance * force) << b_over_a;
    }
}

/// A sphere on a rod is stiffer than on a flat wall, inside a cylinder softer; the equivalent
/// radius lies between the two principal radii (near their geometric mean).
TEST(HertzEquivalentRadius, LiesBetweenThePrincipalRadii) {
    const double r = 1e-3, r_rod = 0.5e-3, r_cyl = 9.5e-3;
    const double rod = hertz_equivalent_radius(r, 1.0 / (1.0 / r + 1.0 / r_rod));
    EXPECT_LT(rod, r);
    EXPECT_GT(rod, 1.0 / (1.0 / r + 1.0 / r_rod));
    const double cyl = hertz_equivalent_radius(r, 1.0 / (1.0 / r - 1.0 / r_cyl));
    EXPECT_GT(cyl, r);
    EXPECT_LT(cyl, 1.0 / (1.0 / r - 1.0 / r_cyl));
}

}  // namespace
}  // namespace sb::dem

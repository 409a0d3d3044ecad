// Beam natural frequencies against closed forms and the seed papers' reference numbers.
#include "structure/beam_model.hpp"

#include <gtest/gtest.h>

#include "beam_fixtures.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::structure {
namespace {

using testing::bending_frequencies;
using testing::euler_bernoulli_hz;
using testing::steel_strip;
using testing::support;

// Converged cubic elements: 40 elements put the third mode's discretisation error near 1e-6,
// far below the 0.1 % the analytic roots (five digits) allow.
constexpr double kAnalyticTolerance = 1e-3;
constexpr int kModes = 30;  // enough to hold three weak-bending modes among the others
constexpr int kAxisZ = 2;

void expect_first_three(const BeamSpec& beam, const std::array<double, 3>& beta_l) {
    const LinearModel model = build_beam_model(beam, ExcitationSpec{});
    const ModalBasis basis = compute_modes(model, DampingSpec{}, kModes);
    const auto f = bending_frequencies(model, basis, kAxisZ);
    ASSERT_GE(f.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        const double expected = euler_bernoulli_hz(beta_l[i], beam);
        EXPECT_NEAR(f[i] / expected, 1.0, kAnalyticTolerance) << "mode " << i + 1;
    }
}

TEST(BeamModel, CantileverMatchesEulerBernoulliRoots) {
    BeamSpec b = steel_strip();
    b.supports = {support("root", 0.0, SupportKind::clamped)};
    expect_first_three(b, {1.8751, 4.6941, 7.8548});
}

TEST(BeamModel, SimplySupportedBeamMatchesMultiplesOfPi) {
    BeamSpec b = steel_strip();
    b.supports = {support("a", 0.0, SupportKind::pinned), support("b", 1.0, SupportKind::pinned)};
    expect_first_three(b, {kPi, 2.0 * kPi, 3.0 * kPi});
}

TEST(BeamModel, ClampedClampedBeamMatchesEulerBernoulliRoots) {
    BeamSpec b = steel_strip();
    b.supports = {support("a", 0.0, SupportKind::clamped), support("b", 1.0, SupportKind::clamped)};
    expect_first_three(b, {4.7300, 7.8532, 10.9956});
}

TEST(BeamModel, ClampedPinnedBeamMatchesEulerBernoulliRoots) {
    BeamSpec b = steel_strip();
    b.supports = {support("a", 0.0, SupportKind::clamped), support("b", 1.0, SupportKind::pinned)};
    expect_first_three(b, {3.9266, 7.0686, 10.2102});
}

TEST(BeamModel, ShortThickTimoshenkoBeamFollowsTimoshenkosFrequencyEquation) {
    // Simply supported, L/t = 5: shear and rotary inertia lower the frequency noticeably.
    // The 40-element mesh (h = t/8) leaves a discretisation error of 2.3e-5 (mode 1) and
    // 2.7e-4 (mode 2) against Timoshenko's equation; the Euler-Bernoulli mesh error is below
    // 1e-6. The tolerances hold these with a margin of two and are far below the effect
    // (6 % and 18.5 %).
    constexpr double kTimoshenkoTolerance = 5e-4;
    constexpr double kReductionTolerance = 5e-4;  // on 1 - f_T/f_EB: the same mesh error
    BeamSpec b = steel_strip();
    b.length_m = 0.2;
    b.thickness_m = 0.04;
    b.width_m = 0.06;
    b.shear_modulus_pa = 80.77e9;
    b.supports = {support("a", 0.0, SupportKind::pinned), support("b", 0.2, SupportKind::pinned)};
    const LinearModel model = build_beam_model(b, ExcitationSpec{});
    const auto f = bending_frequencies(model, compute_modes(model, DampingSpec{}, kModes), kAxisZ);
    BeamSpec euler_beam = b;
    euler_beam.shear_modulus_pa.reset();
    const LinearModel euler_model = build_beam_model(euler_beam, ExcitationSpec{});
    const auto f_euler =
        bending_frequencies(euler_model, compute_modes(euler_model, DampingSpec{}, kModes), kAxisZ);
    ASSERT_GE(f.size(), 2u);
    ASSERT_GE(f_euler.size(), 2u);
    // Timoshenko's equation for w = sin(k x) e^{iWt}, k = n pi / L (Timoshenko, Vibration
    // Problems in Engineering, sec. 5.14): (rho^2 I / (kappa G)) W^4
    // - (rho A + rho I k^2 (1 + E / (kappa G))) W^2 + E I k^4 = 0; the lower root bends.
    const double kappa = 5.0 / 6.0;
    const double area = b.width_m * b.thickness_m;
    const double inertia = b.width_m * std::pow(b.thickness_m, 3) / 12.0;
    const double rho = b.density_kg_m3;
    const double e = b.youngs_modulus_pa;
    const double g = *b.shear_modulus_pa;
    for (int n = 1; n <= 2; ++n) {
        const auto i = static_cast<std::size_t>(n - 1);
        const double k = n * kPi / b.length_m;
        const double qa = rho * rho * inertia / (kappa * g);
        const double qb = -(rho * area + rho * inertia * k * k * (1.0 + e / (kappa * g)));
        const double qc = e * inertia * std::pow(k, 4);
        const double w2 = (-qb - std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
        const double expected = std::sqrt(w2) / kTwoPi;
        EXPECT_NEAR(f[i] / expected, 1.0, kTimoshenkoTolerance) << "mode " << n;
        // The FE shear reduction against the FE Euler-Bernoulli beam on the same mesh is the
        // theoretical one (Timoshenko root over Euler-Bernoulli's (n pi)^2 frequency).
        const double fe_reduction = 1.0 - f[i] / f_euler[i];
        const double theory_reduction = 1.0 - expected / euler_bernoulli_hz(n * kPi, b);
        EXPECT_NEAR(fe_reduction, theory_reduction, kReductionTolerance) << "mode " << n;
        EXPECT_GT(fe_reduction, 0.03) << "mode " << n;  // the effect is a few per cent
    }
}

TEST(BeamModel, Paper000BareBeamHasItsFirstModeAt8Point50Hz) {
    constexpr double kPaperTolerance = 5e-3;  // Table 1 values have two to three digits
    StructureSpec spec;
    spec.beam = testing::paper000_bare_beam();
    const LinearModel model = build_beam_model(spec.beam, spec.excitation);
    const auto f = bending_frequencies(model, compute_modes(model, spec.damping, 6), kAxisZ);
    ASSERT_FALSE(f.empty());
    EXPECT_NEAR(f[0] / 8.50, 1.0, kPaperTolerance);
}

TEST(BeamModel, Paper000BeamWithSensorsAndDamperHasItsFirstModeNear6Point37Hz) {
    const StructureSpec spec = testing::paper000_loaded();
    const LinearModel model = build_linear_model(spec, {});
    const ModalBasis basis = compute_modes(model, spec.damping, 6);
    const auto f = bending_frequencies(model, basis, kAxisZ);
    ASSERT_FALSE(f.empty());
    EXPECT_GE(f[0], 6.30);
    EXPECT_LE(f[0], 6.45);
    EXPECT_DOUBLE_EQ(basis.modes[0].frequency_hz, f[0]);  // the fundamental is first
}

TEST(BeamModel, Paper002ClampedPinnedSteelBeamHasItsFirstModeNear144Point7Hz) {
    BeamSpec b;
    b.length_m = 0.45;  // 500 mm bar, 50 mm in the clamp
    b.width_m = 0.016;
    b.thickness_m = 0.008;  // the exciter drives the 8 mm direction
    b.density_kg_m3 = 7850.0;
    b.youngs_modulus_pa = 210e9;
    b.supports = {support("clamp", 0.0, SupportKind::clamped),
                  support("exciter", 0.45, SupportKind::pinned)};
    const LinearModel model = build_beam_model(b, ExcitationSpec{});
    const auto f = bending_frequencies(model, compute_modes(model, DampingSpec{}, 6), kAxisZ);
    ASSERT_FALSE(f.empty());
    EXPECT_GE(f[0], 144.0);
    EXPECT_LE(f[0], 146.0);
}

TEST(BeamModel, CantileverDrivenAtItsRootHasARigidTranslationAsInfluenceVector) {
    constexpr double kSolveRoundOff = 1e-9;  // condition number of K times machine epsilon
    StructureSpec spec = testing::paper000_loaded();
    spec.excitation.kind = ExcitationSpec::Kind::base;
    spec.excitation.support = "root";
    spec.excitation.direction = {0.0, 0.0, 2.0};  // normalised at use
    const LinearModel model = build_linear_model(spec, {});
    ASSERT_TRUE(model.base_influence().has_value());
    for (const auto& name : model.point_names()) {  // the root too, through its fixed DOFs
        const Eigen::Matrix<double, 6, 1>& u = model.point(name).base_motion;
        EXPECT_NEAR(u(2), 1.0, kSolveRoundOff) << name;
        EXPECT_NEAR(u.norm(), 1.0, kSolveRoundOff) << name;
    }
}

TEST(BeamModel, OffsetMassPointMovesWithTheRotationOfTheBeam) {
    const StructureSpec spec = testing::paper000_loaded();
    const LinearModel model = build_linear_model(spec, {});
    // Rotation of the damper node about y moves a CG offset along +z in -x: u = theta x r.
    const auto& damper = model.point("damper").op;
    const auto& shaker = model.point("shaker").op;
    EXPECT_NEAR(damper.row(0).cwiseAbs().sum(), 1.0 + 0.0155, 1e-12);
    EXPECT_EQ(shaker.row(0).cwiseAbs().sum(), 1.0);
    EXPECT_THROW((void)model.point("nowhere"), std::out_of_range);
}

}  // namespace
}  // namespace sb::structure

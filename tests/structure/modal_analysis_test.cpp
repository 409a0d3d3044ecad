// Modal analysis: effective masses, modal masses and lumped models against closed forms.
#include "structure/modal_analysis.hpp"

#include <gtest/gtest.h>

#include "beam_fixtures.hpp"
#include "structure/beam_model.hpp"
#include "structure/lumped_model.hpp"

namespace sb::structure {
namespace {

// Sums of a few hundred positive terms of O(1e-2) kg: round-off only.
constexpr double kSumRoundOff = 1e-10;

TEST(ModalAnalysis, EffectiveMassesOfAllModesSumToTheMassNotHeldBySupports) {
    BeamSpec b = testing::paper000_bare_beam();
    b.shear_modulus_pa.reset();
    b.min_elements = 20;
    const LinearModel model = build_beam_model(b, ExcitationSpec{});
    const ModalBasis basis = compute_modes(model, DampingSpec{}, model.dofs());
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& m : basis.modes) sum += m.effective_mass_kg;
    const double rho_a = b.density_kg_m3 * b.width_m * b.thickness_m;
    const double h = b.length_m / b.min_elements;
    // Consistent masses: the clamped node keeps 2/3 rho A h of the axial bar mass
    // (2/6 + 2 * 1/6), and 13/35 + 2 * 9/70 = 44/70 of rho A h in each bending direction.
    const double total = rho_a * b.length_m;
    EXPECT_NEAR(sum.x(), total - 2.0 / 3.0 * rho_a * h, kSumRoundOff);
    EXPECT_NEAR(sum.y(), total - 44.0 / 70.0 * rho_a * h, kSumRoundOff);
    EXPECT_NEAR(sum.z(), total - 44.0 / 70.0 * rho_a * h, kSumRoundOff);
}

TEST(ModalAnalysis, ShapesAreMassNormalised) {
    const StructureSpec spec = testing::paper000_loaded();
    const LinearModel model = build_linear_model(spec, {});
    const ModalBasis basis = compute_modes(model, spec.damping, 8);
    const Eigen::MatrixXd g = basis.shapes.transpose() * model.mass() * basis.shapes;
    EXPECT_LT((g - Eigen::MatrixXd::Identity(8, 8)).norm(), 1e-9);
    EXPECT_DOUBLE_EQ(basis.modes[0].damping_ratio, 0.005);
}

TEST(ModalAnalysis, CantileverModalMassAtTheTipIsAQuarterOfTheBeamMass) {
    // Euler-Bernoulli cantilever, shape scaled to 1 at the tip: generalised mass 0.25 m
    // (integral of the normalised first mode squared; Blevins Table 8-1).
    constexpr double kMeshError = 1e-4;
    BeamSpec b = testing::paper000_bare_beam();
    b.shear_modulus_pa.reset();
    const LinearModel model = build_beam_model(b, ExcitationSpec{});
    const ModalBasis basis = compute_modes(model, DampingSpec{}, 1);
    const double beam_mass = b.density_kg_m3 * b.width_m * b.thickness_m * b.length_m;
    EXPECT_NEAR(basis.modes[0].modal_mass_kg / beam_mass, 0.25, kMeshError);
}

TEST(LumpedModel, SpringMassDashpotHasItsTextbookFrequencyAndDampingRatio) {
    LumpedSpec l;
    l.masses = {{"m", 2.0}};
    const double k = 5000.0;
    const double c = 3.0;
    l.springs = {{"m", "ground", k, c}};
    ExcitationSpec e;
    e.point = "m";
    const LinearModel model = build_lumped_model(l, e);
    ASSERT_TRUE(model.damping().has_value());
    const ModalBasis basis = compute_modes(model, DampingSpec{}, 1);
    EXPECT_NEAR(basis.modes[0].frequency_hz, std::sqrt(k / 2.0) / kTwoPi, 1e-12);
    EXPECT_NEAR(basis.modes[0].damping_ratio, c / (2.0 * std::sqrt(k * 2.0)), 1e-12);
    EXPECT_NEAR(basis.modes[0].effective_mass_kg.z(), 2.0, 1e-12);
}

TEST(LumpedModel, TwoMassChainHasGoldenRatioFrequencies) {
    // m - k - m - k - ground: w^2 = (k/m) (3 -+ sqrt 5) / 2.
    LumpedSpec l;
    l.masses = {{"a", 1.5}, {"b", 1.5}};
    l.springs = {{"ground", "a", 600.0, 0.0}, {"a", "b", 600.0, 0.0}};
    ExcitationSpec e;
    e.kind = ExcitationSpec::Kind::base;
    e.support = "ground";
    const LinearModel model = build_lumped_model(l, e);
    EXPECT_FALSE(model.damping().has_value());
    const ModalBasis basis = compute_modes(model, DampingSpec{}, 2);
    const double w0 = std::sqrt(600.0 / 1.5);
    EXPECT_NEAR(kTwoPi * basis.modes[0].frequency_hz, w0 * std::sqrt((3.0 - std::sqrt(5.0)) / 2.0),
                1e-10);
    EXPECT_NEAR(kTwoPi * basis.modes[1].frequency_hz, w0 * std::sqrt((3.0 + std::sqrt(5.0)) / 2.0),
                1e-10);
    ASSERT_TRUE(model.base_influence().has_value());
    EXPECT_NEAR((*model.base_influence() - Eigen::Vector2d::Ones()).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace sb::structure

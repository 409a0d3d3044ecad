// Validation of structure specs: every violation is reported with its exact key.
#include "structure/spec.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "beam_fixtures.hpp"

namespace sb::structure {
namespace {

const Violation* find_key(const Violations& v, const std::string& key) {
    const auto it = std::find_if(v.begin(), v.end(), [&](const auto& x) { return x.key == key; });
    return it == v.end() ? nullptr : &*it;
}

TEST(StructureSpec, PaperBeamWithAttachmentsIsValid) {
    EXPECT_TRUE(testing::paper000_loaded().validate().empty());
}

TEST(StructureSpec, NegativeLengthIsReportedUnderBeamLength) {
    StructureSpec spec = testing::paper000_loaded();
    spec.beam.length_m = -1.0;
    const auto v = spec.validate();
    const Violation* hit = find_key(v, "beam.length_m");
    ASSERT_NE(hit, nullptr);
    EXPECT_EQ(hit->value, "-1");
    EXPECT_EQ(hit->constraint, "must be > 0");
}

TEST(StructureSpec, MassOutsideTheBeamNamesItsIndexAndTheRange) {
    StructureSpec spec = testing::paper000_loaded();
    spec.beam.masses[1].x_m = 0.6;
    const auto v = spec.validate();
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].key, "beam.masses[1].x_m");
    EXPECT_EQ(v[0].constraint, "must be in [0, 0.543]");
    EXPECT_EQ(v[0].meaning, "mass position along the beam [m]");
}

TEST(StructureSpec, MissingSupportsAreReported) {
    StructureSpec spec = testing::paper000_loaded();
    spec.beam.supports.clear();
    EXPECT_NE(find_key(spec.validate(), "beam.supports"), nullptr);
}

TEST(StructureSpec, DuplicatePointNamesAreReported) {
    StructureSpec spec = testing::paper000_loaded();
    spec.beam.points.push_back({"shaker", 0.2});
    const auto v = spec.validate();
    const Violation* hit = find_key(v, "beam.points.shaker");
    ASSERT_NE(hit, nullptr);
    EXPECT_EQ(hit->constraint, "must be unique");
}

TEST(StructureSpec, AllViolationsAreCollectedNotJustTheFirst) {
    StructureSpec spec = testing::paper000_loaded();
    spec.beam.width_m = 0.0;
    spec.beam.youngs_modulus_pa = -5.0;
    spec.beam.min_elements = 0;
    spec.beam.points[0].x_m = -0.1;
    spec.modes = 0;
    spec.damping.default_ratio = 1.0;
    const auto v = spec.validate();
    for (const char* key : {"beam.width_m", "beam.youngs_modulus_pa", "beam.elements",
                            "beam.points.shaker", "modes", "damping.default_ratio"}) {
        EXPECT_NE(find_key(v, key), nullptr) << key;
    }
}

TEST(StructureSpec, ElasticSupportNeedsNonNegativeSprings) {
    StructureSpec spec = testing::paper000_loaded();
    spec.beam.supports[0].kind = SupportKind::elastic;
    spec.beam.supports[0].translational_stiffness_n_per_m = {1e6, -1.0, 1e6};
    EXPECT_NE(find_key(spec.validate(), "beam.supports.root.translational_stiffness_n_per_m[1]"),
              nullptr);
}

TEST(StructureSpec, ExcitationMustReferToAnExistingPointOrSupport) {
    StructureSpec spec = testing::paper000_loaded();
    spec.excitation.point = "nowhere";
    EXPECT_NE(find_key(spec.validate(), "excitation.point"), nullptr);
    spec.excitation.kind = ExcitationSpec::Kind::base;
    spec.excitation.support = "nowhere";
    EXPECT_NE(find_key(spec.validate(), "excitation.support"), nullptr);
    spec.excitation.support = "root";
    spec.excitation.direction.setZero();
    EXPECT_NE(find_key(spec.validate(), "excitation.direction"), nullptr);
}

TEST(StructureSpec, ANegativeLengthDoesNotMakeEveryPositionAnError) {
    StructureSpec spec = testing::paper000_loaded();
    spec.beam.length_m = -1.0;
    const auto v = spec.validate();
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].key, "beam.length_m");
}

TEST(StructureSpec, ASectionThickerThanItIsWideIsReported) {
    // y is the longer side, z the weak bending direction the shaker drives.
    StructureSpec spec = testing::paper000_loaded();
    spec.beam.thickness_m = 0.06;
    const auto v = spec.validate();
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].key, "beam.thickness_m");
    EXPECT_EQ(v[0].constraint, "must be <= width_m = 0.05");
    spec.beam.thickness_m = spec.beam.width_m;  // a square section is fine
    EXPECT_TRUE(spec.validate().empty());
}

TEST(LumpedSpec, SpringsMustReferenceMassesOrGround) {
    LumpedSpec l;
    l.masses = {{"a", 1.0}, {"b", 0.0}};
    l.springs = {{"a", "ground", 10.0, 0.0}, {"a", "c", 10.0, 0.0}, {"a", "b", 0.0, -1.0}};
    const auto v = l.validate();
    EXPECT_NE(find_key(v, "masses[1].mass_kg"), nullptr);
    EXPECT_NE(find_key(v, "springs[1].to"), nullptr);
    EXPECT_NE(find_key(v, "springs[2].stiffness_n_per_m"), nullptr);
    EXPECT_NE(find_key(v, "springs[2].damping_n_s_per_m"), nullptr);
    EXPECT_EQ(v.size(), 4u);
}

TEST(DampingSpec, ModalRatioFallsBackToTheDefault) {
    DampingSpec d;
    d.modal_ratios = {0.01, 0.02};
    d.default_ratio = 0.003;
    EXPECT_DOUBLE_EQ(d.ratio(1, 10.0), 0.01);
    EXPECT_DOUBLE_EQ(d.ratio(2, 10.0), 0.02);
    EXPECT_DOUBLE_EQ(d.ratio(3, 10.0), 0.003);
}

TEST(DampingSpec, RayleighRatioFollowsAlphaOverTwoOmegaPlusBetaOmegaOverTwo) {
    DampingSpec d;
    d.model = DampingSpec::Model::rayleigh;
    d.alpha_per_s = 2.0;
    d.beta_s = 1e-4;
    EXPECT_DOUBLE_EQ(d.ratio(1, 100.0), 2.0 / 200.0 + 1e-4 * 50.0);
    d.beta_s = -1.0;
    EXPECT_EQ(d.validate().size(), 1u);
}

}  // namespace
}  // namespace sb::structure

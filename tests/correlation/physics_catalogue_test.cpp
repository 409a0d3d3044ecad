// The catalogue's rows: which configs each applies to, and what switching it on changes and
// frees (the keys must parse as calibration intervals of the switched config).
#include "correlation/physics_catalogue.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "bench/resolved_config.hpp"
#include "correlation/free_parameters.hpp"

namespace sb::correlation {
namespace {

bench::CampaignConfig h0(const std::vector<std::string>& overrides = {}) {
    auto config =
        bench::load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    bench::apply_overrides(config, overrides);
    return config;
}

bool applies(const std::string& row, const bench::CampaignConfig& config) {
    const auto& entry = catalogue_entry(row);
    return !entry.applies || entry.applies(config);
}

/// Switches `row` on in a copy of `config` and parses its keys there.
std::vector<FreeParameter> switched(const std::string& row, bench::CampaignConfig& config) {
    return parse_free_parameters(config, catalogue_entry(row).switch_on(config), "catalogue");
}

TEST(PhysicsCatalogue, EveryRowIsNamedOnceWithItsWordsAndASignature) {
    std::set<std::string> names;
    for (const auto& row : physics_catalogue()) {
        EXPECT_TRUE(names.insert(row.name).second) << row.name;
        EXPECT_FALSE(row.left_out.empty()) << row.name;
        EXPECT_FALSE(row.description.empty()) << row.name;
        EXPECT_FALSE(row.signature.empty()) << row.name;
        EXPECT_TRUE(static_cast<bool>(row.switch_on)) << row.name;
    }
    EXPECT_GE(names.size(), 12U);
    EXPECT_THROW(catalogue_entry("no-such-physics"), std::invalid_argument);
}

TEST(PhysicsCatalogue, RollingResistanceAppliesToADemBedThatRollsFreely) {
    EXPECT_FALSE(applies("rolling-resistance", h0()));  // paper 000 models it
    EXPECT_FALSE(applies("rolling-resistance", h0({"dampers.pd.model=rigid"})));
    auto config = h0({"dampers.pd.contact.rolling=none"});
    ASSERT_TRUE(applies("rolling-resistance", config));
    const auto free = switched("rolling-resistance", config);
    EXPECT_EQ(config.campaign.dampers.front().contact.rolling, dem::RollingLaw::constant_torque);
    ASSERT_EQ(free.size(), 1U);
    EXPECT_EQ(free.front().path, "dampers.pd.contact.rolling_friction");
    EXPECT_EQ(free.front().lo, 0.0);
    EXPECT_EQ(free.front().hi, 0.05);
    EXPECT_FALSE(applies("rolling-resistance", config));  // now modelled
}

TEST(PhysicsCatalogue, StaticFrictionTurnsAStatelessFrictionIntoAHistorySpring) {
    EXPECT_FALSE(applies("static-friction", h0({"dampers.pd.model=rigid"})));
    auto config = h0();
    ASSERT_TRUE(applies("static-friction", config));
    const auto free = switched("static-friction", config);
    EXPECT_EQ(config.campaign.dampers.front().contact.tangential,
              dem::TangentialLaw::coulomb_spring);
    ASSERT_EQ(free.size(), 1U);
    EXPECT_EQ(free.front().path, "dampers.pd.contact.tangential_stiffness_ratio");
    EXPECT_TRUE(free.front().log_scale);
    EXPECT_EQ(free.front().lo, 0.05);
    EXPECT_EQ(free.front().hi, 1.0);
    EXPECT_FALSE(applies("static-friction", config));
}

TEST(PhysicsCatalogue, VelocityDependentRestitutionMakesTheContactsViscoelastic) {
    EXPECT_FALSE(applies("velocity-dependent-restitution", h0({"dampers.pd.model=rigid"})));
    auto config = h0();
    ASSERT_TRUE(applies("velocity-dependent-restitution", config));
    const auto free = switched("velocity-dependent-restitution", config);
    const auto& contact = config.campaign.dampers.front().contact;
    EXPECT_EQ(contact.normal, dem::NormalLaw::hertz);
    EXPECT_EQ(contact.damping, dem::DampingLaw::viscoelastic);
    ASSERT_EQ(free.size(), 1U);
    EXPECT_EQ(free.front().path, "dampers.pd.contact.dissipative_constant_s");
    EXPECT_TRUE(free.front().log_scale);
    EXPECT_EQ(free.front().lo, 1e-9);
    EXPECT_EQ(free.front().hi, 1e-5);
    // The wall follows the particles' constant; the switched config is a valid one.
    EXPECT_EQ(contact.particle_wall().dissipative_constant_s, 1e-9);
    EXPECT_NO_THROW(bench::load_campaign_config_text(bench::resolved_config_toml(config), "on"));
    EXPECT_FALSE(applies("velocity-dependent-restitution", config));
}

TEST(PhysicsCatalogue, GravityTiltFreesEveryArrangementsTiltForADemBed) {
    EXPECT_FALSE(applies("gravity-tilt", h0({"dampers.pd.model=rigid"})));
    EXPECT_FALSE(applies("gravity-tilt", h0({"arrangements.H-0.gravity_tilt_deg=2"})));
    auto config = h0();
    ASSERT_TRUE(applies("gravity-tilt", config));
    const auto free = switched("gravity-tilt", config);
    ASSERT_EQ(free.size(), config.campaign.arrangements.size());
    EXPECT_EQ(free.front().path, "arrangements.H-0.gravity_tilt_deg");
    EXPECT_EQ(free.front().lo, -10.0);
    EXPECT_EQ(free.front().hi, 10.0);
}

TEST(PhysicsCatalogue, ParticleSizeScatterScattersTheDiametersOfADemBedOfNominalSpheres) {
    const std::string row = "particle-size-scatter";
    EXPECT_FALSE(applies(row, h0({"dampers.pd.model=rigid"})));
    EXPECT_FALSE(applies(row, h0({"dampers.pd.particles.diameter_scatter=0.05"})));
    const auto& signature = catalogue_entry(row).signature;
    ASSERT_EQ(signature.size(), 1U);
    EXPECT_EQ(signature.front().feature, LevelFeature::damping_ratio);
    EXPECT_EQ(signature.front().shape, ScalingShape::inverse);
    EXPECT_EQ(signature.front().sign, +1);
    auto config = h0();
    ASSERT_TRUE(applies(row, config));
    const auto free = switched(row, config);
    EXPECT_EQ(config.campaign.dampers.front().particles.diameter_scatter, 0.005);
    ASSERT_EQ(free.size(), 1U);
    EXPECT_EQ(free.front().path, "dampers.pd.particles.diameter_scatter");
    EXPECT_FALSE(free.front().log_scale);
    EXPECT_EQ(free.front().lo, 0.005);
    EXPECT_EQ(free.front().hi, 0.2);
    EXPECT_NO_THROW(bench::load_campaign_config_text(bench::resolved_config_toml(config), "on"));
    EXPECT_FALSE(applies(row, config));
    // Freed by its key alone, it is searched over its whole declared bound.
    const auto declared =
        parse_free_parameters(h0(), {"dampers.pd.particles.diameter_scatter"}, "--free");
    ASSERT_EQ(declared.size(), 1U);
    EXPECT_EQ(declared.front().lo, 0.0);
    EXPECT_EQ(declared.front().hi, 0.2);
}

TEST(PhysicsCatalogue, ClampComplianceHingesTheClampOnASpringAboutTheDrivenBendingAxis) {
    auto config = h0({"dampers.pd.model=rigid"});
    ASSERT_TRUE(applies("clamp-compliance", config));
    const auto& beam = config.structure.beam;
    const double ei_per_l = beam.youngs_modulus_pa * beam.width_m * std::pow(beam.thickness_m, 3) /
                            12.0 / beam.length_m;
    const auto free = switched("clamp-compliance", config);
    ASSERT_EQ(free.size(), 1U);
    EXPECT_EQ(free.front().path,
              "structure.beam.supports.root_rotational_spring.rotational_stiffness_nm_per_rad[1]");
    EXPECT_TRUE(free.front().log_scale);
    EXPECT_NEAR(free.front().lo, 3.0 * ei_per_l, 1e-9 * ei_per_l);
    EXPECT_NEAR(free.front().hi, 3000.0 * ei_per_l, 1e-9 * ei_per_l);
    ASSERT_EQ(config.structure.beam.supports.size(), 2U);
    EXPECT_EQ(config.structure.beam.supports[0].kind, structure::SupportKind::pinned);
    EXPECT_EQ(config.structure.beam.supports[1].kind, structure::SupportKind::elastic);
    EXPECT_FALSE(applies("clamp-compliance", config));
}

}  // namespace
}  // namespace sb::correlation

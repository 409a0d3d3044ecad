#include "bench/campaign_config.hpp"

#include <gtest/gtest.h>

#include <string>

#include "bench/config_errors.hpp"

namespace sb::bench {
namespace {

const std::string kValidBeam = R"(
[campaign]
name = "t"

[structure]
kind = "beam"

[structure.beam]
length_m = 0.5
width_m = 0.05
thickness_m = 0.003
density_kg_m3 = 2700.0
youngs_modulus_pa = 70e9

[structure.beam.supports.root]
x_m = 0.0
kind = "clamped"

[structure.beam.points]
shaker = 0.1
tip = 0.5

[[structure.beam.masses]]
point = "tip"
mass_kg = 0.01

[structure.excitation]
point = "shaker"
)";

/// Loads `text`, expecting failure; returns the formatted errors.
std::vector<std::string> errors_of(const std::string& text) {
    try {
        load_campaign_config_text(text, "bad.toml");
    } catch (const ConfigException& e) {
        std::vector<std::string> out;
        for (const auto& error : e.errors()) {
            out.push_back(error.format());
        }
        return out;
    }
    ADD_FAILURE() << "the config was accepted";
    return {};
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

TEST(CampaignConfig, AValidBeamConfigLoadsInSi) {
    const auto config = load_campaign_config_text(kValidBeam, "good.toml");
    EXPECT_EQ(config.name, "t");
    EXPECT_DOUBLE_EQ(config.structure.beam.length_m, 0.5);
    ASSERT_EQ(config.structure.beam.masses.size(), 1u);
    EXPECT_DOUBLE_EQ(config.structure.beam.masses[0].x_m, 0.5);
    EXPECT_EQ(config.structure.beam.masses[0].name, "tip");
    EXPECT_FALSE(config.structure.beam.shear_modulus_pa.has_value());
}

TEST(CampaignConfig, ANegativeLengthIsReportedWithItsLine) {
    const auto errors = errors_of(replaced(kValidBeam, "length_m = 0.5", "length_m = -0.5"));
    ASSERT_FALSE(errors.empty());
    EXPECT_EQ(errors[0].rfind("bad.toml:9:12: structure.beam.length_m = -0.5: must be > 0", 0), 0u)
        << errors[0];
}

TEST(CampaignConfig, AnUnknownKeyIsAnError) {
    const auto errors =
        errors_of(replaced(kValidBeam, "width_m = 0.05", "width_m = 0.05\nwdith_m = 0.05"));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].rfind("bad.toml:11:11: structure.beam.wdith_m = 0.05: unknown key", 0), 0u)
        << errors[0];
}

TEST(CampaignConfig, AMassOutsideTheBeamIsReported) {
    const auto errors = errors_of(replaced(kValidBeam, "point = \"tip\"", "x_m = 0.7"));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(
        errors[0].find("bad.toml:24:7: structure.beam.masses[0].x_m = 0.7: must be in [0, 0.5]"),
        std::string::npos)
        << errors[0];
}

TEST(CampaignConfig, AMissingSectionIsReported) {
    const auto errors = errors_of("[campaign]\nname = \"t\"\n");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("structure: is required"), std::string::npos) << errors[0];
}

TEST(CampaignConfig, AMissingBeamTableIsReported) {
    const auto errors = errors_of("[structure]\nkind = \"beam\"\n");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("structure.beam: is required"), std::string::npos) << errors[0];
}

TEST(CampaignConfig, AWrongTypeIsReported) {
    const auto errors =
        errors_of(replaced(kValidBeam, "density_kg_m3 = 2700.0", "density_kg_m3 = \"steel\""));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0],
              "bad.toml:12:17: structure.beam.density_kg_m3 = \"steel\": must be a number "
              "(beam density [kg/m^3])");
}

TEST(CampaignConfig, EveryErrorIsCollectedNotJustTheFirst) {
    std::string text = replaced(kValidBeam, "length_m = 0.5", "length_m = -0.5");
    text = replaced(text, "kind = \"clamped\"", "kind = \"glued\"");
    text = replaced(text, "mass_kg = 0.01", "mass_kg = 0.01\ncolour = \"red\"");
    EXPECT_GE(errors_of(text).size(), 3u);
}

TEST(CampaignConfig, AnUnknownExcitationPointIsReported) {
    const auto errors =
        errors_of(replaced(kValidBeam, "point = \"shaker\"", "point = \"nowhere\""));
    ASSERT_FALSE(errors.empty());
    EXPECT_NE(errors[0].find("structure.excitation.point = "), std::string::npos);
    EXPECT_NE(errors[0].find("nowhere"), std::string::npos) << errors[0];
}

TEST(CampaignConfig, TheBuiltInConfigLoads) {
    const auto config = load_campaign_config_text(builtin_config_text(), kBuiltinConfigName);
    EXPECT_EQ(config.structure.kind, structure::StructureSpec::Kind::beam);
    EXPECT_GE(config.structure.beam.masses.size(), 6u);
}

}  // namespace
}  // namespace sb::bench

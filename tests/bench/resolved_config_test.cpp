// The resolved config: every value written out from the typed model, read back to the same
// campaign and the same hash.
#include "bench/resolved_config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "bench/campaign_config.hpp"
#include "core/text_file.hpp"

namespace sb::bench {
namespace {

std::string shipped(const std::string& name) {
    return read_text_file(std::string(SB_SOURCE_DIR) + "/configs/" + name);
}

TEST(ResolvedConfig, WritesTheDefaultsTheConfigLeftOut) {
    const std::string raw = shipped("paper000-h0.toml");
    ASSERT_EQ(raw.find("early_periods"), std::string::npos);
    const auto config = load_campaign_config_text(raw, "h0.toml");
    const std::string resolved = resolved_config_toml(config);
    for (const char* line : {"early_periods = 3", "drift_horizon_periods = 32",
                             "point_start = \"equivalent-steady-state\"",
                             "time_step_fraction = \"automatic\"", "direction = \"up\"", "seed = 1",
                             "closest_rerun_periods = 4", "normal_stiffness = \"automatic\"",
                             "initial_amplitude = \"automatic\"", "wall_sliding_friction = 0.6"}) {
        EXPECT_NE(resolved.find(std::string("\n") + line + "\n"), std::string::npos) << line << "\n"
                                                                                     << resolved;
    }
}

TEST(ResolvedConfig, EveryShippedConfigReadsBackToItsOwnTextAndHash) {
    int checked = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(SB_SOURCE_DIR) + "/configs")) {
        if (entry.path().extension() != ".toml") continue;
        SCOPED_TRACE(entry.path().filename().string());
        const auto config = load_campaign_config(entry.path());
        const std::string resolved = resolved_config_toml(config);
        const auto again = load_campaign_config_text(resolved, "resolved.toml");
        EXPECT_EQ(config_hash(again), config_hash(config));
        EXPECT_EQ(resolved_config_toml(again), resolved);
        ++checked;
    }
    EXPECT_GE(checked, 5);
}

TEST(ResolvedConfig, AStructureValueChangedInMemoryIsWrittenAndChangesTheHash) {
    auto config = load_campaign_config_text(shipped("paper000-h0.toml"), "h0.toml");
    const std::string before = config_hash(config);
    config.structure.beam.youngs_modulus_pa = 70e9;
    EXPECT_NE(resolved_config_toml(config).find("youngs_modulus_pa = 7e+10\n"), std::string::npos)
        << resolved_config_toml(config);
    EXPECT_NE(config_hash(config), before);
}

TEST(ResolvedConfig, KeyOrderCommentsAndLayoutDoNotChangeTheHash) {
    const std::string a =
        "[structure]\nkind = \"beam\"\n[structure.beam]\nlength_m = 0.5\nwidth_m = 0.05\n"
        "thickness_m = 0.003\ndensity_kg_m3 = 2700.0\nyoungs_modulus_pa = 70e9\n"
        "[structure.beam.supports.root]\nx_m = 0.0\n[structure.beam.points]\nshaker = 0.1\n"
        "[structure.excitation]\npoint = \"shaker\"\n";
    const std::string b =
        "# the same beam, written otherwise\n[structure.excitation]\npoint = 'shaker'\n\n"
        "[structure.beam]\nyoungs_modulus_pa = 7.0e10   # aluminium\ndensity_kg_m3 = 2700\n"
        "thickness_m = 3e-3\nwidth_m = 0.050\nlength_m = 0.5\n"
        "points = { shaker = 0.1 }\nsupports.root = { x_m = 0, kind = \"clamped\" }\n"
        "[structure]\nkind = \"beam\"\n";
    const auto first = load_campaign_config_text(a, "a.toml");
    const auto second = load_campaign_config_text(b, "b.toml");
    EXPECT_EQ(config_hash(first), config_hash(second));
    EXPECT_EQ(canonical_config_text(first), canonical_config_text(second));
}

TEST(ResolvedConfig, AnyChangedValueChangesTheHash) {
    const auto base = load_campaign_config_text(shipped("paper000-h0.toml"), "h0.toml");
    for (const auto& [path, value] : std::vector<std::pair<std::string, std::string>>{
             {"dampers.pd.contact.sliding_friction", "0.45"},
             {"dampers.pd.contact.normal_stiffness", "2e5"},
             {"campaign.seed", "2"},
             {"structure.beam.masses[5].mass_kg", "0.024"},
             {"controller.tolerance", "0.04"},
             {"campaign.point_start", "linear-steady-state"}}) {
        auto changed = base;
        set_value_text(changed, path, value, "test");
        EXPECT_NE(config_hash(changed), config_hash(base)) << path;
    }
}

}  // namespace
}  // namespace sb::bench

// The resolved config: every default written out, and it loads back to the same campaign.
#include "bench/resolved_config.hpp"

#include <gtest/gtest.h>

#include <string>

#include "bench/campaign_config.hpp"
#include "bench/sweep_checkpoint.hpp"

namespace sb::bench {
namespace {

TEST(ResolvedConfig, WritesTheDefaultsTheConfigLeftOut) {
    const std::string raw = read_file(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    ASSERT_EQ(raw.find("early_periods"), std::string::npos);
    const auto config = load_campaign_config_text(raw, "h0.toml");
    const std::string resolved = resolved_config_toml(config, raw);
    for (const char* line : {"early_periods = 3", "drift_horizon_periods = 32",
                             "point_start = 'previous-state'", "time_step_fraction = 0.05",
                             "direction = 'up'", "seed = 1", "closest_rerun_periods = 4"}) {
        EXPECT_NE(resolved.find(line), std::string::npos) << line << "\n" << resolved;
    }
}

TEST(ResolvedConfig, LoadsBackToTheSameCampaign) {
    const std::string raw =
        read_file(std::string(SB_SOURCE_DIR) + "/configs/paper000-campaign.toml");
    const auto config = load_campaign_config_text(raw, "campaign.toml");
    const std::string resolved = resolved_config_toml(config, raw);
    const auto again = load_campaign_config_text(resolved, "resolved.toml");
    // Written again, the text does not change: nothing was lost or reinterpreted.
    EXPECT_EQ(resolved_config_toml(again, resolved), resolved);
    EXPECT_EQ(again.name, config.name);
    EXPECT_EQ(again.campaign.levels_g, config.campaign.levels_g);
    ASSERT_EQ(again.campaign.arrangements.size(), config.campaign.arrangements.size());
    for (std::size_t i = 0; i < config.campaign.arrangements.size(); ++i) {
        const auto& a = config.campaign.arrangements[i];
        const auto& b = again.campaign.arrangements[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.damper_angle_deg, b.damper_angle_deg);
        EXPECT_EQ(a.block_mass_kg, b.block_mass_kg);
        EXPECT_EQ(a.block_cathetus_m, b.block_cathetus_m);
        EXPECT_EQ(a.mount_lift_m, b.mount_lift_m);
    }
    EXPECT_EQ(again.structure.beam.masses.size(), config.structure.beam.masses.size());
    EXPECT_EQ(again.campaign.dampers.front().solver.contact.particle_wall.sliding_friction,
              config.campaign.dampers.front().solver.contact.particle_wall.sliding_friction);
}

}  // namespace
}  // namespace sb::bench

// Whole campaigns: the bench against the linear model when the particles are a rigid mass,
// and the outputs a campaign writes.
#include "bench/campaign.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "bench/config_errors.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "campaign_fixtures.hpp"
#include "identification/recording_io.hpp"
#include "structure/frf.hpp"
#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::bench {
namespace {

namespace fs = std::filesystem;
using test::fresh_dir;
using test::paper000_h0_with;

/// Rigid particles: the campaign is a linear stepped-sine test of the structure, so the
/// controller, the coupling loop, the harmonic extraction and the identification together
/// must give back the linear model's accelerance and its 0.5 % damping.
TEST(Campaign, WithRigidParticlesTheFrfAndDampingEqualTheLinearModel) {
    const std::string text = paper000_h0_with({
        {"point = \"damper\"", "point = \"damper\"\nmodel = \"rigid\""},
        {"levels_g", "levels_g = [1.0]"},
        {"low_ratio", "low_ratio = 0.985"},
        {"high_ratio", "high_ratio = 1.015"},
        {"count", "count = 15"},
        {"grid_damping_ratio", "grid_damping_ratio = 0.005"},
    });
    const auto config = load_campaign_config_text(text, "rigid.toml");
    CampaignRunOptions options;
    options.out_dir = fresh_dir("rigid");
    options.config_text = text;
    const auto summary = run_campaign(config, options);
    EXPECT_EQ(summary.points, 15);
    EXPECT_EQ(summary.converged, 15);

    const auto spec = arrangement_structure(config, config.campaign.arrangements[0], true);
    const auto model = structure::build_linear_model(spec, config.base_dir);
    const auto basis = structure::compute_modes(model, spec.damping, spec.modes);
    const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();

    const auto recording = identification::read_recording(options.out_dir);
    ASSERT_EQ(recording.points.size(), 15u);
    const auto force = recording.channel_index("force");
    const auto acc = recording.channel_index("acc_damper");
    // design.md: the campaign's FRF equals the linear model's within 2 %.
    constexpr double kFrfTolerance = 0.02;
    for (const auto& row : recording.points) {
        const auto measured = row.values[acc].amplitude / row.values[force].amplitude;
        const auto exact =
            structure::modal_accelerance(model, basis, "damper", z, "shaker", z, row.frequency_hz);
        EXPECT_NEAR(std::abs(measured) / std::abs(exact), 1.0, kFrfTolerance)
            << row.frequency_hz << " Hz";
        EXPECT_NEAR(std::arg(measured / exact), 0.0, kFrfTolerance) << row.frequency_hz << " Hz";
        EXPECT_NEAR(row.values[acc].rms, 9.80665, 0.05 * 9.80665) << "level held at 1 g";
    }
    // ... and its damping: 0.5 % by half-power and circle fit, within 2 % (relative).
    int methods = 0;
    for (const auto& row : recording.damping) {
        EXPECT_NEAR(row.damping_ratio, 0.005, 0.02 * 0.005) << row.method;
        ++methods;
    }
    EXPECT_EQ(methods, 2);
    EXPECT_TRUE(fs::exists(options.out_dir / "frf.uff"));
    EXPECT_TRUE(fs::exists(options.out_dir / "control.csv"));
    EXPECT_TRUE(fs::exists(options.out_dir / "provenance.toml"));
}

TEST(Campaign, ARunWithoutLevelsIsAConfigError) {
    const std::string text = paper000_h0_with({{"levels_g", "levels_g = []"}});
    const auto config = load_campaign_config_text(text, "nolevels.toml");
    CampaignRunOptions options;
    options.out_dir = fresh_dir("nolevels");
    EXPECT_THROW(run_campaign(config, options), ConfigException);
}

}  // namespace
}  // namespace sb::bench

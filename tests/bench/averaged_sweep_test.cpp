// A chaotic damper controlled on block means: paper 003's single rubber sphere in its 10 mm
// gap at 3 g, where one period's RMS at the casing differs from the next by up to 15 %.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"

namespace sb::bench {
namespace {

/// The rig's own damping, the empty casing's, which configs/paper003-beam.toml gives its beam.
constexpr double kRigDamping = 0.01382;

CampaignConfig paper003_at(const std::string& level_rms_g) {
    CampaignConfig config =
        load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper003-beam.toml");
    set_value_text(config, "campaign.levels_g", "[" + level_rms_g + "]", "test");
    return config;
}

TEST(AveragedSweep, AChaoticSphereIsControlledOnBlockMeansAndItsDampingShows) {
    // The shipped config judges means of 32 periods: every point of the sweep converges, and the
    // beam's circle-fit damping lies above the rig's own by the sphere's share. One filling's
    // share scatters widely: -0.01 to +0.27 % over eight fillings (docs/validation.md; which
    // share a filling gives also moves with the machine's floating-point library, the sphere
    // being chaotic), so the share is judged on the mean of eight fillings against its
    // standard error, not on one filling.
    constexpr int kFillings = 8;
    CampaignConfig config = paper003_at("2.12132034");  // 3 g peak
    ASSERT_EQ(config.campaign.controller.average_periods, 32);
    set_value_text(config, "campaign.seeds", std::to_string(kFillings), "test");
    CampaignContext context;
    context.threads = 2;
    const CampaignResult result = run_campaign(config, context);
    ASSERT_FALSE(result.recording.points.empty());
    for (const auto& point : result.recording.points) {
        EXPECT_EQ(point.status, "converged") << point.frequency_hz << " Hz";
    }
    std::vector<double> share;  // circle-fit damping above the rig's, per filling
    for (const auto& level : result.levels) {
        ASSERT_EQ(level.circle_fit.status, identification::EstimateStatus::ok)
            << "filling " << level.filling << ": " << level.circle_fit.message;
        EXPECT_LT(level.circle_fit.damping_ratio,
                  2.0 * kRigDamping);  // the paper's 4.3 %: out of reach
        share.push_back(level.circle_fit.damping_ratio - kRigDamping);
    }
    ASSERT_EQ(share.size(), static_cast<std::size_t>(kFillings));
    double mean = 0.0;
    for (double x : share) mean += x / kFillings;
    double variance = 0.0;
    for (double x : share) variance += (x - mean) * (x - mean) / (kFillings - 1);
    const double standard_error = std::sqrt(variance / kFillings);
    // Three standard errors: a sphere that added nothing would pass about one time in a hundred
    // (Student's t with 7 degrees of freedom); measured here 4.3.
    EXPECT_GT(mean, 3.0 * standard_error)
        << "mean share " << mean << ", standard error " << standard_error;
    EXPECT_GT(mean, 0.0005);  // and more than the fit's own error on this beam (0.004 %)
}

TEST(AveragedSweep, SinglePeriodsLeaveTheSameSweepUnsettled) {
    // The same points judged period by period within the same budget: the windows of single
    // periods scatter beyond the tolerance and most points fall back to the closest amplitude
    // (10 of 11 measured).
    CampaignConfig config = paper003_at("2.12132034");
    set_value_text(config, "controller.average_periods", "1", "test");
    set_value_text(config, "controller.window_periods", "32", "test");
    set_value_text(config, "controller.max_periods", "400", "test");
    CampaignContext context;
    context.threads = 1;
    const CampaignResult result = run_campaign(config, context);
    int closest = 0;
    for (const auto& point : result.recording.points) closest += point.status == "closest";
    EXPECT_GT(2 * closest, static_cast<int>(result.recording.points.size()));
}

}  // namespace
}  // namespace sb::bench

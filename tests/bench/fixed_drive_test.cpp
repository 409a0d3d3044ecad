// The open-loop drive (campaign.drive.kind = "fixed") on the linear paper-000 bench: every
// point at the given amplitude, the response the structure's exact steady state, in the run
// and in the prediction; a base displacement drives (2 pi f)^2 X; bad combinations refused.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "bench/campaign.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/prediction.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"
#include "structure/frf.hpp"

namespace sb::bench {
namespace {

/// The linear bench (particles as rigid mass) at fixed force amplitudes of 0.05 and 0.2 N,
/// seven frequencies over ±4 % of the mode.
CampaignConfig fixed_force_bench() {
    auto config = test::linear_paper000_bench(7);
    config.campaign.levels_g.clear();
    config.campaign.drive.kind = DriveSpec::Kind::fixed;
    config.campaign.drive.amplitudes = {0.05, 0.2};
    config.campaign.frequencies.refine_points = 0;
    return config;
}

/// Control channel over reference channel of a row: the recorded accelerance.
std::complex<double> recorded_ratio(const identification::PointRow& row) {
    return row.values[1].amplitude / row.values[0].amplitude;
}

TEST(FixedDrive, EveryPointIsDrivenAtItsAmplitudeAndRecordsTheExactSteadyState) {
    const auto config = fixed_force_bench();
    CampaignContext context;
    context.threads = 2;
    const CampaignResult run = run_campaign(config, context);
    const CampaignResult predicted = predict_campaign(config, {});
    const auto plan = plan_campaign(config, {});
    ASSERT_EQ(plan.tasks.front().level_unit, "N");
    EXPECT_NE(plan.tasks.front().key.find("0.05N"), std::string::npos) << plan.tasks.front().key;
    const auto& prepared = plan.arrangements.front();
    const Eigen::Vector3d d = config.structure.excitation.direction.normalized();
    for (const auto* result : {&run, &predicted}) {
        const char* which = result == &run ? "run" : "prediction";
        ASSERT_EQ(result->recording.points.size(), 14U) << which;
        for (const auto& row : result->recording.points) {
            // The level column holds the amplitude the point was driven at, unchanged.
            EXPECT_TRUE(row.level_g == 0.05 || row.level_g == 0.2) << row.level_g;
            EXPECT_NEAR(std::abs(row.values[0].amplitude), row.level_g, 1e-9 * row.level_g)
                << which << " " << row.frequency_hz;
            EXPECT_TRUE(row.status == "converged" || row.status == "predicted") << row.status;
            // The structure's own accelerance (modal, rigid particles) from the model.
            const auto exact = structure::modal_accelerance(
                prepared.model, prepared.basis, config.campaign.control_point, d,
                config.structure.excitation.point, d, row.frequency_hz);
            EXPECT_LT(std::abs(recorded_ratio(row) - exact), 0.01 * std::abs(exact))
                << which << " " << row.level_g << " N " << row.frequency_hz << " Hz";
        }
    }
}

TEST(FixedDrive, ABaseDisplacementDrivesTheBaseAccelerationOmegaSquaredX) {
    auto config = test::linear_paper000_bench(5);
    apply_overrides(
        config,
        {"structure.excitation.kind=\"base\"", "structure.excitation.support=\"root\"",
         "campaign.levels_g=[]", "campaign.drive.kind=\"fixed\"",
         "campaign.drive.quantity=\"base-displacement\"", "campaign.drive.amplitudes=[2e-4]"});
    config.campaign.frequencies.refine_points = 0;
    CampaignContext context;
    context.threads = 2;
    const CampaignResult run = run_campaign(config, context);
    ASSERT_EQ(run.recording.points.size(), 5U);
    for (const auto& row : run.recording.points) {
        const double w = 2.0 * std::numbers::pi * row.frequency_hz;
        EXPECT_NEAR(std::abs(row.values[0].amplitude), w * w * 2e-4, 1e-9 * w * w * 2e-4)
            << row.frequency_hz;
        EXPECT_EQ(row.status, "converged");
    }
    EXPECT_EQ(plan_campaign(config, {}).tasks.front().level_unit, "m");
}

TEST(FixedDrive, ContradictoryDriveKeysAreRefusedAtTheirKeys) {
    const auto refused = [](const std::vector<std::string>& overrides, const std::string& key,
                            const std::string& words) {
        auto config = test::linear_paper000_bench(5);
        try {
            apply_overrides(config, overrides);
            ADD_FAILURE() << "accepted: " << overrides.back();
        } catch (const config::ConfigException& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(key), std::string::npos) << what;
            EXPECT_NE(what.find(words), std::string::npos) << what;
        }
    };
    // Both a controller's targets and fixed amplitudes.
    refused({"campaign.drive.kind=\"fixed\"", "campaign.drive.amplitudes=[1.0]"},
            "campaign.levels_g", "is not used with campaign.drive.kind = \"fixed\"");
    refused({"campaign.levels_g=[]", "campaign.drive.kind=\"fixed\""}, "campaign.drive.amplitudes",
            "is required");
    refused({"campaign.drive.amplitudes=[1.0]"}, "campaign.drive.amplitudes",
            "needs campaign.drive.kind = \"fixed\"");
    refused({"campaign.levels_g=[]", "campaign.drive.kind=\"fixed\"",
             "campaign.drive.quantity=\"base-displacement\"", "campaign.drive.amplitudes=[1e-3]"},
            "campaign.drive.quantity", "needs base excitation");
}

}  // namespace
}  // namespace sb::bench

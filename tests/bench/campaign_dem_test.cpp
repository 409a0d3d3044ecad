// A real (DEM) campaign: paper 000's H-0 sweep at 1, 2 and 3 g.
#include <gtest/gtest.h>

#include "bench/campaign.hpp"
#include "campaign_fixtures.hpp"
#include "identification/damping_curve.hpp"
#include "identification/recording_io.hpp"

namespace sb::bench {
namespace {

using test::fresh_dir;
using test::paper000_h0_with;

/// Paper 000's H-0 sweep with simulated particles at 1, 2 and 3 g: every point ends converged
/// or flagged, and the particles damp the first mode well above the empty beam's 0.5 %.
TEST(Campaign, ARealH0CampaignDampsWellAboveTheEmptyBeam) {
    // The shipped grid and budget: with seven frequencies the steps near resonance are small
    // enough for the warm start, and fewer points run out of budget than with six (whose
    // `closest` points cost more periods than the seventh frequency).
    const std::string text = paper000_h0_with({
        // Softer contacts (5 % overlap at the largest impact speed) double the time step;
        // the damping of a fluidised bed barely depends on it.
        {"max_overlap_fraction", "max_overlap_fraction = 0.05"},
    });
    const auto config = load_campaign_config_text(text, "real.toml");
    CampaignRunOptions options;
    options.out_dir = fresh_dir("real");
    options.config_text = text;
    options.threads = 2;
    const auto summary = run_campaign(config, options);
    // Seven frequencies at each of three levels, and those the grid refinement adds where a
    // level's estimates are unresolved (it depends on the fillings' chaotic response, which
    // differs from one machine's floating-point library to another's).
    EXPECT_GE(summary.points, 21);
    EXPECT_EQ(summary.converged + summary.limit_cycle + summary.closest, summary.points);
    // Near resonance at 2-3 g the bed's response takes 15-20 periods to follow an amplitude
    // change, so some points spend their 40-period budget (5 to 6 of 21 observed, most at
    // 3 g); a controller or coupling that failed would leave most of them there, so the bound
    // is a third of the points.
    const int kMostClosest = summary.points / 3;
    EXPECT_LE(summary.closest, kMostClosest);

    const auto recording = identification::read_recording(options.out_dir);
    ASSERT_EQ(recording.points.size(), static_cast<std::size_t>(summary.points));
    const auto acc = recording.channel_index("acc_damper");
    const double tolerance = config.campaign.controller.tolerance;
    // The recorded RMS is over the whole window, the controller's level the mean of the
    // periods' RMS values; for values within the tolerance of each other the two differ by
    // less than a tenth of a percent.
    constexpr double kWindowRmsOverMeanRms = 1e-3;
    for (const auto& row : recording.points) {
        if (row.status == "closest") continue;
        const double target = 9.80665 * row.level_g;
        EXPECT_NEAR(row.values[acc].rms / target, 1.0, tolerance + kWindowRmsOverMeanRms)
            << row.status << " at " << row.level_g << " g, " << row.frequency_hz << " Hz";
    }
    // "Well above": at least twice the empty beam's 0.5 % at 2 and 3 g, by every method that
    // resolved the band, and at least one did at each level. All three estimators count: on
    // the short shipped grid the band at 3 g (about 2 % damping, 0.25 Hz) holds fewer points
    // than half-power and the circle fit need, and they say so instead of returning a number.
    constexpr double kEmptyBeamDamping = 0.005;
    const auto levels = identification::identify_recording(recording);
    for (double level : {2.0, 3.0}) {
        int found = 0;
        for (const auto& l : levels) {
            if (l.level_g != level) continue;
            for (const auto* e : {&l.half_power, &l.circle_fit, &l.rational_fraction}) {
                if (!e->ok()) continue;
                EXPECT_GT(e->damping_ratio, 2.0 * kEmptyBeamDamping) << "at " << level << " g";
                ++found;
            }
        }
        EXPECT_GE(found, 1) << "no damping identified at " << level << " g";
    }
}

}  // namespace
}  // namespace sb::bench

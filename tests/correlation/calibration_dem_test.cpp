// Calibrating the particles' friction on the coupled DEM campaign, on a recording simulated by
// ShakerBench with known friction (other fillings of the bed than the calibration's, 2 %
// noise): near the onset of particle motion the data inform the sliding friction; in the
// collisional regime they do not, and the report must say so instead of giving a number.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration_fixtures.hpp"
#include "core/text_file.hpp"
#include "correlation/calibration.hpp"

namespace sb::correlation {
namespace {

namespace fs = std::filesystem;
using testing::fresh_dir;

constexpr double kTrueSliding = 0.45;
constexpr double kTrueRolling = 0.02;

/// The golden bed (30 particles, H-0) at `levels`, two fillings per level.
bench::CampaignConfig small_bed(const std::string& levels) {
    auto config = bench::load_campaign_config(std::string(SB_SOURCE_DIR) +
                                              "/tests/bench/golden/small-h0.toml");
    bench::apply_overrides(config, {"campaign.levels_g=" + levels, "campaign.seeds=2",
                                    "dampers.pd.contact.sliding_friction=0.3",
                                    "dampers.pd.contact.rolling_friction=0.0"});
    return config;
}

/// The measurement: the same bed with the true friction, filled with other seeds.
fs::path measured(const std::string& name, const std::string& levels) {
    auto config = small_bed(levels);
    bench::apply_overrides(
        config,
        {"dampers.pd.contact.sliding_friction=" + exact_text(kTrueSliding),
         "dampers.pd.contact.rolling_friction=" + exact_text(kTrueRolling), "campaign.seed=101"});
    bench::CampaignContext context;
    context.threads = 2;
    const auto dir = fresh_dir(name);
    testing::write_noisy_recording(bench::run_campaign(config, context), 0.02, 11, dir);
    return dir;
}

std::vector<FreeParameter> friction(const bench::CampaignConfig& config) {
    return parse_free_parameters(
        config, {"dampers.pd.contact.sliding_friction", "dampers.pd.contact.rolling_friction"});
}

/// Recovered within 10 %, or reported as not identifiable: never a wrong number.
void expect_recovered_or_flagged(const CalibrationResult& r) {
    ASSERT_EQ(r.findings.size(), 2U) << r.findings_note;
    const double truth[] = {kTrueSliding, kTrueRolling};
    for (std::size_t j = 0; j < 2; ++j) {
        const auto& f = r.findings[j];
        if (f.identifiable) {
            EXPECT_NEAR(f.value, truth[j], 0.1 * truth[j]) << f.parameter.path << ": " << f.reason;
        }
        // Either way the 95 % interval holds the truth.
        EXPECT_LE(f.lo95, truth[j] * 1.1) << f.parameter.path;
        EXPECT_GE(f.hi95, truth[j] * 0.9) << f.parameter.path;
    }
}

TEST(CalibrationDem,
     NearTheOnsetOfSlidingTheFrictionIsRecoveredOrFlaggedAndTheSurrogateNeedsFewerSimulations) {
    const auto config = small_bed("[0.4]");
    const auto m = read_measurement(measured("onset", "[0.4]"), {0.02, 0.002, 0.02});
    CalibrationOptions options;
    options.threads = 2;
    options.search.mode = SearchMode::direct;
    options.search.budget = 14;
    const auto direct = calibrate(config, m, friction(config), options);
    expect_recovered_or_flagged(direct);
    EXPECT_LT(direct.best.misfit, direct.start.misfit);

    options.search.mode = SearchMode::surrogate;
    options.search.budget = 10;
    const auto surrogate = calibrate(config, m, friction(config), options);
    expect_recovered_or_flagged(surrogate);
    EXPECT_LT(surrogate.simulations, direct.simulations);
}

TEST(CalibrationDem, InTheCollisionalRegimeTheSlidingFrictionIsReportedNotIdentifiable) {
    auto config = small_bed("[2.0, 3.0]");
    bench::apply_overrides(config, {"campaign.seeds=1"});
    const auto m = read_measurement(measured("collisional", "[2.0, 3.0]"), {0.02, 0.002, 0.02});
    CalibrationOptions options;
    options.threads = 2;
    options.search.mode = SearchMode::surrogate;
    options.search.budget = 8;
    const auto r = calibrate(config, m, friction(config), options);
    ASSERT_EQ(r.findings.size(), 2U) << r.findings_note;
    EXPECT_FALSE(r.findings[0].identifiable) << r.findings[0].reason;
    const auto out = fresh_dir("collisional-report");
    write_calibration(out, r, m, "test");
    const std::string report = read_text_file(out / "report.md");
    EXPECT_NE(report.find("not identifiable"), std::string::npos);
}

}  // namespace
}  // namespace sb::correlation

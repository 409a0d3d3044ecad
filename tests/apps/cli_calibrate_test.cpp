// `shakerbench calibrate` from the command line: a linear campaign calibrated against its own
// recording, and bad input named with a non-zero exit.
#include <gtest/gtest.h>
#include <unistd.h>

#include "campaign_files.hpp"
#include "cli_helpers.hpp"

namespace sb::test {
namespace {

namespace fs = std::filesystem;

TEST(CliCalibrate, ALinearCampaignCalibratedAgainstItsOwnRecordingWritesTheReport) {
    const auto dir = temp_dir("calibrate-" + std::to_string(getpid()));
    const auto config = write_rigid_campaign(dir);
    const auto measured = dir / "measured";
    ASSERT_EQ(run("run " + config.string() + " --out " + measured.string() + " -q").exit_code, 0);
    const auto out = dir / "calibrated";
    const auto r = run("calibrate " + config.string() + " --measured " + measured.string() +
                       " --free structure.damping.default_ratio=0.002:0.02 --budget 3 --out " +
                       out.string() + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("structure.damping.default_ratio"), std::string::npos) << r.output;
    for (const char* name :
         {"calibration.toml", "report.md", "calibrated.toml", "evaluations.csv"}) {
        EXPECT_TRUE(fs::exists(out / name)) << name;
    }
    EXPECT_FALSE(fs::is_empty(out / "cache"));
    // The calibrated config runs.
    EXPECT_EQ(run("keys " + (out / "calibrated.toml").string()).exit_code, 0);
}

TEST(CliCalibrate, BadFreeKeysAndAMissingRecordingAreNamedWithExitTwo) {
    const auto dir = temp_dir("calibrate-bad-" + std::to_string(getpid()));
    const auto config = write_rigid_campaign(dir);
    const auto bad = run("calibrate " + config.string() + " --measured " + dir.string() +
                         " --free dampers.pd.contact.no_such=0:1 --free structure.beam.length_m");
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find("--free: dampers.pd.contact.no_such = 0:1: names no value"),
              std::string::npos)
        << bad.output;
    EXPECT_NE(bad.output.find("length_m: has no default search interval"), std::string::npos)
        << bad.output;
    const auto missing =
        run("calibrate " + config.string() + " --measured " + (dir / "no-such-recording").string() +
            " --free structure.damping.default_ratio=0.002:0.02");
    EXPECT_EQ(missing.exit_code, 2) << missing.output;
    EXPECT_NE(missing.output.find("not a recording directory"), std::string::npos)
        << missing.output;
    EXPECT_NE(run("calibrate " + config.string()).exit_code, 0);  // --measured is required
    // Without --free the default set is the DEM dampers' friction and restitution: a config
    // with none says so.
    const auto none = run("calibrate " + config.string() + " --measured " + dir.string());
    EXPECT_EQ(none.exit_code, 2) << none.output;
    EXPECT_NE(none.output.find("no damper with model = \"dem\""), std::string::npos) << none.output;
}

}  // namespace
}  // namespace sb::test

// `shakerbench diagnose` from the command line: a linear campaign measured with more damping
// than its config says is located and the physics confirmed on the coupled campaign, its own
// recording is not, bad input is named.
#include <gtest/gtest.h>
#include <unistd.h>

#include "campaign_files.hpp"
#include "cli_helpers.hpp"

namespace sb::test {
namespace {

namespace fs = std::filesystem;

/// The linear campaign at 1, 2 and 3 g on nine frequencies over ±4 % of the mode (enough for
/// the damping estimators).
const std::string kLevels =
    " --set 'campaign.levels_g=[1.0, 2.0, 3.0]' --set campaign.frequencies.count=9"
    " --set campaign.frequencies.low_ratio=0.96 --set campaign.frequencies.high_ratio=1.04";

TEST(CliDiagnose, MoreDampingThanTheConfigSaysIsLocatedAndItsOwnRecordingIsNot) {
    const auto dir = temp_dir("diagnose-" + std::to_string(getpid()));
    const auto config = write_rigid_campaign(dir).string();
    const auto measured = dir / "measured";
    ASSERT_EQ(run("run " + config + kLevels +
                  " --set structure.damping.default_ratio=0.008 --out " + measured.string() + " -q")
                  .exit_code,
              0);
    const auto out = dir / "diagnosis";
    const auto r =
        run("diagnose " + config + kLevels + " --measured " + measured.string() +
            " --drift structure.damping.default_ratio=0.002:0.02 --out " + out.string() + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("mismatch beyond the noise: H-0 damping ratio"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("H-0: the damping ratio disagrees beyond the noise"), std::string::npos)
        << r.output;
    // The damping is level-independent in both: no drift.
    EXPECT_NE(r.output.find("no drift beyond the noise"), std::string::npos) << r.output;
    const auto toml = file_text(out / "diagnosis.toml");
    EXPECT_NE(toml.find("mismatch = true\n"), std::string::npos) << toml;
    EXPECT_NE(toml.find("feature = \"damping ratio\"\nbeyond_noise = true\n"), std::string::npos)
        << toml;
    EXPECT_TRUE(fs::exists(out / "report.md"));
    // The winner, fitted on the prediction, is run again by the coupled campaign: the
    // recording's own simulation, so the misfits fall there too.
    EXPECT_NE(toml.find("[hypotheses.confirmation]\nsimulation = \"the coupled campaign\"\n"
                        "confirmed = true\n"),
              std::string::npos)
        << toml;
    EXPECT_NE(file_text(out / "report.md").find("confirmed on the coupled campaign: misfit"),
              std::string::npos);

    // The config that made the recording: nothing to report.
    const auto same = run("diagnose " + config + kLevels +
                          " --set structure.damping.default_ratio=0.008 --measured " +
                          measured.string() + " --out " + (dir / "same").string() + " -q");
    ASSERT_EQ(same.exit_code, 0) << same.output;
    EXPECT_NE(same.output.find("no significant mismatch"), std::string::npos) << same.output;
    EXPECT_NE(file_text(dir / "same" / "diagnosis.toml").find("mismatch = false\n"),
              std::string::npos);
}

TEST(CliDiagnose, AMissingRecordingAndABadDriftKeyAreNamedWithExitTwo) {
    const auto dir = temp_dir("diagnose-bad-" + std::to_string(getpid()));
    const auto config = write_rigid_campaign(dir).string();
    const auto missing = run("diagnose " + config + " --measured " + (dir / "none").string());
    EXPECT_EQ(missing.exit_code, 2) << missing.output;
    EXPECT_NE(missing.output.find("not a recording directory"), std::string::npos)
        << missing.output;
    const auto bad = run("diagnose " + config + " --measured " + dir.string() +
                         " --drift dampers.pd.contact.no_such=0:1");
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find("dampers.pd.contact.no_such"), std::string::npos) << bad.output;
    EXPECT_NE(run("diagnose " + config).exit_code, 0);  // --measured is required
}

}  // namespace
}  // namespace sb::test

// End-to-end campaigns through the shakerbench executable: resume after a hard kill.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "campaign_files.hpp"
#include "cli_helpers.hpp"

namespace {

using namespace sb::test;

TEST(Cli, AKilledCampaignResumesToTheSameFilesAsAnUninterruptedOne) {
    // The process id keeps concurrent runs from resuming each other's checkpoints.
    const auto dir = temp_dir("resume-" + std::to_string(getpid()));
    const auto config = write_small_campaign(dir);
    const auto whole = dir / "whole";
    const auto resumed = dir / "resumed";
    const auto r = run("run " + config.string() + " --out " + whole.string() + " -j 1 -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;

    // Start the same campaign, kill it hard once its first point is checkpointed.
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        execl(SB_CLI, SB_CLI, "run", config.c_str(), "--out", resumed.c_str(), "-j", "1", "-q",
              static_cast<char*>(nullptr));
        _exit(127);
    }
    const auto checkpoint = resumed / "checkpoints" / "H-0_2g.txt";
    bool killed_mid_campaign = false;
    for (int i = 0; i < 60000; ++i) {
        const std::string text = file_text(checkpoint);
        if (text.find("points_done 1\n") != std::string::npos) {
            kill(child, SIGKILL);
            killed_mid_campaign = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(killed_mid_campaign) << "the first point was never checkpointed";
    ASSERT_FALSE(std::filesystem::exists(resumed / "points.csv")) << "killed too late";

    const auto again = run("run " + config.string() + " --out " + resumed.string() + " -j 1 -q");
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("1 taken from checkpoints"), std::string::npos) << again.output;
    // Every file, byte for byte, except the provenance (date, command) and the plot script
    // (it names its own directory).
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(whole)) {
        if (!entry.is_regular_file()) continue;
        const auto name = std::filesystem::relative(entry.path(), whole).string();
        if (name == "provenance.toml" || name == "plots/plots.gp") continue;
        names.push_back(name);
        EXPECT_EQ(file_text(entry.path()), file_text(resumed / name)) << name;
    }
    for (const char* name : {"points.csv", "control.csv", "frf.uff", "recording.toml",
                             "damping.csv", "config.toml", "config.resolved.toml"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    }
    // damping.csv holds rows (both methods resolved the band), not only its header.
    const std::string damping = file_text(whole / "damping.csv");
    EXPECT_GE(std::count(damping.begin(), damping.end(), '\n'), 2) << damping;
}

/// The config_hash line of a provenance or resolved config file.
std::string hash_in(const std::filesystem::path& file) {
    const std::string text = file_text(file);
    const std::string key = "config_hash = \"";
    const auto at = text.find(key);
    return at == std::string::npos ? "" : text.substr(at + key.size(), 16);
}

TEST(CliSet, ARunWithASetValueWritesItAndRefusesAnotherConfigsCheckpoints) {
    const auto dir = temp_dir("set-run-" + std::to_string(getpid()));
    const auto config = write_rigid_campaign(dir);
    const auto out = dir / "out";
    const auto first = run("run " + config.string() + " --out " + out.string() + " -q");
    ASSERT_EQ(first.exit_code, 0) << first.output;
    const std::string first_hash = hash_in(out / "provenance.toml");
    ASSERT_EQ(first_hash.size(), 16u);
    EXPECT_EQ(hash_in(out / "config.resolved.toml"), first_hash);
    const std::string points = file_text(out / "points.csv");

    const std::string set = " --set dampers.pd.contact.sliding_friction=0.45";
    const auto refused = run("run " + config.string() + " --out " + out.string() + " -q" + set);
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_NE(refused.output.find(first_hash), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find("--restart"), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find("nothing was simulated"), std::string::npos) << refused.output;
    EXPECT_EQ(file_text(out / "points.csv"), points);
    EXPECT_EQ(hash_in(out / "provenance.toml"), first_hash);

    const auto again =
        run("run " + config.string() + " --out " + out.string() + set + " --restart");
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("0 taken from checkpoints"), std::string::npos) << again.output;
    const std::string resolved = file_text(out / "config.resolved.toml");
    EXPECT_NE(resolved.find("\nsliding_friction = 0.45\n"), std::string::npos) << resolved;
    const std::string second_hash = hash_in(out / "provenance.toml");
    EXPECT_EQ(second_hash.size(), 16u);
    EXPECT_NE(second_hash, first_hash);
    EXPECT_NE(file_text(out / "provenance.toml").find("--set 'dampers.pd.contact.sliding_friction"),
              std::string::npos);
}

TEST(Cli, RunWithABadConfigExitsTwoBeforeSimulating) {
    const auto dir = temp_dir("run-bad-" + std::to_string(getpid()));
    const auto file = dir / "bad.toml";
    std::ofstream(file) << file_text(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml")
                        << "\n[dampers.pd2]\npoint = \"nowhere\"\n";
    const auto r = run("run " + file.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("dampers.pd2.point = \"nowhere\": must name a point"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "points.csv"));
}

}  // namespace

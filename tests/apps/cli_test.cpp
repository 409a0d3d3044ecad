// End-to-end checks of the shakerbench executable: exit codes and messages users see.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

struct Result {
    int exit_code = -1;
    std::string output;  // stdout and stderr together
};

Result run(const std::string& arguments) {
    const std::string command = std::string(SB_CLI) + " " + arguments + " 2>&1";
    Result result;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    std::array<char, 4096> buffer{};
    while (fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) {
        result.output += buffer.data();
    }
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

std::filesystem::path temp_dir(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("shakerbench-cli-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

TEST(Cli, HelpListsTheSubcommandsAndExitsZero) {
    const auto r = run("--help");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.output.find("modes"), std::string::npos) << r.output;
}

TEST(Cli, VersionPrintsTheVersion) {
    const auto r = run("--version");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.output.find("shakerbench 0."), std::string::npos) << r.output;
}

TEST(Cli, AnUnknownSubcommandIsBadInput) {
    const auto r = run("shake-it");
    EXPECT_EQ(r.exit_code, 2) << r.output;
}

TEST(Cli, AMissingConfigFileIsBadInputNamingTheFile) {
    const auto r = run("modes /nonexistent/campaign.toml");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("/nonexistent/campaign.toml"), std::string::npos) << r.output;
}

TEST(Cli, ABadConfigGivesFileLineKeyAndExitCodeTwo) {
    const auto dir = temp_dir("bad");
    const auto file = dir / "bad.toml";
    std::ofstream(file) << "[structure]\nkind = \"beam\"\n[structure.beam]\nlength_m = -1.0\n"
                           "width_m = 0.05\nthickness_m = 0.003\ndensity_kg_m3 = 2700.0\n"
                           "youngs_modulus_pa = 7e10\n[structure.beam.supports.root]\nx_m = 0.0\n";
    const auto r = run("modes " + file.string() + " --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(file.string() + ":4:12: structure.beam.length_m = -1: must be > 0"),
              std::string::npos)
        << r.output;
}

TEST(Cli, ModesOnTheBuiltInBeamPrintsTheFirstModeAndWritesShapes) {
    const auto dir = temp_dir("modes");
    const auto r = run("modes --out " + dir.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("frequency [Hz]"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "paper000-beam-modes.csv"));
}

}  // namespace

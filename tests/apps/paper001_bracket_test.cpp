// The matrices configs/paper001/ imports are the bracket model the generator builds
// (apps/paper001_bracket.cpp): a change of the model without its files, or of the files by
// hand, fails here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_helpers.hpp"

namespace sb::test {
namespace {

const std::filesystem::path kCommitted = std::filesystem::path(SB_SOURCE_DIR) / "configs/paper001";

Result check(const std::filesystem::path& dir) {
    return run_command(std::string(SB_BRACKET) + " --check " + dir.string() + " 2>&1");
}

TEST(Paper001BracketModel, TheCommittedMatricesAreTheModelTheGeneratorBuilds) {
    const Result result = check(kCommitted);
    EXPECT_EQ(result.exit_code, 0) << result.output;
}

TEST(Paper001BracketModel, AStiffnessEntryChangedByHandIsCaught) {
    const auto dir = temp_dir("paper001-bracket");
    for (const auto& entry : std::filesystem::directory_iterator(kCommitted))
        std::filesystem::copy_file(entry.path(), dir / entry.path().filename());
    // The last entry of the stiffness file, its value scaled by 1.001.
    const auto file = dir / "bracket_stiffness.mtx";
    std::string text = file_text(file);
    const auto line_start = text.rfind('\n', text.size() - 2) + 1;
    const auto value_start = text.rfind(' ') + 1;
    ASSERT_GT(value_start, line_start);
    const double value = std::stod(text.substr(value_start));
    text = text.substr(0, value_start) + std::to_string(value * 1.001) + "\n";
    std::ofstream(file, std::ios::binary) << text;
    const Result result = check(dir);
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("bracket_stiffness.mtx: differs"), std::string::npos)
        << result.output;
}

TEST(Paper001BracketModel, PrintsItsModesAtThePapersFrequencies) {
    const Result result = run_command(std::string(SB_BRACKET) + " 2>&1");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("239.0"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("1170.0"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("1575.0"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace sb::test

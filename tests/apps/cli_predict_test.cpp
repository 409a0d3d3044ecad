// `shakerbench predict` and `characterize` through the executable: a prediction is a
// recording like a run's, and bad input exits 2 naming the file, line or key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_helpers.hpp"

namespace {

using namespace sb::test;
namespace fs = std::filesystem;

/// A characterisation of damper pd in H-0 by hand: a constant apparent mass of 13 g (about
/// the 120 spheres) with some loss, on 0.5-3 g and 5-8 Hz.
std::string characterization_text() {
    std::string text =
        "# shakerbench characterization 1\n"
        "# config = by-hand\n"
        "damper,arrangement,level_g,acceleration_m_s2,frequency_hz,bed_mass_kg,"
        "rotation_x_rad_m,rotation_y_rad_m,rotation_z_rad_m,seeds,apparent_mass_re_kg,"
        "apparent_mass_re_std_kg,apparent_mass_im_kg,apparent_mass_im_std_kg,power_w,"
        "power_std_w,h2,h3,kinetic_j,kinetic_std_j,periods,settled\n";
    for (const char* level : {"0.5,6.934", "1,13.869", "3,41.606"}) {
        for (const char* f : {"5", "8"}) {
            text += std::string("pd,H-0,") + level + "," + f +
                    ",0.0132,0,0,0,3,0.013,0.0001,-0.003,0.0001,0.01,0.001,0.01,0.2,1e-4,1e-5,20,"
                    "1\n";
        }
    }
    return text;
}

/// The shipped H-0 campaign at 1 g on its seven frequencies, with `extra` lines after the
/// damper's point line.
fs::path write_config(const fs::path& dir, const std::string& extra = "") {
    std::string text = file_text(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    const auto set = [&text](const std::string& key, const std::string& line) {
        const auto at = text.find("\n" + key);
        const auto end = text.find('\n', at + 1);
        text.replace(at + 1, end - at - 1, line);
    };
    set("levels_g", "levels_g = [1.0]");
    if (!extra.empty()) set("point = \"damper\"", "point = \"damper\"\n" + extra);
    const auto file = dir / "h0.toml";
    std::ofstream(file) << text;
    return file;
}

TEST(CliPredict, APredictionIsARecordingThatIdentifyReads) {
    const auto dir = temp_dir("predict-" + std::to_string(getpid()));
    std::ofstream(dir / "characterization.csv") << characterization_text();
    const auto config = write_config(dir);
    const auto out = dir / "predicted";
    const auto r = run("predict " + config.string() + " --characterization " +
                       (dir / "characterization.csv").string() + " --out " + out.string() + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("7 points (7 predicted, 0 extrapolated, 0 uncertain)"),
              std::string::npos)
        << r.output;
    for (const char* f : {"points.csv", "damping.csv", "recording.toml", "frf.uff", "control.csv",
                          "config.resolved.toml", "provenance.toml"}) {
        EXPECT_TRUE(fs::exists(out / f)) << f;
    }
    EXPECT_NE(file_text(out / "points.csv").find(",predicted,"), std::string::npos);
    EXPECT_NE(file_text(out / "config.resolved.toml").find("describing-function"),
              std::string::npos);
    const auto identified = run("identify " + out.string() + " --no-plots");
    EXPECT_EQ(identified.exit_code, 0) << identified.output;
    EXPECT_NE(identified.output.find("half-power"), std::string::npos) << identified.output;
}

TEST(CliPredict, ADemDamperWithoutACharacterizationIsRefused) {
    const auto dir = temp_dir("predict-dem-" + std::to_string(getpid()));
    const auto r =
        run("predict " + write_config(dir).string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("dampers.pd.model = \"dem\": cannot be predicted"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(CliPredict, ABadCharacterizationFileIsNamedWithItsLineAndColumn) {
    const auto dir = temp_dir("predict-bad-" + std::to_string(getpid()));
    std::string text = characterization_text();
    // Line 5 is the second data row; its level becomes text.
    const auto row = text.find("pd,H-0,0.5,6.934,8");
    text.replace(row + 7, 3, "abc");
    const auto file = dir / "bad.csv";
    std::ofstream(file) << text;
    const auto r = run("predict " + write_config(dir).string() + " --characterization " +
                       file.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(file.string() + ":5:8: column 'level_g': 'abc' is not a number"),
              std::string::npos)
        << r.output;
}

TEST(CliPredict, ADescribingFunctionNeedsItsFileAndTheFileItsDamper) {
    const auto dir = temp_dir("predict-key-" + std::to_string(getpid()));
    const auto none =
        run("predict " + write_config(dir, "model = \"describing-function\"").string());
    EXPECT_EQ(none.exit_code, 2) << none.output;
    EXPECT_NE(none.output.find("dampers.pd.characterization_file: is required with model = "
                               "\"describing-function\""),
              std::string::npos)
        << none.output;

    std::string other = characterization_text();
    for (std::size_t at = other.find("pd,H-0"); at != std::string::npos;
         at = other.find("pd,H-0", at)) {
        other.replace(at, 2, "qd");
    }
    std::ofstream(dir / "other.csv") << other;
    const auto config = write_config(dir,
                                     "model = \"describing-function\"\n"
                                     "characterization_file = \"other.csv\"");
    const auto wrong = run("predict " + config.string());
    EXPECT_EQ(wrong.exit_code, 2) << wrong.output;
    EXPECT_NE(wrong.output.find("h0.toml:"), std::string::npos) << wrong.output;
    EXPECT_NE(wrong.output.find("holds no rows for damper \"pd\""), std::string::npos)
        << wrong.output;
}

TEST(CliPredict, CharacterizeRefusesALevelBelowZeroALevelTwiceAndAnUnknownRotation) {
    const auto dir = temp_dir("characterize-bad-" + std::to_string(getpid()));
    const auto config = write_config(dir).string();
    const auto level =
        run("characterize " + config + " --levels-g 1,-1 --out " + (dir / "c").string());
    EXPECT_EQ(level.exit_code, 2) << level.output;
    EXPECT_NE(level.output.find("levels_g = -1: must be > 0"), std::string::npos) << level.output;
    EXPECT_FALSE(fs::exists(dir / "c"));
    // A level or frequency given twice would be averaged as twice the fillings.
    const auto twice = run("characterize " + config + " --levels-g 1,2 --levels-g 2" +
                           " --frequencies-hz 6,6.5,6 --out " + (dir / "c").string());
    EXPECT_EQ(twice.exit_code, 2) << twice.output;
    EXPECT_NE(twice.output.find("levels_g = 2: is given twice"), std::string::npos) << twice.output;
    EXPECT_NE(twice.output.find("frequencies_hz = 6: is given twice"), std::string::npos)
        << twice.output;
    EXPECT_FALSE(fs::exists(dir / "c"));
    const auto rotation = run("characterize " + config + " --rotation sideways");
    EXPECT_EQ(rotation.exit_code, 2) << rotation.output;
    const auto both = run("characterize " + config + " --energy --no-energy");
    EXPECT_EQ(both.exit_code, 2) << both.output;
    EXPECT_NE(both.output.find("--energy excludes --no-energy"), std::string::npos) << both.output;
}

TEST(CliPredict, CharacterizeWithoutTheEnergyTakesTheRunsStoredWithIt) {
    // The golden bed with output.energy on: the energy files, then --no-energy in the same
    // directory takes every run from the store (their numbers are the same) and writes the
    // same table without the energy files.
    const auto dir = temp_dir("characterize-energy-" + std::to_string(getpid()));
    const std::string common = std::string(SB_SOURCE_DIR) +
                               "/tests/bench/golden/small-h0.toml --set output.energy=true"
                               " --levels-g 1 --frequency-count 1 --seeds 1 --max-periods 7"
                               " --window-periods 3 --transient-periods 1 -j 1 -q --out ";
    const auto with = run("characterize " + common + (dir / "with").string());
    ASSERT_EQ(with.exit_code, 0) << with.output;
    ASSERT_TRUE(fs::exists(dir / "with" / "characterization_energy.csv"));
    fs::remove(dir / "with" / "characterization_energy.csv");
    fs::remove(dir / "with" / "energy_spectrum.csv");
    const std::string table = file_text(dir / "with" / "characterization.csv");
    const auto without = run("characterize " + common + (dir / "with").string() + " --no-energy");
    ASSERT_EQ(without.exit_code, 0) << without.output;
    EXPECT_NE(without.output.find("1 of them taken from the store"), std::string::npos)
        << without.output;
    EXPECT_FALSE(fs::exists(dir / "with" / "characterization_energy.csv"));
    EXPECT_FALSE(fs::exists(dir / "with" / "energy_spectrum.csv"));
    const auto rows = [](const std::string& text) {  // the table without its header's command
        return text.substr(text.find("\ndamper,"));
    };
    EXPECT_EQ(rows(file_text(dir / "with" / "characterization.csv")), rows(table));
}

}  // namespace

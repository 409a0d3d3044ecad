// The small campaigns the CLI tests run: written next to the test's files from the built-in
// config, line by line.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_helpers.hpp"

namespace sb::test {

/// A small real campaign: 30 particles, one level, seven frequencies close around the
/// resonance (enough for half-power and circle fits), short budgets.
inline std::filesystem::path write_small_campaign(const std::filesystem::path& dir) {
    std::string text = file_text(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    const auto set = [&text](const std::string& key, const std::string& line) {
        const auto at = text.find("\n" + key);
        const auto end = text.find('\n', at + 1);
        text.replace(at + 1, end - at - 1, line);
    };
    set("levels_g", "levels_g = [2.0]");
    set("low_ratio", "low_ratio = 0.94");
    set("high_ratio", "high_ratio = 1.06");
    set("count = 120", "count = 30");
    set("max_overlap_fraction", "max_overlap_fraction = 0.05");
    set("max_periods", "max_periods = 14");
    set("window_periods", "window_periods = 3");
    set("transient_periods", "transient_periods = 1");
    const auto file = dir / "small.toml";
    std::ofstream(file) << text;
    return file;
}

/// A linear campaign (rigid particles, one level, three frequencies): a second or so.
inline std::filesystem::path write_rigid_campaign(const std::filesystem::path& dir) {
    std::string text = file_text(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    const auto set = [&text](const std::string& key, const std::string& line) {
        const auto at = text.find("\n" + key);
        const auto end = text.find('\n', at + 1);
        text.replace(at + 1, end - at - 1, line);
    };
    set("point = \"damper\"", "point = \"damper\"\nmodel = \"rigid\"");
    set("levels_g", "levels_g = [1.0]");
    set("low_ratio", "low_ratio = 0.99");
    set("high_ratio", "high_ratio = 1.01");
    set("count = 7", "count = 3");
    const auto file = dir / "rigid.toml";
    std::ofstream(file) << text;
    return file;
}

}  // namespace sb::test

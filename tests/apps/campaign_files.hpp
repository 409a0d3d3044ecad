// The small campaigns the CLI tests run: written next to the test's files from the built-in
// config, line by line.
#pragma once

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cli_helpers.hpp"

namespace sb::test {

/// The built-in H-0 config (configs/paper000-h0.toml) with lines replaced, written to
/// dir/name: each edit names the start of a line and the line that takes its place.
inline std::filesystem::path write_edited_h0(
    const std::filesystem::path& dir, const std::string& name,
    const std::vector<std::pair<std::string, std::string>>& edits) {
    std::string text = file_text(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    for (const auto& [key, line] : edits) {
        const auto at = text.find("\n" + key);
        if (at == std::string::npos) throw std::runtime_error("no line starts with " + key);
        const auto end = text.find('\n', at + 1);
        text.replace(at + 1, end - at - 1, line);
    }
    const auto file = dir / name;
    std::ofstream(file) << text;
    return file;
}

/// A small real campaign: 30 particles, one level, seven frequencies close around the
/// resonance (enough for half-power and circle fits), short budgets.
inline std::filesystem::path write_small_campaign(const std::filesystem::path& dir) {
    return write_edited_h0(dir, "small.toml",
                           {{"levels_g", "levels_g = [2.0]"},
                            {"low_ratio", "low_ratio = 0.94"},
                            {"high_ratio", "high_ratio = 1.06"},
                            {"count = 120", "count = 30"},
                            {"max_overlap_fraction", "max_overlap_fraction = 0.05"},
                            {"max_periods", "max_periods = 14"},
                            {"window_periods", "window_periods = 3"},
                            {"transient_periods", "transient_periods = 1"}});
}

/// A linear campaign (rigid particles, one level, three frequencies): a second or so.
inline std::filesystem::path write_rigid_campaign(const std::filesystem::path& dir) {
    return write_edited_h0(dir, "rigid.toml",
                           {{"point = \"damper\"", "point = \"damper\"\nmodel = \"rigid\""},
                            {"levels_g", "levels_g = [1.0]"},
                            {"low_ratio", "low_ratio = 0.99"},
                            {"high_ratio", "high_ratio = 1.01"},
                            {"count = 7", "count = 3"}});
}

}  // namespace sb::test

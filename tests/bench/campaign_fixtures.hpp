// Campaign configs for tests: the shipped H-0 campaign with lines replaced.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bench/sweep_checkpoint.hpp"

namespace sb::bench::test {

/// The shipped H-0 campaign with its lines starting with `key` replaced.
inline std::string paper000_h0_with(const std::vector<std::pair<std::string, std::string>>& edits) {
    std::string text = read_file(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    for (const auto& [key, line] : edits) {
        const auto at = text.find("\n" + key);
        EXPECT_NE(at, std::string::npos) << key;
        const auto end = text.find('\n', at + 1);
        text.replace(at + 1, end - at - 1, line);
    }
    return text;
}

inline std::filesystem::path fresh_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("shakerbench-campaign-" + name);
    std::filesystem::remove_all(dir);
    return dir;
}

}  // namespace sb::bench::test

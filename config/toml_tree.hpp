// Inside config/ only: the TOML tree of a Document and helpers on its nodes.
#pragma once

#include <toml++/toml.h>

#include <algorithm>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "config/document.hpp"

namespace sb::config {

struct Document::Tree {
    toml::table root;
};

/// The place of a node in the file named `file`.
inline Origin origin_of(const toml::node& node, const std::string& file) {
    return {file, static_cast<int>(node.source().begin.line),
            static_cast<int>(node.source().begin.column)};
}

/// The keys of a table in the order the file writes them (toml++ keeps them sorted).
inline std::vector<std::pair<std::string, const toml::node*>> in_file_order(
    const toml::table& table) {
    std::vector<std::pair<std::string, const toml::node*>> out;
    for (const auto& [key, value] : table) out.emplace_back(std::string(key.str()), &value);
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        const auto& sa = a.second->source().begin;
        const auto& sb = b.second->source().begin;
        return std::tie(sa.line, sa.column) < std::tie(sb.line, sb.column);
    });
    return out;
}

}  // namespace sb::config

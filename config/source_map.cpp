// Locating values of a loaded config.
#include "config/source_map.hpp"

#include <algorithm>

namespace sb::config {

Origin SourceMap::locate(std::string_view path) const {
    // The latest override of the path wins.
    const auto it = std::find_if(overrides.rbegin(), overrides.rend(),
                                 [&](const auto& o) { return o.first == path; });
    if (it != overrides.rend()) return it->second;
    if (document) return document->locate(path);
    return {file(), 0, 0};
}

std::string SourceMap::file() const { return document ? document->name() : "<in memory>"; }

}  // namespace sb::config

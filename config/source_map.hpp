// Where the values of a loaded config came from: its file, and the overrides applied since.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "config/document.hpp"

namespace sb::config {

struct SourceMap {
    std::shared_ptr<const Document> document;  ///< null for a config built in code
    /// Values changed after reading, by path (latest last), with the origin messages name:
    /// "--set dampers.pd.contact.sliding_friction=0.45".
    std::vector<std::pair<std::string, Origin>> overrides;

    /// Where the value at `path` came from: its latest override, else its place in the file.
    [[nodiscard]] Origin locate(std::string_view path) const;
    /// The file name messages give ("<in memory>" without a document).
    [[nodiscard]] std::string file() const;
};

}  // namespace sb::config

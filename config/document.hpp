// A parsed config file: the TOML tree (held out of sight, so that only config/ sees the TOML
// library), its name for messages, and the folder relative file names resolve in.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "config/errors.hpp"

namespace sb::config {

class Document {
  public:
    /// Parses `path`; an unreadable file or a syntax error throws ConfigException.
    static std::shared_ptr<const Document> parse_file(const std::filesystem::path& path);
    /// Parses text held in memory; `name` stands for the file in messages, relative file
    /// names resolve in `base_dir`.
    static std::shared_ptr<const Document> parse_text(std::string_view text, std::string name,
                                                      std::filesystem::path base_dir = {});
    ~Document();

    [[nodiscard]] const std::string& name() const { return name_; }
    [[nodiscard]] const std::filesystem::path& base_dir() const { return base_dir_; }
    /// Where the file writes the value at a config path ("dampers.pd.contact.restitution",
    /// "structure.beam.masses[1].x_m"): the deepest part of the path the file holds, so a
    /// default is placed at the table it would belong to.
    [[nodiscard]] Origin locate(std::string_view path) const;

    struct Tree;  ///< the TOML tree (config/document.cpp)
    [[nodiscard]] const Tree& tree() const { return *tree_; }

  private:
    Document(std::unique_ptr<Tree> tree, std::string name, std::filesystem::path base_dir);
    std::unique_ptr<Tree> tree_;
    std::string name_;
    std::filesystem::path base_dir_;
};

/// A dotted path split into its parts: names (quotes removed) and array indexes.
struct PathPart {
    std::string name;
    bool is_index = false;
    std::size_t index = 0;
};
/// Splits "a.b[2].\"c.d\""; nothing when the path is malformed.
bool split_path(std::string_view path, std::vector<PathPart>& parts);

}  // namespace sb::config

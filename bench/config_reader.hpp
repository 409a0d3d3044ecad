// Typed, located reading of TOML config sections: every problem collected with file:line:col.
#pragma once

#include <toml++/toml.h>

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bench/config_errors.hpp"
#include "core/violation.hpp"

namespace sb::bench {

/// Collects the errors of one config file.
class ConfigDiagnostics {
  public:
    explicit ConfigDiagnostics(std::string file) : file_(std::move(file)) {}

    void add(const toml::source_region& where, std::string key_path, std::string value,
             std::string constraint, std::string meaning);
    [[nodiscard]] bool empty() const { return errors_.empty(); }
    [[nodiscard]] bool has_error_at(std::string_view key_path) const;
    [[nodiscard]] const std::string& file() const { return file_; }
    /// Throws ConfigException with everything collected, if anything was.
    void throw_if_any() const;

  private:
    std::string file_;
    std::vector<ConfigError> errors_;
};

/// A parsed config document: the file name travels with the table for error messages.
class ConfigDocument {
  public:
    /// Parses `path`; a syntax error or an unreadable file throws ConfigException.
    static ConfigDocument parse_file(const std::filesystem::path& path);
    /// Parses text held in memory; `name` stands for the file in messages.
    static ConfigDocument parse_text(std::string_view text, std::string name);

    [[nodiscard]] const toml::table& root() const { return root_; }
    [[nodiscard]] ConfigDiagnostics& diagnostics() { return diagnostics_; }
    [[nodiscard]] const std::filesystem::path& base_dir() const { return base_dir_; }

  private:
    ConfigDocument(toml::table root, std::string name, std::filesystem::path base_dir)
        : root_(std::move(root)), diagnostics_(std::move(name)), base_dir_(std::move(base_dir)) {}
    toml::table root_;
    ConfigDiagnostics diagnostics_;
    std::filesystem::path base_dir_;
};

/// One table of the config, read key by key. Every key read is remembered so that finish()
/// reports the keys nobody asked for: an unknown key is an error, never silently ignored.
class Section {
  public:
    Section(const toml::table* table, std::string path, toml::source_region where,
            ConfigDiagnostics& diagnostics);
    /// The root table of a document.
    static Section root(ConfigDocument& document);

    [[nodiscard]] bool present() const { return table_ != nullptr; }
    [[nodiscard]] bool has(std::string_view key) const;
    [[nodiscard]] const std::string& path() const { return path_; }
    [[nodiscard]] std::string key_path(std::string_view key) const;

    double number(std::string_view key, double fallback, std::string_view meaning);
    double required_number(std::string_view key, std::string_view meaning);
    std::optional<double> optional_number(std::string_view key, std::string_view meaning);
    int integer(std::string_view key, int fallback, std::string_view meaning);
    bool boolean(std::string_view key, bool fallback, std::string_view meaning);
    std::string string(std::string_view key, std::string fallback, std::string_view meaning);
    std::string required_string(std::string_view key, std::string_view meaning);
    /// A string that must be one of `choices`.
    std::string choice(std::string_view key, std::string fallback,
                       const std::vector<std::string>& choices, std::string_view meaning);
    Eigen::Vector3d vector3(std::string_view key, const Eigen::Vector3d& fallback,
                            std::string_view meaning);
    std::vector<double> numbers(std::string_view key, std::string_view meaning);
    std::vector<std::string> strings(std::string_view key, std::string_view meaning);

    /// A sub-table; absent gives a section with present() == false.
    Section table(std::string_view key, std::string_view meaning);
    /// Every key of this table whose value is a table, as named sections (for [points.NAME]).
    std::vector<std::pair<std::string, Section>> named_tables(std::string_view meaning);
    /// Every key of this table read as a number, in file order.
    std::vector<std::pair<std::string, double>> named_numbers(std::string_view meaning);
    /// An array of tables ([[key]]).
    std::vector<Section> array_of_tables(std::string_view key, std::string_view meaning);

    /// Reports an error located at `key` (or at this table when the key is absent).
    void error(std::string_view key, std::string value, std::string constraint,
               std::string meaning);
    /// Locates leaf-module violations (keys relative to this section) and reports them.
    void report(const Violations& violations);
    /// Reports every key of this table that was never read.
    void finish();

    [[nodiscard]] const toml::source_region& where() const { return where_; }

  private:
    const toml::node* node(std::string_view key) const;
    const toml::node* lookup(std::string_view key);  // marks the key used
    void wrong_type(std::string_view key, const toml::node& node, std::string_view expected,
                    std::string_view meaning);

    const toml::table* table_;
    std::string path_;
    toml::source_region where_;
    ConfigDiagnostics* diagnostics_;
    std::set<std::string, std::less<>> used_;
};

/// Text of a TOML node as the file would show it (for messages).
std::string node_text(const toml::node& node);

}  // namespace sb::bench

// Config errors with their place: collected while reading or changing a config, thrown once.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sb::config {

/// Where a value came from: a place in a file (line and column 1-based, 0 when unknown), or
/// an override such as `--set dampers.pd.contact.sliding_friction=0.45` (line 0).
struct Origin {
    std::string file;
    int line = 0;
    int column = 0;
};

/// One error, formatted `FILE:LINE:COL: key.path = value: constraint (meaning)`.
struct ConfigError {
    std::string file;
    int line = 0;    ///< 1-based; 0 when the place is unknown
    int column = 0;  ///< 1-based; 0 when the place is unknown
    std::string key_path;
    std::string value;
    std::string constraint;
    std::string meaning;

    [[nodiscard]] std::string format() const;
};

/// Thrown once reading or changing is complete, carrying every error found. Exit code 2 at
/// the CLI.
class ConfigException : public std::runtime_error {
  public:
    explicit ConfigException(std::vector<ConfigError> errors);
    [[nodiscard]] const std::vector<ConfigError>& errors() const { return errors_; }

  private:
    std::vector<ConfigError> errors_;
};

/// Collects the errors of one read or one change.
class Diagnostics {
  public:
    void add(const Origin& where, std::string key_path, std::string value, std::string constraint,
             std::string meaning);
    void add(ConfigError error);
    [[nodiscard]] bool empty() const { return errors_.empty(); }
    /// True when an error was reported at `key_path` or at a key inside it.
    [[nodiscard]] bool has_error_within(std::string_view key_path) const;
    /// True when an error was reported at `key_path` or at a table that holds it.
    [[nodiscard]] bool has_error_covering(std::string_view key_path) const;
    /// Throws ConfigException with everything collected (sorted by place), if anything was.
    void throw_if_any() const;

  private:
    std::vector<ConfigError> errors_;
};

/// Exit codes (style.md): bad input (config, data, command line) 2, failures 1.
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitFailure = 1;

}  // namespace sb::config

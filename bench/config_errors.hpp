// Config errors with their place in the file: collected, never thrown one at a time.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace sb::bench {

/// One error in a config file, formatted `file:line:col: key.path = value: constraint (meaning)`.
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

/// Thrown once loading is complete, carrying every error found. Exit code 2 at the CLI.
class ConfigException : public std::runtime_error {
  public:
    explicit ConfigException(std::vector<ConfigError> errors);
    [[nodiscard]] const std::vector<ConfigError>& errors() const { return errors_; }

  private:
    std::vector<ConfigError> errors_;
};

/// Exit code for a bad config or input file (style.md: config errors exit 2, failures 1).
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitFailure = 1;

}  // namespace sb::bench

// A config value as a file holds it, and its text as TOML writes it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace sb::config {

/// A value of a declared key. std::monostate stands for "automatic" (a key whose value the
/// bench chooses) or for an optional key that is absent.
using Value = std::variant<std::monostate, bool, std::int64_t, double, std::string,
                           std::vector<double>, std::vector<std::string>>;

/// The word a file writes for an automatic value.
inline constexpr std::string_view kAutomatic = "automatic";

/// TOML text of a number with the shortest digits that read back to the same double, always
/// as a float literal ("1.0", "7.2e+10", "inf").
std::string number_text(double value);

/// A TOML basic string with the escapes TOML requires.
std::string quoted(std::string_view text);

/// TOML text of a value; std::monostate gives "automatic" quoted.
std::string value_text(const Value& value);

/// The value as a double when it is a number (an integer counts), else nothing.
bool as_number(const Value& value, double& out);

}  // namespace sb::config

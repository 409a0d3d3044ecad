// Formatting and collecting config errors.
#include "config/errors.hpp"

#include <algorithm>
#include <sstream>
#include <tuple>

namespace sb::config {

std::string ConfigError::format() const {
    std::ostringstream out;
    out << file;
    if (line > 0) {
        out << ':' << line << ':' << column;
    }
    out << ": " << key_path;
    if (!value.empty()) {
        out << " = " << value;
    }
    out << ": " << constraint;
    if (!meaning.empty()) {
        out << " (" << meaning << ')';
    }
    return out.str();
}

namespace {
std::string join(const std::vector<ConfigError>& errors) {
    std::string text;
    for (const auto& e : errors) {
        if (!text.empty()) {
            text += '\n';
        }
        text += e.format();
    }
    return text;
}

/// True when `inner` is `outer` or a key inside it ("a.b" is inside "a", "a[2].x" inside "a").
bool within(std::string_view inner, std::string_view outer) {
    if (outer.empty()) return true;
    if (inner.substr(0, outer.size()) != outer) return false;
    return inner.size() == outer.size() || inner[outer.size()] == '.' || inner[outer.size()] == '[';
}
}  // namespace

ConfigException::ConfigException(std::vector<ConfigError> errors)
    : std::runtime_error(join(errors)), errors_(std::move(errors)) {}

void Diagnostics::add(const Origin& where, std::string key_path, std::string value,
                      std::string constraint, std::string meaning) {
    ConfigError e;
    e.file = where.file;
    e.line = where.line;
    e.column = where.column;
    e.key_path = std::move(key_path);
    e.value = std::move(value);
    e.constraint = std::move(constraint);
    e.meaning = std::move(meaning);
    errors_.push_back(std::move(e));
}

void Diagnostics::add(ConfigError error) { errors_.push_back(std::move(error)); }

bool Diagnostics::has_error_within(std::string_view key_path) const {
    return std::any_of(errors_.begin(), errors_.end(),
                       [&](const ConfigError& e) { return within(e.key_path, key_path); });
}

bool Diagnostics::has_error_covering(std::string_view key_path) const {
    return std::any_of(errors_.begin(), errors_.end(),
                       [&](const ConfigError& e) { return within(key_path, e.key_path); });
}

void Diagnostics::throw_if_any() const {
    if (errors_.empty()) return;
    auto sorted = errors_;
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
        return std::tie(a.line, a.column) < std::tie(b.line, b.column);
    });
    throw ConfigException(std::move(sorted));
}

}  // namespace sb::config

// Formatting of config errors.
#include "bench/config_errors.hpp"

#include <sstream>

namespace sb::bench {

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
}  // namespace

ConfigException::ConfigException(std::vector<ConfigError> errors)
    : std::runtime_error(join(errors)), errors_(std::move(errors)) {}

}  // namespace sb::bench

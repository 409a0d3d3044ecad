// TOML text of config values.
#include "config/value.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace sb::config {

std::string number_text(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
    char buffer[64];
    // Shortest round-trip digits (C++17 to_chars without a format).
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    std::string text(buffer, result.ptr);
    // TOML reads "3" as an integer: a float literal needs a point or an exponent.
    if (text.find_first_of(".eE") == std::string::npos) {
        text += ".0";
    }
    return text;
}

std::string quoted(std::string_view text) {
    std::string out = "\"";
    for (const char c : text) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            case '\r':
                out += "\\r";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
                    char escape[8];
                    std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned>(c));
                    out += escape;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

std::string value_text(const Value& value) {
    struct Visitor {
        std::string operator()(std::monostate /*automatic*/) const { return quoted(kAutomatic); }
        std::string operator()(bool b) const { return b ? "true" : "false"; }
        std::string operator()(std::int64_t i) const { return std::to_string(i); }
        std::string operator()(double d) const { return number_text(d); }
        std::string operator()(const std::string& s) const { return quoted(s); }
        std::string operator()(const std::vector<double>& v) const {
            std::string out = "[";
            for (std::size_t i = 0; i < v.size(); ++i) {
                out += (i > 0 ? ", " : "") + number_text(v[i]);
            }
            return out + "]";
        }
        std::string operator()(const std::vector<std::string>& v) const {
            std::string out = "[";
            for (std::size_t i = 0; i < v.size(); ++i) {
                out += (i > 0 ? ", " : "") + quoted(v[i]);
            }
            return out + "]";
        }
    };
    return std::visit(Visitor{}, value);
}

bool as_number(const Value& value, double& out) {
    if (const auto* d = std::get_if<double>(&value)) {
        out = *d;
        return true;
    }
    if (const auto* i = std::get_if<std::int64_t>(&value)) {
        out = static_cast<double>(*i);
        return true;
    }
    return false;
}

}  // namespace sb::config

// Numbers and strings as the reports of correlation/ write them (TOML and Markdown).
#pragma once

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace sb::correlation {

/// `v` with `digits` significant digits (general) or decimals (fixed); "nan" if not finite.
inline std::string num(double v, int digits = 6, bool fixed = false) {
    if (!std::isfinite(v)) return "nan";
    std::ostringstream out;
    if (fixed) out << std::fixed;
    out << std::setprecision(digits) << v;
    return out.str();
}

/// A TOML basic string: quoted, with quotes, backslashes and newlines escaped.
inline std::string toml_string(const std::string& s) {
    std::string out = "\"";
    for (const char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n') {
            out += "\\n";
            continue;
        }
        out += c;
    }
    return out + "\"";
}

}  // namespace sb::correlation

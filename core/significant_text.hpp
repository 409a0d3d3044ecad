// Doubles as text with a given number of significant digits, for run logs, reports and files
// read by people (exact_text.hpp is the one that reads back bit for bit).
#pragma once

#include <cstdio>
#include <string>

namespace sb {

/// `v` with `digits` significant digits (printf's "%.*g").
inline std::string significant_text(double v, int digits = 9) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
    return buffer;
}

}  // namespace sb

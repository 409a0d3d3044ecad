// Doubles as text that reads back bit for bit, for what one process hands another (results
// between ranks, keys of stored results).
#pragma once

#include <cstdio>
#include <string>

namespace sb {

/// `v` as a hexadecimal float (printf's "%a"): std::strtod gives the same double back.
inline std::string exact_text(double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%a", v);
    return buffer;
}

}  // namespace sb

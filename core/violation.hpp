// A broken constraint of an options struct, as found by its validate(); shared by all modules.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace sb {

/// One violated constraint. Leaf modules know nothing of files: `key` is the dotted path
/// relative to the options struct, and the config layer in bench/ adds file, line and column.
struct Violation {
    std::string key;         ///< dotted key path relative to the struct, e.g. "beam.length_m"
    std::string value;       ///< the offending value as text
    std::string constraint;  ///< e.g. "must be > 0"
    std::string meaning;     ///< what the value is, e.g. "beam length [m]"
};

using Violations = std::vector<Violation>;

/// Text of a number as a config file would write it.
inline std::string format_value(double value) {
    std::ostringstream out;
    out.precision(12);
    out << value;
    return out.str();
}

/// Adds a violation unless `value` is finite and strictly positive.
inline void require_positive(Violations& out, std::string_view key, double value,
                             std::string_view meaning) {
    if (!(std::isfinite(value) && value > 0.0)) {
        out.push_back({std::string(key), format_value(value), "must be > 0", std::string(meaning)});
    }
}

/// Adds a violation unless `value` is finite and >= 0.
inline void require_non_negative(Violations& out, std::string_view key, double value,
                                 std::string_view meaning) {
    if (!(std::isfinite(value) && value >= 0.0)) {
        out.push_back(
            {std::string(key), format_value(value), "must be >= 0", std::string(meaning)});
    }
}

/// Adds a violation unless lo <= value <= hi.
inline void require_in_range(Violations& out, std::string_view key, double value, double lo,
                             double hi, std::string_view meaning) {
    if (!(std::isfinite(value) && value >= lo && value <= hi)) {
        out.push_back({std::string(key), format_value(value),
                       "must be in [" + format_value(lo) + ", " + format_value(hi) + "]",
                       std::string(meaning)});
    }
}

/// Prefixes every key of `inner` with `prefix.` and appends them to `out`.
inline void append_prefixed(Violations& out, std::string_view prefix, const Violations& inner) {
    for (const auto& v : inner) {
        Violation copy = v;
        copy.key = std::string(prefix) + "." + v.key;
        out.push_back(std::move(copy));
    }
}

}  // namespace sb

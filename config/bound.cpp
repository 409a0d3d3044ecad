// Bounds of declared numbers.
#include "config/bound.hpp"

#include <cmath>
#include <sstream>

namespace sb::config {
namespace {
std::string number(double v) {
    std::ostringstream out;
    out.precision(12);
    out << v;
    return out.str();
}
}  // namespace

bool Bound::contains(double value) const {
    if (std::isnan(value)) return false;
    if (std::isinf(value)) {
        return infinite_allowed && (value > 0.0 ? std::isinf(hi) : std::isinf(lo));
    }
    const bool above = lo_open ? value > lo : value >= lo;
    const bool below = hi_open ? value < hi : value <= hi;
    return above && below;
}

std::string Bound::text() const {
    const bool has_lo = std::isfinite(lo);
    const bool has_hi = std::isfinite(hi);
    if (has_lo && has_hi) {
        return std::string("in ") + (lo_open ? "(" : "[") + number(lo) + ", " + number(hi) +
               (hi_open ? ")" : "]");
    }
    if (has_lo) return (lo_open ? "> " : ">= ") + number(lo);
    if (has_hi) return (hi_open ? "< " : "<= ") + number(hi);
    return "";
}

std::string Bound::constraint() const {
    const std::string t = text();
    return t.empty() ? "must be finite" : "must be " + t;
}

}  // namespace sb::config

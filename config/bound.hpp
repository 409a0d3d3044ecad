// The interval a number must lie in, as declared with its key.
#pragma once

#include <limits>
#include <string>

namespace sb::config {

/// lo < or <= value < or <= hi; infinite ends are open. Default: any finite number.
struct Bound {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = true;
    bool hi_open = true;
    /// Infinity itself is allowed (an amplitude without upper bound).
    bool infinite_allowed = false;

    static Bound any() { return {}; }
    static Bound positive() { return {0.0, kInf, true, true}; }
    static Bound non_negative() { return {0.0, kInf, false, true}; }
    static Bound at_least(double lo) { return {lo, kInf, false, true}; }
    static Bound greater_than(double lo) { return {lo, kInf, true, true}; }
    /// [lo, hi]
    static Bound closed(double lo, double hi) { return {lo, hi, false, false}; }
    /// (lo, hi]
    static Bound left_open(double lo, double hi) { return {lo, hi, true, false}; }
    /// [lo, hi)
    static Bound right_open(double lo, double hi) { return {lo, hi, false, true}; }
    /// (lo, hi)
    static Bound open(double lo, double hi) { return {lo, hi, true, true}; }
    Bound& allow_infinite() {
        infinite_allowed = true;
        return *this;
    }

    [[nodiscard]] bool contains(double value) const;
    /// "> 0", ">= 0", "in [0, 90]", "in (0, 1]", or "" for any finite number.
    [[nodiscard]] std::string text() const;
    /// The constraint of a message: "must be > 0", "must be finite".
    [[nodiscard]] std::string constraint() const;

    static constexpr double kInf = std::numeric_limits<double>::infinity();
};

}  // namespace sb::config

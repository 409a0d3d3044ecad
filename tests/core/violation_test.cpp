#include "core/violation.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace sb {
namespace {

TEST(Violation, PositiveCheckRejectsZeroNegativeAndNan) {
    Violations out;
    require_positive(out, "a", 0.0, "a thing");
    require_positive(out, "b", -1.0, "b thing");
    require_positive(out, "c", std::numeric_limits<double>::quiet_NaN(), "c thing");
    require_positive(out, "d", 1e-12, "d thing");
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out[0].key, "a");
    EXPECT_EQ(out[1].value, "-1");
    EXPECT_EQ(out[2].constraint, "must be > 0");
}

TEST(Violation, RangeCheckNamesBothBounds) {
    Violations out;
    require_in_range(out, "ratio", 1.5, 0.0, 1.0, "damping ratio");
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].constraint, "must be in [0, 1]");
}

TEST(Violation, PrefixedKeysKeepTheirOrder) {
    Violations inner{{"x", "1", "c", "m"}, {"y", "2", "c", "m"}};
    Violations out;
    append_prefixed(out, "beam", inner);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].key, "beam.x");
    EXPECT_EQ(out[1].key, "beam.y");
}

}  // namespace
}  // namespace sb

// The ratio rule, the step limit and the secant through the widened bracket.
#include "control/update.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sb::control {
namespace {

/// Closed-form expectations computed in double; only rounding separates them.
constexpr double kRounding = 1e-12;

TEST(Bracket, WidenedSecantStaysInsideAndIsPulledTowardTheMiddle) {
    ControllerOptions o;  // tolerance 0.05, overshoot 1
    Bracket b;
    EXPECT_TRUE(b.add({1.0, 0.5}, 1.0));
    EXPECT_FALSE(b.secant(1.0, o).has_value());  // one side only
    EXPECT_TRUE(b.add({2.0, 1.05}, 1.0));
    const auto a = b.secant(1.0, o);
    ASSERT_TRUE(a.has_value());
    // Plain secant: 1 + 0.5/0.55 = 1.909; widened levels 0.475 and 1.1025 give
    // 1 + 0.525/0.6275 = 1.8367, nearer the middle 1.5.
    EXPECT_NEAR(*a, 1.0 + 0.525 / 0.6275, kRounding);
    EXPECT_GT(*a, 1.0);
    EXPECT_LT(*a, 1.0 + 0.5 / 0.55);
}

TEST(Bracket, SampleImprovingNeitherSideRestartsIt) {
    Bracket b;
    EXPECT_TRUE(b.add({1.0, 0.8}, 1.0));
    EXPECT_TRUE(b.add({2.0, 1.2}, 1.0));
    EXPECT_FALSE(b.add({1.5, 0.7}, 1.0));  // below, but worse than 0.8
    ASSERT_TRUE(b.lower().has_value());
    EXPECT_EQ(b.lower()->amplitude, 1.5);
    EXPECT_FALSE(b.upper().has_value());
}

TEST(Bracket, PointsTheToleranceCannotSeparateGiveNoSecant) {
    ControllerOptions o;
    Bracket b;
    b.add({1.0, 0.97}, 1.0);
    b.add({1.1, 1.02}, 1.0);  // 5 % apart < 2 x overshoot x tolerance = 10 %
    EXPECT_FALSE(b.secant(1.0, o).has_value());
}

TEST(Bracket, AResponseFallingWithTheDriveGivesNoSecant) {
    ControllerOptions o;
    Bracket b;
    b.add({2.0, 0.5}, 1.0);
    b.add({1.0, 1.5}, 1.0);
    EXPECT_FALSE(b.secant(1.0, o).has_value());
}

TEST(Update, PowerLawGradientHitsAPowerLawResponseInOneStep) {
    ControllerOptions o;
    // level = amplitude^(1/3): from (1, 1) and (8, 2) the target 3 needs amplitude 27.
    const auto a = power_law_amplitude({1.0, 1.0}, {8.0, 2.0}, 3.0, o);
    ASSERT_TRUE(a.has_value());
    EXPECT_NEAR(*a, 27.0, 27.0 * kRounding);
    // Levels the tolerance cannot separate, or falling with the drive: no gradient.
    EXPECT_FALSE(power_law_amplitude({1.0, 1.0}, {2.0, 1.02}, 3.0, o).has_value());
    EXPECT_FALSE(power_law_amplitude({1.0, 2.0}, {2.0, 1.0}, 3.0, o).has_value());
}

TEST(Update, RatioRuleScalesByTargetOverLevel) {
    EXPECT_NEAR(ratio_amplitude(2.0, 0.5, 1.0), 4.0, kRounding);
    EXPECT_TRUE(std::isinf(ratio_amplitude(2.0, 0.0, 1.0)));
}

TEST(Update, StepsAreLimitedByTheFactorAndTheBounds) {
    ControllerOptions o;
    o.max_step_factor = 2.0;
    o.min_amplitude = 0.3;
    o.max_amplitude = 3.0;
    EXPECT_EQ(limit_step(1.0, 10.0, o), 2.0);
    EXPECT_EQ(limit_step(1.0, 0.1, o), 0.5);
    EXPECT_EQ(limit_step(1.0, -4.0, o), 0.5);
    EXPECT_EQ(limit_step(1.0, std::numeric_limits<double>::infinity(), o), 2.0);
    EXPECT_EQ(limit_step(2.0, 10.0, o), 3.0);
    EXPECT_EQ(limit_step(0.4, 0.1, o), 0.3);
    EXPECT_EQ(limit_step(1.0, 1.3, o), 1.3);
}

}  // namespace
}  // namespace sb::control

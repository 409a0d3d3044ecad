// Settling, two-period cycle and early-decision tests on hand-made windows.
#include "control/window.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace sb::control {
namespace {

/// Windows below are exact decimal numbers; levels are means of them, so only rounding.
constexpr double kRounding = 1e-12;

ControllerOptions options() {
    ControllerOptions o;  // tolerance 0.05, window 4, early 3, limit_cycle_jump 2
    return o;
}

TEST(AssessWindow, ValuesWithinTheToleranceAreSettledAtTheirMean) {
    const std::vector<double> v{1.00, 1.02, 0.99, 1.01};
    const WindowVerdict r = assess_window(v, 1.0, options());
    EXPECT_EQ(r.state, WindowState::kSettled);
    EXPECT_NEAR(r.level, 1.005, kRounding);
    EXPECT_EQ(r.count, 4);
}

TEST(AssessWindow, OnlyTheNewestWindowPeriodsVote) {
    // An old outlier beyond the window does not spoil a settled window.
    const std::vector<double> v{5.0, 1.00, 1.02, 0.99, 1.01};
    EXPECT_EQ(assess_window(v, 1.0, options()).state, WindowState::kSettled);
}

TEST(AssessWindow, FewerValuesThanEarlyPeriodsNeverDecide) {
    const std::vector<double> v{0.0, 0.0};
    EXPECT_EQ(assess_window(v, 1.0, options()).state, WindowState::kFilling);
}

TEST(AssessWindow, AlternatingValuesAreATwoPeriodCycleOverAnEvenWindow) {
    const std::vector<double> v{0.5, 1.2, 0.8, 1.21, 0.81, 1.2, 0.8};
    const WindowVerdict r = assess_window(v, 1.0, options());
    EXPECT_EQ(r.state, WindowState::kLimitCycle2);
    EXPECT_EQ(r.count, 6);
    EXPECT_NEAR(r.level, (1.2 + 0.8 + 1.21 + 0.81 + 1.2 + 0.8) / 6.0, kRounding);
}

TEST(AssessWindow, TwoRepetitionsAreNotEnoughForALimitCycle) {
    // Four alternating values could be chance; limit_cycle_periods = 6 are required.
    const std::vector<double> v{1.2, 0.8, 1.21, 0.81};
    EXPECT_EQ(assess_window(v, 1.0, options()).state, WindowState::kUnsettled);
}

TEST(AssessWindow, AlternationSmallerThanTheJumpIsNotALimitCycle) {
    // 8 % apart: beyond the tolerance, below 2 x tolerance.
    const std::vector<double> v{1.04, 0.96, 1.04, 0.96, 1.04, 0.96};
    EXPECT_EQ(assess_window(v, 1.0, options()).state, WindowState::kUnsettled);
}

TEST(AssessWindow, ScatterAroundTheTargetIsUnsettled) {
    const std::vector<double> v{1.2, 0.8, 1.1, 0.9};
    EXPECT_EQ(assess_window(v, 1.0, options()).state, WindowState::kUnsettled);
}

TEST(AssessWindow, ValuesAllFarBelowDecideEarlyAtTheValueNearestTheTarget) {
    const std::vector<double> v{0.5, 0.3, 0.4};
    const WindowVerdict r = assess_window(v, 1.0, options());
    EXPECT_EQ(r.state, WindowState::kEarlyLow);
    EXPECT_EQ(r.level, 0.5);
    EXPECT_EQ(r.count, 3);
}

TEST(AssessWindow, ValuesAllFarAboveDecideEarlyAtTheValueNearestTheTarget) {
    const std::vector<double> v{1.5, 1.9, 1.7};
    const WindowVerdict r = assess_window(v, 1.0, options());
    EXPECT_EQ(r.state, WindowState::kEarlyHigh);
    EXPECT_EQ(r.level, 1.5);
}

TEST(AssessWindow, OneValueInsideTheMarginBlocksTheEarlyDecision) {
    // 0.96 * 1.05 > 1: not too low beyond the tolerance.
    const std::vector<double> v{0.5, 0.96, 0.4};
    EXPECT_EQ(assess_window(v, 1.0, options()).state, WindowState::kFilling);
}

TEST(AssessWindow, DriftTowardTheTargetVetoesTheEarlyDecision) {
    EXPECT_EQ(assess_window(std::vector<double>{0.3, 0.5, 0.6}, 1.0, options()).state,
              WindowState::kFilling);
    EXPECT_EQ(assess_window(std::vector<double>{1.9, 1.6, 1.5, 1.3}, 1.0, options()).state,
              WindowState::kUnsettled);
}

TEST(AssessWindow, DriftAwayFromTheTargetStillDecidesEarly) {
    EXPECT_EQ(assess_window(std::vector<double>{0.6, 0.5, 0.3}, 1.0, options()).state,
              WindowState::kEarlyLow);
}

TEST(AssessWindow, AZeroResponseIsTooLowNotADrift) {
    const WindowVerdict r = assess_window(std::vector<double>{0.0, 0.0, 0.0}, 1.0, options());
    EXPECT_EQ(r.state, WindowState::kEarlyLow);
    EXPECT_EQ(r.level, 0.0);
}

}  // namespace
}  // namespace sb::control

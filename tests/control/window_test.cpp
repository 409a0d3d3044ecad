// Settling, two-period cycle and early-decision tests on hand-made windows.
#include "control/window.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
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

TEST(AssessWindow, ABeatingTransientWhosePhaseTurnsIsNotSettledThoughItsRmsBarelyMoves) {
    // Steady response 1 plus a transient of amplitude 0.03 at the structure's own frequency,
    // half a cycle per period away from the drive and in quadrature with the response: its
    // phasor flips from +0.03i to -0.03i period by period. The RMS of each period,
    // |1 +- 0.03i| = 1.00045, does not move; the phasors lie 0.06 apart, beyond the 5 %
    // tolerance: not a steady state.
    std::vector<double> rms;
    std::vector<std::complex<double>> phasors;
    for (int k = 0; k < 4; ++k) {
        const std::complex<double> x(1.0, k % 2 == 0 ? 0.03 : -0.03);
        phasors.push_back(x);
        rms.push_back(std::abs(x));
    }
    ASSERT_EQ(assess_window(rms, 1.0, options()).state, WindowState::kSettled);
    EXPECT_NE(assess_window(rms, 1.0, options(), phasors).state, WindowState::kSettled);
    // A steady response with scatter well within the tolerance is settled by both tests.
    const std::vector<std::complex<double>> steady{
        {1.0, 0.0}, {1.01, 0.005}, {0.995, -0.01}, {1.0, 0.01}};
    std::vector<double> steady_rms;
    for (const auto& x : steady) steady_rms.push_back(std::abs(x));
    EXPECT_EQ(assess_window(steady_rms, 1.0, options(), steady).state, WindowState::kSettled);
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

/// x_k = 1 - 0.1 * 0.9^k: a transient approaching 1 geometrically, 10 % away at first.
const std::vector<double> kGeometricApproach{1.0 - 0.1, 1.0 - 0.09, 1.0 - 0.081, 1.0 - 0.0729};

TEST(AssessWindow, AGeometricApproachInsideTheSpreadIsNotSettled) {
    // Spread 2.9 % < 5 %, but 7.3 % of the way is still to come (more than half the
    // tolerance): a transient, not a steady state.
    const WindowVerdict r = assess_window(kGeometricApproach, 1.0, options());
    EXPECT_EQ(r.state, WindowState::kUnsettled);
    // Without the drift test the same window passed as settled.
    ControllerOptions no_drift = options();
    no_drift.drift_horizon_periods = 0;
    EXPECT_EQ(assess_window(kGeometricApproach, 1.0, no_drift).state, WindowState::kSettled);
}

TEST(AssessWindow, ADriftOfLessThanHalfTheToleranceIsSettledAtWhereItIsGoing) {
    // x_k = 1 - 0.01 * 0.5^k: 1 % still to come at most; the level is the steady value 1.
    const std::vector<double> v{1.0 - 0.01, 1.0 - 0.005, 1.0 - 0.0025, 1.0 - 0.00125};
    const WindowVerdict r = assess_window(v, 1.0, options());
    EXPECT_EQ(r.state, WindowState::kSettled);
    EXPECT_NEAR(r.level, 1.0, kRounding);
    EXPECT_NEAR(r.mean, (v[0] + v[1] + v[2] + v[3]) / 4.0, kRounding);
}

TEST(AssessWindow, ACreepThatDoesNotDecayIsNeverSettled) {
    // +0.5 % per period, forever: extrapolated over the 32-period horizon, 16 % to come.
    const std::vector<double> v{1.0, 1.005, 1.010, 1.015};
    EXPECT_EQ(assess_window(v, 1.0, options()).state, WindowState::kUnsettled);
}

TEST(AssessWindow, ADecayingDriftTowardTheTargetDecidesEarlyOnWhereItIsGoing) {
    // Heading for 1.0 while the target is 1.5: too low beyond doubt even where it ends.
    const WindowVerdict r = assess_window(kGeometricApproach, 1.5, options());
    EXPECT_EQ(r.state, WindowState::kEarlyLow);
    EXPECT_NEAR(r.level, 1.0, kRounding);
    // Heading for 1.0 with the target at 1.0: no early decision, it may get there.
    EXPECT_EQ(assess_window(kGeometricApproach, 1.0, options()).state, WindowState::kUnsettled);
}

TEST(AssessDrift, ScatterIsNotAGeometricDecay) {
    // Monotone, but successive ratios 0.2 and 4: not one decay.
    const Drift d = assess_drift(std::vector<double>{1.0, 1.05, 1.06, 1.10}, 32);
    EXPECT_TRUE(d.monotone);
    EXPECT_FALSE(d.decaying);
    EXPECT_FALSE(assess_drift(std::vector<double>{1.0, 1.05, 1.02, 1.03}, 32).monotone);
    EXPECT_FALSE(assess_drift(kGeometricApproach, 0).monotone);
}

TEST(AssessDrift, AGeometricDecayIsExtrapolatedToItsLimit) {
    const Drift d = assess_drift(kGeometricApproach, 32);
    EXPECT_TRUE(d.decaying);
    EXPECT_NEAR(d.ratio, 0.9, kRounding);
    EXPECT_NEAR(d.remaining, 0.0729, kRounding);
}

}  // namespace
}  // namespace sb::control

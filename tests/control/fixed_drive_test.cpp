// The fixed-drive point (no controller) on synthetic plants with analytic per-period RMS.
#include "control/fixed_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <stdexcept>

#include "tests/control/synthetic_plants.hpp"

namespace sb::control {
namespace {

using test::AlternatingPlant;
using test::NoisyPlant;
using test::SdofPlant;

constexpr double kMass = 1.0;
constexpr double kFn = 10.0;

double window_mean(const PointResult& r) {
    const auto begin = r.rms_per_period.begin() + r.window_begin;
    const auto end = r.rms_per_period.begin() + r.window_end;
    return std::accumulate(begin, end, 0.0) / static_cast<double>(r.window_end - r.window_begin);
}

/// Every period at the one amplitude, the window at the end, its mean recorded.
void expect_fixed_record(const PointResult& r, double amplitude) {
    EXPECT_EQ(r.amplitude_final, amplitude);
    EXPECT_EQ(r.updates, 0);
    ASSERT_EQ(r.amplitudes_tried.size(), 1u);
    for (double a : r.amplitude_per_period) EXPECT_EQ(a, amplitude);
    EXPECT_EQ(r.window_end, r.periods_simulated);
    EXPECT_LT(r.window_begin, r.window_end);
    EXPECT_DOUBLE_EQ(r.rms_final, window_mean(r));
    EXPECT_EQ(r.target_rms, 0.0);
}

TEST(FixedDrive, ALinearModeFromRestIsRecordedAtItsSteadyStateNotDuringTheTransient) {
    // 0.5 % damping, 2 % below resonance: the envelope sheds 3 % per period, so a window of
    // four periods within the 5 % tolerance comes long before the steady state. The drift
    // test holds the point until the steady state is within the tolerance.
    SdofPlant plant(kMass, kFn, 0.005);
    ControllerOptions o;
    o.max_periods = 400;
    const double amplitude = 0.2;  // N
    const double f = 9.8;
    const PointResult r = run_fixed_point(plant, f, amplitude, o);
    ASSERT_EQ(r.status, PointStatus::kConverged);
    expect_fixed_record(r, amplitude);
    const double steady = plant.steady_rms(amplitude, f);
    EXPECT_LE(std::abs(r.rms_final - steady) / steady, o.tolerance);
    EXPECT_GT(r.periods_simulated, 20);  // a transient of 1/(2 pi zeta) = 32 periods per e-fold
}

TEST(FixedDrive, WithoutTheDriftTestTheSameTransientIsRecordedFarFromItsSteadyState) {
    // What the test above guards against: the spread-only window takes the rising transient.
    SdofPlant plant(kMass, kFn, 0.005);
    ControllerOptions o;
    o.max_periods = 400;
    o.drift_horizon_periods = 0;
    const double f = 9.8;
    const PointResult r = run_fixed_point(plant, f, 0.2, o);
    ASSERT_EQ(r.status, PointStatus::kConverged);
    const double steady = plant.steady_rms(0.2, f);
    EXPECT_GT(std::abs(r.rms_final - steady) / steady, o.tolerance);
}

TEST(FixedDrive, AWellDampedModeSettlesAtTheClosedFormResponse) {
    SdofPlant plant(kMass, kFn, 0.05);
    ControllerOptions o;
    const double f = 12.0;
    const PointResult r = run_fixed_point(plant, f, 1.5, o);
    ASSERT_EQ(r.status, PointStatus::kConverged);
    expect_fixed_record(r, 1.5);
    // 1.5 N |H_acc| / sqrt 2, computed here from the SDOF's closed form.
    const double ratio = f / kFn;
    const double closed_form = 1.5 * ratio * ratio /
                               (kMass * std::hypot(1.0 - ratio * ratio, 2.0 * 0.05 * ratio)) /
                               std::sqrt(2.0);
    EXPECT_LE(std::abs(r.rms_final - closed_form) / closed_form, o.tolerance);
    EXPECT_EQ(r.window_end - r.window_begin, o.window_periods);
}

TEST(FixedDrive, AnAlternatingResponseIsATwoPeriodCycleAtItsTwoPeriodMean) {
    AlternatingPlant plant(kMass, kFn, 0.2, 0.2);
    ControllerOptions o;
    const PointResult r = run_fixed_point(plant, 10.0, 1.0, o);
    ASSERT_EQ(r.status, PointStatus::kLimitCycle2);
    expect_fixed_record(r, 1.0);
    EXPECT_NEAR(r.rms_final, plant.steady_rms(1.0, 10.0), 0.02 * plant.steady_rms(1.0, 10.0));
}

TEST(FixedDrive, AChaoticResponseIsUnsettledAndRecordsTheMeanOfTheLaterHalf) {
    // +/- 30 % per period (standard deviation 30 % / sqrt 3 = 17 %): never within a 5 %
    // window. The later half of 60 periods averages it down to 17 % / sqrt 29 = 3.2 %.
    NoisyPlant plant(2.0, 0.3, 7);
    ControllerOptions o;
    const PointResult r = run_fixed_point(plant, 10.0, 1.0, o);
    ASSERT_EQ(r.status, PointStatus::kUnsettled);
    expect_fixed_record(r, 1.0);
    EXPECT_EQ(r.periods_simulated, o.max_periods);
    const int after_transient = o.max_periods - o.transient_periods;
    EXPECT_EQ(r.window_end - r.window_begin, after_transient / 2);
    // The long mean is an unbiased estimate of the plant's gain 2: within three of its own
    // standard errors, and those small.
    double squares = 0.0;
    for (int p = r.window_begin; p < r.window_end; ++p) {
        const double d = r.rms_per_period[static_cast<std::size_t>(p)] - r.rms_final;
        squares += d * d;
    }
    const double n = r.window_end - r.window_begin;
    const double standard_error = std::sqrt(squares / (n - 1.0) / n);
    EXPECT_LT(standard_error, 0.05 * 2.0);
    EXPECT_NEAR(r.rms_final, 2.0, 3.0 * standard_error);
    EXPECT_EQ(to_string(r.status), "unsettled");
}

TEST(FixedDrive, AChaoticResponseSettlesOnTheMeansOfBlocksOfPeriods) {
    // The same +/- 30 % scatter averaged over blocks of 32 periods: the blocks' standard
    // deviation is 17 % / sqrt 32 = 3.1 %, so four of them fall within a 10 % window, as a
    // swept-sine analyser's averages do. The recorded window is whole blocks.
    NoisyPlant plant(2.0, 0.3, 7);
    ControllerOptions o;
    o.tolerance = 0.1;
    o.average_periods = 32;
    o.max_periods = 1000;
    const PointResult r = run_fixed_point(plant, 10.0, 1.0, o);
    ASSERT_EQ(r.status, PointStatus::kConverged);
    expect_fixed_record(r, 1.0);
    EXPECT_EQ(r.window_end - r.window_begin, o.window_periods * o.average_periods);
    EXPECT_EQ((r.periods_simulated - o.transient_periods) % o.average_periods, 0);
    // The mean of 128 periods: within three of its standard errors (17 % / sqrt 128) of 2.
    EXPECT_NEAR(r.rms_final, 2.0, 3.0 * 2.0 * 0.3 / std::sqrt(3.0 * 128.0));
}

TEST(FixedDrive, InvalidFrequencyAmplitudeOrOptionsAreRejected) {
    SdofPlant plant(kMass, kFn, 0.05);
    ControllerOptions o;
    EXPECT_THROW(run_fixed_point(plant, 0.0, 1.0, o), std::invalid_argument);
    EXPECT_THROW(run_fixed_point(plant, 10.0, -1.0, o), std::invalid_argument);
    EXPECT_THROW(run_fixed_point(plant, 10.0, std::nan(""), o), std::invalid_argument);
    o.tolerance = -0.1;
    EXPECT_THROW(run_fixed_point(plant, 10.0, 1.0, o), std::invalid_argument);
}

}  // namespace
}  // namespace sb::control

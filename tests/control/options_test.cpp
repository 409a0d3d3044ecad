// Validation of the controller options: defaults valid, every violation named by its key.
#include "control/options.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace sb::control {
namespace {

bool has_key(const Violations& v, const std::string& key) {
    return std::any_of(v.begin(), v.end(), [&](const Violation& x) { return x.key == key; });
}

TEST(ControllerOptions, DefaultsAreValid) { EXPECT_TRUE(ControllerOptions{}.validate().empty()); }

TEST(ControllerOptions, EveryViolationIsCollectedUnderItsConfigKey) {
    ControllerOptions o;
    o.tolerance = 0.0;
    o.window_periods = 2;
    o.transient_periods = -1;
    o.max_periods = 1;
    o.closest_rerun_periods = 0;
    o.initial_amplitude = -1.0;
    o.min_amplitude = 2.0;
    o.max_amplitude = 1.0;
    o.max_step_factor = 1.0;
    o.overshoot = -1.0;
    o.limit_cycle_jump = 0.5;
    o.max_restarts = -1;
    o.limit_cycle_periods = 5;
    const Violations v = o.validate();
    for (const char* key :
         {"tolerance", "window_periods", "early_periods", "transient_periods", "max_periods",
          "closest_rerun_periods", "initial_amplitude", "max_amplitude", "max_step_factor",
          "overshoot", "limit_cycle_jump", "max_restarts", "limit_cycle_periods"}) {
        EXPECT_TRUE(has_key(v, key)) << key;
    }
    for (const Violation& x : v) {
        EXPECT_FALSE(x.value.empty()) << x.key;
        EXPECT_FALSE(x.constraint.empty()) << x.key;
        EXPECT_FALSE(x.meaning.empty()) << x.key;
    }
}

TEST(ControllerOptions, InitialAmplitudeOutsideTheBoundsIsRejected) {
    ControllerOptions o;
    o.max_amplitude = 0.5;
    EXPECT_TRUE(has_key(o.validate(), "initial_amplitude"));
}

TEST(ControllerOptions, AveragesNeedAtLeastOnePeriodAndTheBudgetAWindowOfThem) {
    ControllerOptions o;
    o.average_periods = 0;
    EXPECT_TRUE(has_key(o.validate(), "average_periods"));
    // The default budget, 60 periods, holds the transient period and six blocks of 8 (the
    // two-period cycle's six values, more than the window's four: 49) but not of 16 (97).
    o.average_periods = 8;
    EXPECT_TRUE(o.validate().empty());
    o.average_periods = 16;
    EXPECT_TRUE(has_key(o.validate(), "max_periods"));
    o.max_periods = 97;
    EXPECT_TRUE(o.validate().empty());
    // Products beyond int do not wrap into a budget that passes.
    o.average_periods = 1 << 30;
    EXPECT_TRUE(has_key(o.validate(), "max_periods"));
}

TEST(ControllerOptions, EarlyDecisionCannotNeedMoreThanTheWindow) {
    ControllerOptions o;
    o.early_periods = 5;
    EXPECT_TRUE(has_key(o.validate(), "early_periods"));
    o.early_periods = 4;
    EXPECT_TRUE(o.validate().empty());
}

}  // namespace
}  // namespace sb::control

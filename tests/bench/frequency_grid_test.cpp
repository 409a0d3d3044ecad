// The stepped-sine frequency grid: given, or built around the first mode.
#include "bench/frequency_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace sb::bench {
namespace {

/// Closed-form grid points: only rounding.
constexpr double kGridRounding = 1e-9;
constexpr double kFirstModeHz = 6.37;

double phase(double r, double zeta) { return std::atan2(2.0 * zeta * r, 1.0 - r * r); }

TEST(FrequencyGrid, ABuiltGridSpansTheRatiosAndStepsEquallyInPhase) {
    FrequencyGridSpec spec;
    spec.low_ratio = 0.9;
    spec.high_ratio = 1.1;
    spec.count = 9;
    spec.grid_damping_ratio = 0.03;
    const auto grid = frequency_grid(spec, kFirstModeHz);
    ASSERT_EQ(grid.size(), 9u);
    EXPECT_NEAR(grid.front(), 0.9 * kFirstModeHz, kGridRounding);
    EXPECT_NEAR(grid.back(), 1.1 * kFirstModeHz, kGridRounding);
    const double step = (phase(1.1, 0.03) - phase(0.9, 0.03)) / 8.0;
    for (std::size_t k = 1; k < grid.size(); ++k) {
        EXPECT_GT(grid[k], grid[k - 1]) << "stepped upward";
        EXPECT_NEAR(phase(grid[k] / kFirstModeHz, 0.03) - phase(grid[k - 1] / kFirstModeHz, 0.03),
                    step, kGridRounding);
    }
}

TEST(FrequencyGrid, PointsCrowdNearResonance) {
    FrequencyGridSpec spec;
    spec.low_ratio = 0.9;
    spec.high_ratio = 1.1;
    spec.count = 11;
    const auto grid = frequency_grid(spec, kFirstModeHz);
    // The step next to the resonance is several times smaller than the steps at the ends.
    double smallest = 1e9;
    std::size_t at = 0;
    for (std::size_t k = 1; k < grid.size(); ++k) {
        if (grid[k] - grid[k - 1] < smallest) {
            smallest = grid[k] - grid[k - 1];
            at = k;
        }
    }
    EXPECT_NEAR(0.5 * (grid[at] + grid[at - 1]), kFirstModeHz, 0.02 * kFirstModeHz);
    EXPECT_LT(3.0 * smallest, grid[1] - grid[0]);
    EXPECT_LT(3.0 * smallest, grid[10] - grid[9]);
    // Half-power bandwidth of the grid's damping: at least three points inside it.
    const auto inside = std::count_if(grid.begin(), grid.end(), [](double f) {
        return std::abs(f / kFirstModeHz - 1.0) <= 0.03;
    });
    EXPECT_GE(inside, 3);
}

TEST(FrequencyGrid, DownwardReversesTheOrder) {
    FrequencyGridSpec spec;
    spec.count = 7;
    const auto up = frequency_grid(spec, kFirstModeHz);
    spec.direction = FrequencyGridSpec::Direction::down;
    auto down = frequency_grid(spec, kFirstModeHz);
    std::reverse(down.begin(), down.end());
    EXPECT_EQ(up, down);
}

TEST(FrequencyGrid, AGivenGridIsSortedInTheSweepDirection) {
    FrequencyGridSpec spec;
    spec.values_hz = {6.5, 6.0, 7.0};
    EXPECT_EQ(frequency_grid(spec, kFirstModeHz), (std::vector<double>{6.0, 6.5, 7.0}));
    spec.direction = FrequencyGridSpec::Direction::down;
    EXPECT_EQ(frequency_grid(spec, kFirstModeHz), (std::vector<double>{7.0, 6.5, 6.0}));
}

}  // namespace
}  // namespace sb::bench

// The parameter-drift test: a damping ratio calibrated level by level on the linear bench
// drifts when the measured damping grows with the level, and does not when it is constant.
#include "correlation/drift.hpp"

#include <gtest/gtest.h>

#include <iostream>

#include "calibration_fixtures.hpp"

namespace sb::correlation {
namespace {

using namespace testing;

constexpr const char* kDamping = "structure.damping.default_ratio";

/// The rigid bench at one or more levels, nine frequencies over ±4 % of the mode, with the
/// given damping ratio.
bench::CampaignConfig bench_at(const std::string& levels, double damping_ratio) {
    auto config = rigid_h0();
    bench::apply_overrides(
        config,
        {"campaign.levels_g=" + levels, std::string(kDamping) + "=" + exact_text(damping_ratio),
         "campaign.frequencies.count=9", "campaign.frequencies.low_ratio=0.96",
         "campaign.frequencies.high_ratio=1.04"});
    return config;
}

/// A recording at 1, 2 and 3 g whose damping ratio at level A is damping(A), 1 % noise.
template <typename Damping>
Measurement measured(const std::string& name, Damping damping) {
    bench::CampaignResult all;
    for (const double level : {1.0, 2.0, 3.0}) {
        auto one = predict(bench_at("[" + exact_text(level) + "]", damping(level)), {}, 1);
        if (all.recording.points.empty()) {
            all = one;
        } else {
            for (auto& p : one.recording.points) all.recording.points.push_back(p);
        }
    }
    const auto dir = fresh_dir(name);
    write_noisy_recording(all, 0.01, 11, dir);
    return read_measurement(dir, {0.05, 0.002, 0.01 * std::sqrt(2.0)});
}

DriftResult drift_of(const Measurement& m) {
    const auto config = bench_at("[1.0, 2.0, 3.0]", 0.005);
    CalibrationOptions options;
    options.simulate = predict;
    options.search.budget = 20;
    const auto free = parse_free_parameters(config, {std::string(kDamping) + "=0.002:0.02"});
    auto r = drift_test(config, m, free.front(), options);
    std::cout << r.sentence << '\n';
    return r;
}

TEST(Drift, ADampingThatGrowsWithTheLevelDrifts) {
    // ζ(A) = 0.004 + 0.002 A: 0.6, 0.8 and 1.0 % at 1, 2 and 3 g.
    const auto r = drift_of(measured("drift-grows", [](double a) { return 0.004 + 0.002 * a; }));
    ASSERT_EQ(r.levels.size(), 3U);
    EXPECT_EQ(r.used, 3);
    EXPECT_TRUE(r.drifts) << r.sentence;
    EXPECT_NEAR(r.slope, 0.002, 0.0004) << r.sentence;
    for (const auto& v : r.levels) {
        EXPECT_NEAR(v.value, 0.004 + 0.002 * v.level_g, 0.05 * (0.004 + 0.002 * v.level_g));
    }
    EXPECT_NE(r.sentence.find("drifts with the level"), std::string::npos);
}

TEST(Drift, AConstantDampingDoesNotDrift) {
    const auto r = drift_of(measured("drift-constant", [](double) { return 0.008; }));
    EXPECT_EQ(r.used, 3);
    EXPECT_FALSE(r.drifts) << r.sentence;
    EXPECT_LT(std::abs(r.slope), 3.0 * r.slope_sigma) << r.sentence;
}

}  // namespace
}  // namespace sb::correlation

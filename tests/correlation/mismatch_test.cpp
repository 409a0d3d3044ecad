// Locating a mismatch: the scaling laws of a residual over the levels recovered from
// synthetic residuals, the χ² quantile against tabulated values, the features of a recording
// and the features that disagree between two of them.
#include "correlation/mismatch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>

#include "calibration_fixtures.hpp"

namespace sb::correlation {
namespace {

using namespace testing;

/// Δ = c A^p at levels 0.5 ... 8 g, each perturbed by a fixed ±1 σ pattern, σ = 3 % of the
/// largest |Δ|.
std::vector<LevelResidual> residuals_like(double c, double p) {
    const std::vector<double> levels{0.5, 1.0, 2.0, 4.0, 8.0};
    const std::vector<double> pattern{0.6, -0.9, 0.3, 0.8, -0.5};
    double largest = 0.0;
    for (double a : levels) largest = std::max(largest, std::abs(c * std::pow(a, p)));
    std::vector<LevelResidual> out;
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const double sigma = 0.03 * largest;
        out.push_back({levels[k], c * std::pow(levels[k], p) + pattern[k] * sigma, sigma});
    }
    return out;
}

TEST(ScalingLaw, EachShapeIsRecognisedFromItsResiduals) {
    EXPECT_EQ(fit_scaling(residuals_like(0.002, 0.0)).front().shape, ScalingShape::constant);
    EXPECT_EQ(fit_scaling(residuals_like(0.002, 1.0)).front().shape, ScalingShape::linear);
    EXPECT_EQ(fit_scaling(residuals_like(0.002, -1.0)).front().shape, ScalingShape::inverse);
    EXPECT_EQ(fit_scaling(residuals_like(0.002, 2.0)).front().shape, ScalingShape::quadratic);
    // Microslip: 0 < χ < 1, recovered with an interval that holds it.
    const auto microslip = fit_scaling(residuals_like(0.002, 0.5));
    ASSERT_EQ(microslip.front().shape, ScalingShape::power);
    EXPECT_NEAR(microslip.front().exponent, 0.5, 0.05);
    EXPECT_LE(microslip.front().exponent_lo, 0.5);
    EXPECT_GE(microslip.front().exponent_hi, 0.5);
    EXPECT_NEAR(microslip.front().coefficient, 0.002, 0.0002);
    // Noise alone: no shape earns its parameter.
    std::vector<LevelResidual> noise;
    for (const auto& r : residuals_like(0.0, 0.0)) noise.push_back({r.level, 0.4 * r.sigma, 1.0});
    for (auto& r : noise) r.residual = r.residual == 0.0 ? 0.3 : r.residual;
    EXPECT_EQ(fit_scaling(noise).front().shape, ScalingShape::none);
}

TEST(ScalingLaw, BadResidualsAreRefused) {
    EXPECT_THROW(fit_scaling({}), std::invalid_argument);
    EXPECT_THROW(fit_scaling({{0.0, 1.0, 1.0}}), std::invalid_argument);
    EXPECT_THROW(fit_scaling({{1.0, 1.0, 0.0}}), std::invalid_argument);
    EXPECT_THROW(fit_scaling({{1.0, std::nan(""), 1.0}}), std::invalid_argument);
}

TEST(Mismatch, TheChiSquaredQuantileMatchesItsTables) {
    // Tabulated: χ²(0.99; 1) = 6.635, (0.99; 4) = 13.277, (0.95; 10) = 18.307.
    EXPECT_NEAR(chi2_quantile(0.99, 1), 6.635, 0.03 * 6.635);
    EXPECT_NEAR(chi2_quantile(0.99, 4), 13.277, 0.005 * 13.277);
    EXPECT_NEAR(chi2_quantile(0.95, 10), 18.307, 0.002 * 18.307);
}

TEST(Mismatch, AConstantDampingOffsetIsLocatedAndAMatchingFrequencyIsNot) {
    std::vector<LevelFeatureValues> measured;
    std::vector<LevelFeatureValues> simulated;
    for (double level : {1.0, 2.0, 3.0, 4.0}) {
        LevelFeatureValues m{"H-0", level, 1, {}, {}};
        m.value.fill(std::nan(""));
        m.sigma.fill(std::nan(""));
        auto s = m;
        const auto f = static_cast<std::size_t>(LevelFeature::natural_frequency);
        const auto z = static_cast<std::size_t>(LevelFeature::damping_ratio);
        m.value[f] = 6.37 + 0.001 * (level - 2.5);
        s.value[f] = 6.37;
        m.sigma[f] = s.sigma[f] = 0.01;
        m.value[z] = 0.012;
        s.value[z] = 0.010;
        m.sigma[z] = s.sigma[z] = 0.0002;
        measured.push_back(m);
        simulated.push_back(s);
    }
    const auto found = locate_mismatch(measured, simulated);
    ASSERT_EQ(found.size(), 2U);
    EXPECT_EQ(found[0].feature, LevelFeature::damping_ratio);
    EXPECT_TRUE(found[0].beyond_noise);
    EXPECT_EQ(found[0].levels_beyond.size(), 4U);
    EXPECT_EQ(found[0].scaling.front().shape, ScalingShape::constant);
    EXPECT_NEAR(found[0].scaling.front().coefficient, 0.002, 1e-9);
    EXPECT_NE(found[0].sentence.find("H-0: the damping ratio disagrees beyond the noise"),
              std::string::npos)
        << found[0].sentence;
    EXPECT_EQ(found[1].feature, LevelFeature::natural_frequency);
    EXPECT_FALSE(found[1].beyond_noise) << found[1].sentence;
}

TEST(Mismatch, ARecordingWithMoreStructuralDampingDiffersInDampingAndPeakNotInFrequency) {
    // The linear bench of the calibration tests, measured with 0.8 % damping (1 % noise on
    // every channel), simulated with 0.5 %: the damping ratio and the peak disagree, the
    // frequency does not.
    // Nine frequencies over ±4 % of the mode: enough for the circle fit and half-power.
    const auto bench_with = [](const std::string& damping) {
        auto config = rigid_h0();
        bench::apply_overrides(
            config,
            {"structure.damping.default_ratio=" + damping, "campaign.frequencies.count=9",
             "campaign.frequencies.low_ratio=0.96", "campaign.frequencies.high_ratio=1.04"});
        return config;
    };
    const auto dir = fresh_dir("mismatch");
    write_noisy_recording(predict(bench_with("0.008"), {}, 1), 0.01, 3, dir);
    const auto measured = level_feature_values(identification::read_recording(dir), kStated);
    const auto simulated =
        level_feature_values(predict(bench_with("0.005"), {}, 1).recording, kStated);
    ASSERT_EQ(measured.size(), 2U);
    ASSERT_EQ(simulated.size(), 2U);
    const auto found = locate_mismatch(measured, simulated);
    for (const auto& m : found) std::cout << m.sentence << '\n';
    const auto find = [&](LevelFeature f) {
        for (const auto& m : found) {
            if (m.feature == f) return m;
        }
        throw std::runtime_error("no " + level_feature_name(f));
    };
    EXPECT_TRUE(find(LevelFeature::damping_ratio).beyond_noise);
    EXPECT_TRUE(find(LevelFeature::peak_magnitude).beyond_noise);
    EXPECT_FALSE(find(LevelFeature::natural_frequency).beyond_noise)
        << find(LevelFeature::natural_frequency).sentence;
    // Measured damping above the simulated one by about 0.3 % at both levels.
    for (const auto& r : find(LevelFeature::damping_ratio).residuals) {
        EXPECT_NEAR(r.residual, 0.003, 0.0008);
    }
}

}  // namespace
}  // namespace sb::correlation

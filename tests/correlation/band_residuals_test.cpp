// FRF residuals per band against a single-degree-of-freedom accelerance known in closed form:
// a stiffer model moves the whole curve, so both flanks disagree with opposite signs; a more
// damped one disagrees most around the resonance; the same model agrees everywhere.
#include "correlation/band_residuals.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

namespace sb::correlation {
namespace {

constexpr double kNaturalHz = 10.0;
constexpr double kDamping = 0.01;
constexpr double kSigma = 0.02;  // of ln|H| and of the phase [rad]

/// Accelerance of a unit-mass oscillator: -w^2 / (wn^2 - w^2 + 2 i zeta wn w).
std::complex<double> accelerance(double f, double fn, double zeta) {
    const double w = 2.0 * M_PI * f;
    const double wn = 2.0 * M_PI * fn;
    return -w * w / std::complex<double>(wn * wn - w * w, 2.0 * zeta * wn * w);
}

/// 21 frequencies over +-5 % of the mode, crowded around it as the bench's grid is.
std::vector<double> grid() {
    std::vector<double> f;
    for (int k = -10; k <= 10; ++k) {
        const double t = k / 10.0;
        f.push_back(kNaturalHz * (1.0 + 0.05 * t * std::abs(t)));
    }
    return f;
}

struct Case {
    Measurement measurement;
    SimulatedFeatures simulated;
    std::vector<LevelFeatureValues> levels;
};

/// The measurement of the oscillator (fn, zeta as above) against a model with `model_fn`
/// and `model_zeta`.
Case compare(double model_fn, double model_zeta) {
    Case c;
    for (const double f : grid()) {
        const auto measured = accelerance(f, kNaturalHz, kDamping);
        const auto model = accelerance(f, model_fn, model_zeta);
        for (const auto kind : {FeatureKind::log_magnitude, FeatureKind::phase}) {
            Feature ft;
            ft.arrangement = "A";
            ft.level_g = 1.0;
            ft.kind = kind;
            ft.frequency_hz = f;
            const bool magnitude = kind == FeatureKind::log_magnitude;
            ft.value = magnitude ? std::log(std::abs(measured)) : std::arg(measured);
            ft.sigma = kSigma;
            c.measurement.features.push_back(ft);
            c.simulated.value.push_back(magnitude ? std::log(std::abs(model)) : std::arg(model));
        }
    }
    LevelFeatureValues level;
    level.arrangement = "A";
    level.level_g = 1.0;
    level.value.fill(std::nan(""));
    level.value[static_cast<std::size_t>(LevelFeature::natural_frequency)] = kNaturalHz;
    level.value[static_cast<std::size_t>(LevelFeature::damping_ratio)] = kDamping;
    c.levels.push_back(level);
    return c;
}

const BandResidual& band(const std::vector<BandResidual>& bands, FrfBand which) {
    for (const auto& b : bands) {
        if (b.band == which) return b;
    }
    throw std::logic_error("no such band");
}

TEST(BandResiduals, AStifferModelDisagreesOnBothFlanksWithOppositeSigns) {
    const Case c = compare(1.01 * kNaturalHz, kDamping);
    const auto bands = band_residuals(c.measurement, c.simulated, c.levels);
    ASSERT_EQ(bands.size(), 3U);
    const auto& below = band(bands, FrfBand::below);
    const auto& above = band(bands, FrfBand::above);
    EXPECT_TRUE(below.beyond_noise) << below.sentence;
    EXPECT_TRUE(above.beyond_noise) << above.sentence;
    // Below its resonance the measured curve is nearer its peak than the stiffer model's:
    // larger; above, the model's peak is nearer: the measured is smaller.
    EXPECT_GT(below.mean_log_ratio, 0.0);
    EXPECT_LT(above.mean_log_ratio, 0.0);
    EXPECT_NE(below.sentence.find("% above the simulation's"), std::string::npos) << below.sentence;
    // The half-power band holds the points within 1 % of the mode: the grid's 0, +-0.05 %,
    // +-0.2 %, +-0.45 % and +-0.8 %.
    EXPECT_EQ(band(bands, FrfBand::resonance).points, 9);
    EXPECT_EQ(below.points + above.points, 12);
}

TEST(BandResiduals, AMoreDampedModelDisagreesMostAroundTheResonance) {
    const Case c = compare(kNaturalHz, 1.2 * kDamping);
    const auto bands = band_residuals(c.measurement, c.simulated, c.levels);
    ASSERT_EQ(bands.size(), 3U);
    const auto& resonance = band(bands, FrfBand::resonance);
    EXPECT_TRUE(resonance.beyond_noise) << resonance.sentence;
    EXPECT_GT(resonance.mean_log_ratio, 0.0);  // less damping measured: a higher peak
    // Per frequency, χ² around the resonance more than four times the flanks' (on a grid of
    // ±5 % the flanks are within five half-power bandwidths and still feel the damping).
    const auto per_point = [](const BandResidual& b) {
        return (b.chi2_magnitude + b.chi2_phase) / b.points;
    };
    EXPECT_GT(per_point(resonance), 4.0 * per_point(band(bands, FrfBand::below)));
    EXPECT_GT(per_point(resonance), 4.0 * per_point(band(bands, FrfBand::above)));
    EXPECT_EQ(bands.front().band, FrfBand::resonance);  // the largest χ² first
}

TEST(BandResiduals, TheSameModelAgreesInEveryBand) {
    const Case c = compare(kNaturalHz, kDamping);
    const auto bands = band_residuals(c.measurement, c.simulated, c.levels);
    ASSERT_EQ(bands.size(), 3U);
    for (const auto& b : bands) {
        EXPECT_FALSE(b.beyond_noise) << b.sentence;
        EXPECT_EQ(b.chi2_magnitude + b.chi2_phase, 0.0);
        EXPECT_NE(b.sentence.find("agrees within the noise"), std::string::npos);
    }
}

TEST(BandResiduals, ALevelWithoutAModalEstimateIsLeftOut) {
    Case c = compare(1.01 * kNaturalHz, kDamping);
    c.levels.front().value[static_cast<std::size_t>(LevelFeature::damping_ratio)] = std::nan("");
    EXPECT_TRUE(band_residuals(c.measurement, c.simulated, c.levels).empty());
}

}  // namespace
}  // namespace sb::correlation

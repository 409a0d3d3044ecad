// Harmonic extraction over whole periods and the H1 estimator, including the noisy pipeline.
#include "identification/harmonics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/units.hpp"
#include "identification/circle_fit.hpp"
#include "identification/h1_estimator.hpp"
#include "identification/half_power.hpp"
#include "identification/rational_fraction.hpp"
#include "sdof_frf.hpp"

namespace sb::identification {
namespace {

/// Whole-period FFT of exact harmonics is exact up to round-off of an N-point sum.
constexpr double kRoundOff = 1e-10;
/// The bound for the noisy pipeline: damping within 5 %.
constexpr double kNoisyDampingTolerance = 0.05;

std::vector<double> signal(double fs, double f, int samples,
                           const std::vector<std::complex<double>>& harmonics) {
    std::vector<double> x(static_cast<std::size_t>(samples));
    for (int m = 0; m < samples; ++m) {
        const double t = m / fs;
        for (std::size_t k = 0; k < harmonics.size(); ++k) {
            x[static_cast<std::size_t>(m)] +=
                (harmonics[k] *
                 std::exp(std::complex<double>(0.0, kTwoPi * f * static_cast<double>(k) * t)))
                    .real();
        }
    }
    return x;
}

TEST(Harmonics, RecoverPeakComplexAmplitudesAndThdOnWholePeriods) {
    // 40 samples per period, 7 periods, plus 13 spare samples that must be ignored.
    const double fs = 2000.0, f = 50.0;
    const std::vector<std::complex<double>> h = {{0.3, 0.0}, {1.0, -2.0}, {0.0, 0.0}, {0.1, 0.2}};
    const auto x = signal(fs, f, 7 * 40 + 13, h);
    const auto a = analyse_harmonics(x, fs, f);
    EXPECT_EQ(a.periods, 7);
    EXPECT_EQ(a.samples, 280);
    for (std::size_t k = 0; k < h.size(); ++k) {
        EXPECT_NEAR(std::abs(a.amplitude[k] - h[k]), 0.0, kRoundOff) << "harmonic " << k;
    }
    EXPECT_NEAR(a.thd, std::abs(h[3]) / std::abs(h[1]), kRoundOff);
    EXPECT_NEAR(rms_over_whole_periods(x, fs, f),
                std::sqrt(0.09 + 0.5 * std::norm(h[1]) + 0.5 * std::norm(h[3])), kRoundOff);
}

TEST(Harmonics, UseTheLongestWholeNumberOfPeriodsWhenAPeriodIsNotAWholeNumberOfSamples) {
    // 1000/6.4 = 156.25 samples per period: 4 periods are exactly 625 samples.
    EXPECT_EQ(whole_periods(2000, 1000.0, 6.4), 12);
    const auto x = signal(1000.0, 6.4, 2000, {{0.0, 0.0}, {0.5, 0.5}});
    EXPECT_NEAR(std::abs(fundamental_amplitude(x, 1000.0, 6.4) - std::complex<double>(0.5, 0.5)),
                0.0, kRoundOff);
    EXPECT_THROW(analyse_harmonics(std::vector<double>(10, 0.0), 1000.0, 6.4),
                 std::invalid_argument);
}

TEST(Harmonics, RatioToTheFundamentalIsUnknownAtOrAboveNyquistAndForAZeroFundamental) {
    // 5 samples per period, 4 periods: bins 4 (k = 1) and 8 (k = 2) lie below Nyquist (bin 10),
    // bin 12 (k = 3) above it.
    const double fs = 50.0, f = 10.0;
    const auto x = signal(fs, f, 20, {{0.0, 0.0}, {2.0, 0.0}, {0.0, -0.5}});
    const auto a = analyse_harmonics(x, fs, f, 3);
    EXPECT_NEAR(harmonic_ratio(a, 2), 0.25, kRoundOff);
    EXPECT_TRUE(std::isnan(harmonic_ratio(a, 3)));
    EXPECT_TRUE(std::isnan(harmonic_ratio(analyse_harmonics(x, fs, f, 1), 2)));
    EXPECT_TRUE(
        std::isnan(harmonic_ratio(analyse_harmonics(std::vector<double>(20, 1.0), fs, f), 2)));
    EXPECT_THROW(harmonic_ratio(a, 0), std::invalid_argument);
}

TEST(H1Estimator, GivesTheExactRatioAndUnitCoherenceOnCleanData) {
    const double fs = 1024.0, f = 16.0;
    const auto force = signal(fs, f, 64 * 10, {{0.0, 0.0}, {2.0, 0.0}});
    const auto acc = signal(fs, f, 64 * 10, {{0.0, 0.0}, {0.0, 3.0}});
    const auto e = h1_estimate(force, acc, fs, f, 2);
    EXPECT_EQ(e.segments, 5);
    EXPECT_NEAR(std::abs(e.h1 - std::complex<double>(0.0, 1.5)), 0.0, kRoundOff);
    EXPECT_NEAR(e.coherence, 1.0, kRoundOff);
}

/// Stepped-sine FRF of an SDOF (m = 1 kg) from simulated time histories: a 1 N sine at every
/// grid frequency, force and acceleration each with Gaussian noise of 1 % of their RMS, 40
/// periods of 64 samples (the bench steps an integer number of steps per period), H1 over
/// one-period segments.
Frf noisy_frf(double fn, double zeta, int points, double shift, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    Frf frf{{}, {}, FrfForm::accelerance};
    for (double f : testing::grid_around(fn, zeta, points, 3.0, shift)) {
        const int periods = 40;
        const double fs_point = 64.0 * f;
        const int n = 64 * periods;
        const double w = hz_to_rad_s(f), wn = hz_to_rad_s(fn);
        const std::complex<double> force(1.0, 0.0);
        const std::complex<double> acc =
            -w * w * force / std::complex<double>(wn * wn - w * w, 2.0 * zeta * wn * w);
        auto fx = signal(fs_point, f, n, {{0.0, 0.0}, force});
        auto ax = signal(fs_point, f, n, {{0.0, 0.0}, acc});
        const double f_rms = std::abs(force) / std::sqrt(2.0);
        const double a_rms = std::abs(acc) / std::sqrt(2.0);
        for (auto& v : fx) v += 0.01 * f_rms * noise(rng);
        for (auto& v : ax) v += 0.01 * a_rms * noise(rng);
        const auto h = h1_estimate(fx, ax, fs_point, f, 1);
        EXPECT_GT(h.coherence, 0.999);
        frf.frequency_hz.push_back(f);
        frf.value.push_back(h.h1);
    }
    return frf;
}

TEST(NoisyPipeline, IdentifiesSdofDampingWithinFivePercentFromTimeHistoriesWithOnePercentNoise) {
    // Several damping ratios, grid sizes (all with at least 3 points in the half-power band
    // over ±3 half-bandwidths) and noise seeds; every method, every case within 5 %.
    const double fn = 20.0;
    int cases = 0;
    for (double zeta : {0.005, 0.02, 0.1}) {
        for (int points : {15, 25, 41}) {
            for (unsigned seed : {12345u, 2u, 77u}) {
                const Frf frf = noisy_frf(fn, zeta, points, 0.3, seed);
                const std::string what = "zeta=" + std::to_string(zeta) +
                                         " points=" + std::to_string(points) +
                                         " seed=" + std::to_string(seed);
                for (const auto& e :
                     {half_power(frf), circle_fit(frf), rational_fraction_fit(frf)}) {
                    ASSERT_TRUE(e.ok()) << what << ": " << e.message;
                    EXPECT_NEAR(e.damping_ratio / zeta, 1.0, kNoisyDampingTolerance) << what;
                    EXPECT_NEAR((e.natural_frequency_hz - fn) / (zeta * fn), 0.0,
                                kNoisyDampingTolerance)
                        << what;
                }
                ++cases;
            }
        }
    }
    EXPECT_EQ(cases, 27);
}

TEST(NoisyPipeline, FundamentalRatioAgreesWithH1WithinTheNoise) {
    const double f = 20.0, fs = 64.0 * f;
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 1.0);
    auto fx = signal(fs, f, 64 * 40, {{0.0, 0.0}, {1.0, 0.0}});
    auto ax = signal(fs, f, 64 * 40, {{0.0, 0.0}, {0.0, 4.0}});
    for (auto& v : fx) v += 0.01 / std::sqrt(2.0) * noise(rng);
    for (auto& v : ax) v += 0.04 / std::sqrt(2.0) * noise(rng);
    const auto h = h1_estimate(fx, ax, fs, f, 1);
    const auto ratio = fundamental_amplitude(ax, fs, f) / fundamental_amplitude(fx, fs, f);
    // 1 % noise on 2560 samples: the fundamental's relative error is ~1e-2/√1280 ≈ 3e-4.
    EXPECT_NEAR(std::abs(ratio - h.h1) / std::abs(h.h1), 0.0, 0.01);
}

}  // namespace
}  // namespace sb::identification

// Welch's spectra against systems whose transfer function and coherence are known exactly:
// a FIR filter, with and without noise on its output, and white noise's density.
#include "identification/welch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "identification/spectrum.hpp"

namespace sb::identification {
namespace {

constexpr double kRateHz = 1000.0;
constexpr int kSegment = 1000;  // 1 Hz lines

std::vector<double> white(std::size_t n, double rms, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, rms);
    std::vector<double> x(n);
    for (double& v : x) v = normal(rng);
    return x;
}

/// y[n] = 0.5 x[n] + 0.3 x[n-1] - 0.2 x[n-2], and its transfer function.
std::vector<double> fir(const std::vector<double>& x) {
    std::vector<double> y(x.size());
    for (std::size_t n = 0; n < x.size(); ++n) {
        y[n] = 0.5 * x[n] + (n >= 1 ? 0.3 * x[n - 1] : 0.0) - (n >= 2 ? 0.2 * x[n - 2] : 0.0);
    }
    return y;
}

std::complex<double> fir_response(double f_hz) {
    const std::complex<double> z = std::polar(1.0, -2.0 * std::numbers::pi * f_hz / kRateHz);
    return 0.5 + 0.3 * z - 0.2 * z * z;
}

/// Welch with half-overlapping segments over the whole record.
WelchSpectra welch(const std::vector<double>& x, const std::vector<double>& y, double low_hz,
                   double high_hz) {
    WelchSpectra spectra(kSegment, kRateHz, low_hz, high_hz, 1);
    for (std::size_t start = 0; start + kSegment <= x.size(); start += kSegment / 2) {
        const std::span<const double> xs(x.data() + start, kSegment);
        const std::span<const double> ys(y.data() + start, kSegment);
        spectra.add_segment(xs, {ys});
    }
    return spectra;
}

TEST(Spectrum, TheInverseGivesTheSequenceBack) {
    for (int n : {16, 17, 1000}) {
        const auto x = white(static_cast<std::size_t>(n), 1.0, 7);
        const auto back = inverse_real_spectrum(real_spectrum(x), n);
        ASSERT_EQ(back.size(), x.size());
        for (int m = 0; m < n; ++m) EXPECT_NEAR(back[m], x[m], 1e-12) << n << " " << m;
    }
    EXPECT_THROW(inverse_real_spectrum(std::vector<std::complex<double>>(5), 16),
                 std::invalid_argument);
}

TEST(Welch, H1OfAFirFilterIsItsTransferFunctionAndItsCoherenceOne) {
    const auto x = white(64 * kSegment, 1.0, 1);
    const auto y = fir(x);
    const WelchSpectra s = welch(x, y, 10.0, 400.0);
    EXPECT_EQ(s.segments(), 127);
    EXPECT_DOUBLE_EQ(s.frequency_hz(0), 10.0);
    EXPECT_DOUBLE_EQ(s.frequency_hz(s.bins() - 1), 400.0);
    for (int k = 0; k < s.bins(); ++k) {
        const auto expected = fir_response(s.frequency_hz(k));
        // The filter's two-sample memory against 1000-sample Hann segments: the leakage of
        // its start and end is of order 2/1000 of a line's power, averaged down.
        EXPECT_LT(std::abs(s.h1(0, k) - expected), 2e-3 * std::abs(expected)) << s.frequency_hz(k);
        EXPECT_GT(s.coherence(0, k), 0.999) << s.frequency_hz(k);
    }
}

TEST(Welch, NoiseOnTheResponseLeavesH1AndLowersTheCoherenceAsTheSignalToNoiseSays) {
    // White noise of RMS 0.3 on the output: gamma² = |H|² Sxx / (|H|² Sxx + Snn), Sxx and Snn
    // both flat.
    const auto x = white(400 * kSegment, 1.0, 2);
    auto y = fir(x);
    const auto noise = white(y.size(), 0.3, 3);
    for (std::size_t n = 0; n < y.size(); ++n) y[n] += noise[n];
    const WelchSpectra s = welch(x, y, 10.0, 400.0);
    double worst_h = 0.0, worst_coherence = 0.0;
    for (int k = 0; k < s.bins(); ++k) {
        const auto h = fir_response(s.frequency_hz(k));
        const double signal = std::norm(h);
        const double expected = signal / (signal + 0.09);
        worst_h = std::max(worst_h, std::abs(s.h1(0, k) - h) / std::abs(h));
        worst_coherence = std::max(worst_coherence, std::abs(s.coherence(0, k) / expected - 1.0));
    }
    // Random errors of 799 averages (Bendat & Piersol 2010, Table 9.6): of |H1| about
    // sqrt(1 - g²)/(|g| sqrt(2 n)) <= 2.4 % here, of g² about sqrt(2)(1 - g²)/(|g| sqrt(n))
    // <= 4 %; the worst of 391 lines lies within about four of them.
    EXPECT_LT(worst_h, 0.08);
    EXPECT_LT(worst_coherence, 0.12);
    EXPECT_GT(worst_h, 0.0);
}

TEST(Welch, TheDensityOfWhiteNoiseIsTwiceItsVarianceOverTheRate) {
    const auto x = white(200 * kSegment, 2.0, 4);
    const WelchSpectra s = welch(x, x, 10.0, 490.0);
    double mean = 0.0;
    for (int k = 0; k < s.bins(); ++k) mean += s.reference_psd(k) / s.bins();
    // One-sided: 2 sigma² / fs = 8e-3 per Hz; 481 lines of 399 averages each.
    EXPECT_NEAR(mean, 2.0 * 4.0 / kRateHz, 0.01 * 8e-3);
    EXPECT_NEAR(s.response_psd(0, 7), s.reference_psd(7), 1e-15);
}

TEST(Welch, SumsContinueWhereTheyStoppedStartOverWhenClearedAndRefuseAnotherBand) {
    const auto x = white(8 * kSegment, 1.0, 5);
    const auto y = fir(x);
    const WelchSpectra whole = welch(x, y, 10.0, 400.0);
    WelchSpectra first(kSegment, kRateHz, 10.0, 400.0, 1);
    for (int seg = 0; seg < 3; ++seg) {
        first.add_segment({x.data() + seg * 500, kSegment}, {{y.data() + seg * 500, kSegment}});
    }
    WelchSpectra resumed(kSegment, kRateHz, 10.0, 400.0, 1);
    resumed.restore(first.sums());
    for (int seg = 3; seg < 15; ++seg) {
        resumed.add_segment({x.data() + seg * 500, kSegment}, {{y.data() + seg * 500, kSegment}});
    }
    ASSERT_EQ(resumed.segments(), whole.segments());
    for (int k = 0; k < whole.bins(); ++k) EXPECT_EQ(resumed.h1(0, k), whole.h1(0, k));
    resumed.clear();
    EXPECT_EQ(resumed.segments(), 0);
    resumed.add_segment({x.data(), kSegment}, {{y.data(), kSegment}});
    WelchSpectra single(kSegment, kRateHz, 10.0, 400.0, 1);
    single.add_segment({x.data(), kSegment}, {{y.data(), kSegment}});
    EXPECT_EQ(resumed.h1(0, 5), single.h1(0, 5));
    WelchSpectra other(kSegment, kRateHz, 20.0, 400.0, 1);
    EXPECT_THROW(other.restore(first.sums()), std::invalid_argument);
    EXPECT_THROW(WelchSpectra(kSegment, kRateHz, 10.0, 600.0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace sb::identification

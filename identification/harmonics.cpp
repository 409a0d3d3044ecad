// Harmonic analysis over whole periods with an FFTW real-to-complex transform.
#include "identification/harmonics.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "identification/spectrum.hpp"

namespace sb::identification {

namespace {
/// A sample count within this of an integer is taken as exact (simulations step exactly).
constexpr double kWholeSampleTolerance = 1e-6;
}  // namespace

int whole_periods(std::size_t samples, double sample_rate_hz, double frequency_hz) {
    if (!(sample_rate_hz > 0.0) || !(frequency_hz > 0.0)) return 0;
    const double per_period = sample_rate_hz / frequency_hz;
    for (auto p = static_cast<long>(std::floor(static_cast<double>(samples) / per_period + 1e-9));
         p > 0; --p) {
        const double n = static_cast<double>(p) * per_period;
        if (std::abs(n - std::round(n)) < kWholeSampleTolerance &&
            std::round(n) <= static_cast<double>(samples)) {
            return static_cast<int>(p);
        }
    }
    return 0;
}

HarmonicAnalysis analyse_harmonics(std::span<const double> x, double sample_rate_hz,
                                   double frequency_hz, int max_harmonic) {
    const int p = whole_periods(x.size(), sample_rate_hz, frequency_hz);
    if (p == 0) {
        throw std::invalid_argument(
            "analyse_harmonics: no whole number of periods spans an integer number of samples");
    }
    const auto n = static_cast<std::size_t>(
        std::llround(static_cast<double>(p) * sample_rate_hz / frequency_hz));
    const auto y = real_spectrum(x.first(n));
    HarmonicAnalysis h;
    h.periods = p;
    h.samples = static_cast<int>(n);
    h.amplitude.assign(static_cast<std::size_t>(max_harmonic) + 1, {0.0, 0.0});
    const double scale = static_cast<double>(n);
    h.amplitude[0] = y[0] / scale;
    // FFTW computes Y_j = Σ x_m e^{−2πi jm/N}; for x = Re{X e^{iωt}} = (X e^{iωt} + c.c.)/2 with
    // P periods in N samples, Y_{kP} = N X_k / 2 exactly, and no other harmonic leaks there.
    for (int k = 1; k <= max_harmonic; ++k) {
        const auto bin = static_cast<std::size_t>(k) * static_cast<std::size_t>(p);
        if (2 * bin >= n) break;  // at or above Nyquist
        h.amplitude[static_cast<std::size_t>(k)] = 2.0 * y[bin] / scale;
    }
    double sum = 0.0;
    for (std::size_t k = 2; k < h.amplitude.size(); ++k) sum += std::norm(h.amplitude[k]);
    const double fundamental = std::abs(h.amplitude.size() > 1 ? h.amplitude[1] : 0.0);
    h.thd = fundamental > 0.0 ? std::sqrt(sum) / fundamental : 0.0;
    return h;
}

double harmonic_ratio(const HarmonicAnalysis& analysis, int k) {
    if (k < 1) throw std::invalid_argument("harmonic_ratio: the order k must be >= 1");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const auto order = static_cast<std::size_t>(k);
    // Bin kP must lie below Nyquist (2kP < N), as in analyse_harmonics: a harmonic there is
    // not zero but unknown.
    if (order >= analysis.amplitude.size() ||
        2L * k * static_cast<long>(analysis.periods) >= static_cast<long>(analysis.samples)) {
        return nan;
    }
    const double fundamental = std::abs(analysis.amplitude[1]);
    if (!(fundamental > 0.0)) return nan;
    return std::abs(analysis.amplitude[order]) / fundamental;
}

std::complex<double> fundamental_amplitude(std::span<const double> x, double sample_rate_hz,
                                           double frequency_hz) {
    return analyse_harmonics(x, sample_rate_hz, frequency_hz, 1).amplitude[1];
}

double rms_over_whole_periods(std::span<const double> x, double sample_rate_hz,
                              double frequency_hz) {
    const int p = whole_periods(x.size(), sample_rate_hz, frequency_hz);
    if (p == 0) throw std::invalid_argument("rms_over_whole_periods: no whole period");
    const auto n = static_cast<std::size_t>(
        std::llround(static_cast<double>(p) * sample_rate_hz / frequency_hz));
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += x[i] * x[i];
    return std::sqrt(sum / static_cast<double>(n));
}

}  // namespace sb::identification

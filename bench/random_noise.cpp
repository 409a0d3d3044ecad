// Band-limited noise by inverse FFT of random lines.
#include "bench/random_noise.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <stdexcept>

#include "identification/spectrum.hpp"

namespace sb::bench {
namespace {

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

BandLimitedNoise::BandLimitedNoise(double low_hz, double high_hz, double duration_s,
                                   std::uint64_t seed)
    : sample_rate_hz_(16.0 * high_hz) {
    if (!(low_hz > 0.0) || !(high_hz > low_hz) || !(duration_s > 0.0)) {
        throw std::invalid_argument("band-limited noise needs 0 < low < high and a duration");
    }
    // An even record of at least the duration.
    const int n = 2 * static_cast<int>(std::ceil(0.5 * duration_s * sample_rate_hz_));
    const double df = sample_rate_hz_ / n;
    std::vector<std::complex<double>> lines(static_cast<std::size_t>(n / 2 + 1), 0.0);
    std::mt19937_64 rng(seed ^ 0xD1B54A32D192ED03ull);
    const int first = std::max(1, static_cast<int>(std::ceil(low_hz / df)));
    const int last = std::min(n / 2 - 1, static_cast<int>(std::floor(high_hz / df)));
    for (int j = first; j <= last; ++j) {
        // Box-Muller: a complex Gaussian line, |Z| Rayleigh and arg Z uniform.
        const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform01(rng)));
        const double phase = 2.0 * std::numbers::pi * uniform01(rng);
        lines[static_cast<std::size_t>(j)] = std::polar(radius, phase);
    }
    samples_ = identification::inverse_real_spectrum(lines, n);
    double mean_square = 0.0;
    for (double v : samples_) mean_square += v * v;
    mean_square /= n;
    if (!(mean_square > 0.0))
        throw std::invalid_argument("band-limited noise: no line in the band");
    const double scale = 1.0 / std::sqrt(mean_square);
    for (double& v : samples_) v *= scale;
}

double BandLimitedNoise::operator()(double t_s) const {
    const double u = t_s * sample_rate_hz_;
    const double whole = std::floor(u);
    const auto n = static_cast<long long>(samples_.size());
    const long long i = static_cast<long long>(whole) % n;
    const double frac = u - whole;
    const double a = samples_[static_cast<std::size_t>(i)];
    const double b = samples_[static_cast<std::size_t>((i + 1) % n)];
    return a + frac * (b - a);
}

}  // namespace sb::bench

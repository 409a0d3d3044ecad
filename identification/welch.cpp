// Welch's averaged periodogram (Welch 1967; Bendat & Piersol 2010, §11.5).
#include "identification/welch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "identification/spectrum.hpp"

namespace sb::identification {
namespace {

std::vector<double> demeaned(std::span<const double> x) {
    double mean = 0.0;
    for (double v : x) mean += v;
    mean /= static_cast<double>(x.size());
    std::vector<double> out(x.begin(), x.end());
    for (double& v : out) v -= mean;
    return out;
}

}  // namespace

WelchSpectra::WelchSpectra(int segment_samples, double sample_rate_hz, double low_hz,
                           double high_hz, int channels)
    : segment_samples_(segment_samples), sample_rate_hz_(sample_rate_hz) {
    if (segment_samples < 8 || !(sample_rate_hz > 0.0)) {
        throw std::invalid_argument("Welch spectra need segments of at least 8 samples");
    }
    if (!(low_hz > 0.0) || !(high_hz > low_hz) || !(high_hz < 0.5 * sample_rate_hz)) {
        throw std::invalid_argument("Welch band " + std::to_string(low_hz) + "-" +
                                    std::to_string(high_hz) + " Hz is not inside (0, " +
                                    std::to_string(0.5 * sample_rate_hz) + ") Hz");
    }
    if (channels < 1) throw std::invalid_argument("Welch spectra need a response channel");
    const double df = resolution_hz();
    first_bin_ = std::max(1, static_cast<int>(std::floor(low_hz / df)));
    const int last_bin =
        std::min(segment_samples / 2 - 1, static_cast<int>(std::ceil(high_hz / df)));
    const auto bins = static_cast<std::size_t>(last_bin - first_bin_ + 1);
    // The periodic Hann window (its DFT has three taps): w_m = sin²(π m / N).
    window_.resize(static_cast<std::size_t>(segment_samples));
    for (int m = 0; m < segment_samples; ++m) {
        const double s = std::sin(std::numbers::pi * m / segment_samples);
        window_[static_cast<std::size_t>(m)] = s * s;
        window_power_ += s * s * s * s;
    }
    sums_.reference.assign(bins, 0.0);
    sums_.response.assign(static_cast<std::size_t>(channels), std::vector<double>(bins, 0.0));
    sums_.cross.assign(static_cast<std::size_t>(channels),
                       std::vector<std::complex<double>>(bins, 0.0));
}

void WelchSpectra::add_segment(std::span<const double> reference,
                               const std::vector<std::span<const double>>& responses) {
    const auto n = static_cast<std::size_t>(segment_samples_);
    if (reference.size() != n || responses.size() != sums_.response.size()) {
        throw std::invalid_argument("Welch segment of the wrong size");
    }
    const auto windowed_spectrum = [&](std::span<const double> x) {
        if (x.size() != n) throw std::invalid_argument("Welch segment of the wrong size");
        std::vector<double> v = demeaned(x);
        for (std::size_t m = 0; m < n; ++m) v[m] *= window_[m];
        return real_spectrum(v);
    };
    const auto X = windowed_spectrum(reference);
    const auto first = static_cast<std::size_t>(first_bin_);
    for (std::size_t k = 0; k < sums_.reference.size(); ++k)
        sums_.reference[k] += std::norm(X[first + k]);
    for (std::size_t c = 0; c < responses.size(); ++c) {
        const auto Y = windowed_spectrum(responses[c]);
        for (std::size_t k = 0; k < sums_.reference.size(); ++k) {
            sums_.response[c][k] += std::norm(Y[first + k]);
            sums_.cross[c][k] += Y[first + k] * std::conj(X[first + k]);
        }
    }
    ++sums_.segments;
}

std::complex<double> WelchSpectra::h1(int channel, int bin) const {
    const auto k = static_cast<std::size_t>(bin);
    return sums_.cross[static_cast<std::size_t>(channel)][k] / sums_.reference[k];
}

double WelchSpectra::coherence(int channel, int bin) const {
    const auto c = static_cast<std::size_t>(channel);
    const auto k = static_cast<std::size_t>(bin);
    return std::norm(sums_.cross[c][k]) / (sums_.reference[k] * sums_.response[c][k]);
}

double WelchSpectra::psd_scale() const {
    // One-sided density of a windowed segment: 2 |X|² / (fs Σw²), averaged over segments.
    return 2.0 / (sample_rate_hz_ * window_power_ * std::max(1, sums_.segments));
}

double WelchSpectra::reference_psd(int bin) const {
    return sums_.reference[static_cast<std::size_t>(bin)] * psd_scale();
}

double WelchSpectra::response_psd(int channel, int bin) const {
    return sums_.response[static_cast<std::size_t>(channel)][static_cast<std::size_t>(bin)] *
           psd_scale();
}

void WelchSpectra::clear() {
    sums_.segments = 0;
    std::fill(sums_.reference.begin(), sums_.reference.end(), 0.0);
    for (auto& v : sums_.response) std::fill(v.begin(), v.end(), 0.0);
    for (auto& v : sums_.cross) std::fill(v.begin(), v.end(), std::complex<double>(0.0));
}

void WelchSpectra::restore(WelchSums sums) {
    const auto fits = [&](const auto& per_channel) {
        if (per_channel.size() != sums_.response.size()) return false;
        for (const auto& v : per_channel)
            if (v.size() != sums_.reference.size()) return false;
        return true;
    };
    if (sums.segments < 0 || sums.reference.size() != sums_.reference.size() ||
        !fits(sums.response) || !fits(sums.cross)) {
        throw std::invalid_argument("Welch sums of another band or channel count");
    }
    sums_ = std::move(sums);
}

}  // namespace sb::identification

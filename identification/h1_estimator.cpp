// H1 estimator over whole-period segments (Bendat & Piersol, Random Data, §9.2).
#include "identification/h1_estimator.hpp"

#include <cmath>
#include <stdexcept>

#include "identification/spectrum.hpp"

namespace sb::identification {

H1Estimate h1_estimate(std::span<const double> reference, std::span<const double> response,
                       double sample_rate_hz, double frequency_hz, int periods_per_segment) {
    if (reference.size() != response.size()) {
        throw std::invalid_argument("h1_estimate: channels differ in length");
    }
    if (periods_per_segment < 1 || !(frequency_hz > 0.0) || !(sample_rate_hz > 0.0)) {
        throw std::invalid_argument("h1_estimate: bad segment, frequency or sample rate");
    }
    const double per_segment = periods_per_segment * sample_rate_hz / frequency_hz;
    const double rounded = std::round(per_segment);
    if (std::abs(per_segment - rounded) > 1e-6) {
        throw std::invalid_argument("h1_estimate: a segment is not an integer number of samples");
    }
    const auto n = static_cast<std::size_t>(rounded);
    const std::size_t segments = reference.size() / n;
    if (segments == 0) throw std::invalid_argument("h1_estimate: shorter than one segment");
    const auto bin = static_cast<std::size_t>(periods_per_segment);
    if (2 * bin >= n) throw std::invalid_argument("h1_estimate: frequency at or above Nyquist");
    std::complex<double> gxy = 0.0;
    double gxx = 0.0;
    double gyy = 0.0;
    for (std::size_t s = 0; s < segments; ++s) {
        const auto x = real_spectrum(reference.subspan(s * n, n))[bin];
        const auto y = real_spectrum(response.subspan(s * n, n))[bin];
        gxy += y * std::conj(x);
        gxx += std::norm(x);
        gyy += std::norm(y);
    }
    H1Estimate e;
    e.h1 = gxy / gxx;
    e.coherence = std::norm(gxy) / (gxx * gyy);
    e.segments = static_cast<int>(segments);
    return e;
}

}  // namespace sb::identification

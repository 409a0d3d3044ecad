// H1 transfer-function estimate at the excitation frequency, averaged over whole-period segments.
#pragma once

#include <complex>
#include <span>

namespace sb::identification {

/// H1 estimate of response/reference at the excitation frequency.
struct H1Estimate {
    std::complex<double> h1;  ///< Σ Y conj(X) / Σ |X|² [response unit / reference unit]
    double coherence = 0.0;   ///< |Σ Y conj(X)|² / (Σ|X|² Σ|Y|²) [-], 1 for noise-free data
    int segments = 0;         ///< segments averaged [-]
};

/// Splits both channels into consecutive segments of `periods_per_segment` whole periods (each
/// an integer number of samples), takes the fundamental bin of each segment's FFT (bin =
/// periods_per_segment) and averages the cross- and auto-spectra (Bendat & Piersol, H1 =
/// G_xy/G_xx). Noise on the response averages out; noise on the reference biases |H1| low by
/// 1/(1 + noise-to-signal power). Throws std::invalid_argument if the segment is not a whole
/// number of samples, the channels differ in length, or fewer than 1 segment fits.
H1Estimate h1_estimate(std::span<const double> reference, std::span<const double> response,
                       double sample_rate_hz, double frequency_hz, int periods_per_segment = 1);

}  // namespace sb::identification

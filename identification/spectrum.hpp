// One-sided spectrum of a real sequence (thin FFTW wrapper shared by harmonics and H1).
#pragma once

#include <complex>
#include <span>
#include <vector>

namespace sb::identification {

/// Y_j = Σ_m x_m e^{−2πi jm/N}, j = 0..N/2 (FFTW r2c, unnormalised). Thread-safe.
std::vector<std::complex<double>> real_spectrum(std::span<const double> x);

/// The real sequence of length n whose real_spectrum() is `spectrum` (n/2 + 1 values; the
/// imaginary parts of the zero and, for even n, Nyquist bins are ignored): x_m = (1/n) Σ_j Y_j
/// e^{2πi jm/n} over the full Hermitian spectrum (FFTW c2r, normalised). Thread-safe. Throws
/// std::invalid_argument unless spectrum.size() == n/2 + 1.
std::vector<double> inverse_real_spectrum(std::span<const std::complex<double>> spectrum, int n);

}  // namespace sb::identification

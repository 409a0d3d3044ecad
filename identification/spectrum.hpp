// One-sided spectrum of a real sequence (thin FFTW wrapper shared by harmonics and H1).
#pragma once

#include <complex>
#include <span>
#include <vector>

namespace sb::identification {

/// Y_j = Σ_m x_m e^{−2πi jm/N}, j = 0..N/2 (FFTW r2c, unnormalised). Thread-safe.
std::vector<std::complex<double>> real_spectrum(std::span<const double> x);

}  // namespace sb::identification

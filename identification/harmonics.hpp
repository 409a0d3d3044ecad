// Harmonic amplitudes of a periodic time history over whole periods (FFTW real-to-complex).
#pragma once

#include <complex>
#include <span>
#include <vector>

namespace sb::identification {

/// Harmonics of one channel. amplitude[k] is the complex amplitude of harmonic k (k = 0 is
/// the mean) with x(t) = Re{X_k e^{ikωt}} (peak amplitude), time origin at the first sample.
struct HarmonicAnalysis {
    std::vector<std::complex<double>> amplitude;  ///< [channel unit], index = harmonic order
    double thd = 0.0;  ///< total harmonic distortion √(Σ_{k=2}^{K}|X_k|²)/|X_1| [-]
    int periods = 0;   ///< whole periods analysed [-]
    int samples = 0;   ///< samples analysed [-]
};

/// Number of whole periods P (largest first) such that P periods hold an integer number of
/// samples (to 1e-6 sample), and at most `samples` of them; 0 if none.
int whole_periods(std::size_t samples, double sample_rate_hz, double frequency_hz);

/// Harmonics 0..max_harmonic of x at the fundamental frequency [Hz], sampled at
/// sample_rate_hz [Hz], using the first N samples that hold the most whole periods P.
/// A real-to-complex FFT (FFTW: tested, and exact on whole periods with no window) of N
/// samples puts harmonic k of the excitation exactly on bin kP; X_k = 2 Y[kP]/N (Y_0/N for
/// the mean). Harmonics above Nyquist are left zero. Throws std::invalid_argument if no whole
/// number of periods fits an integer number of samples.
HarmonicAnalysis analyse_harmonics(std::span<const double> x, double sample_rate_hz,
                                   double frequency_hz, int max_harmonic = 10);

/// |X_k|/|X_1| of an analysis [-]: the distortion of order k, the Fourier coefficient k of a
/// periodic record (Bendat & Piersol, Random Data) over the fundamental. NaN when harmonic k
/// was not analysed (above max_harmonic, or at or above Nyquist, where analyse_harmonics
/// leaves it zero) or the fundamental is zero. Throws std::invalid_argument for k < 1.
double harmonic_ratio(const HarmonicAnalysis& analysis, int k);

/// The fundamental complex amplitude only (harmonic 1 of analyse_harmonics).
std::complex<double> fundamental_amplitude(std::span<const double> x, double sample_rate_hz,
                                           double frequency_hz);

/// RMS of x over the same whole periods [channel unit].
double rms_over_whole_periods(std::span<const double> x, double sample_rate_hz,
                              double frequency_hz);

}  // namespace sb::identification

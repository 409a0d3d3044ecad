// Welch-averaged auto- and cross-spectra of a reference and its responses, and the H1
// transfer function they give: what a random test's analyser computes.
#pragma once

#include <complex>
#include <span>
#include <vector>

namespace sb::identification {

/// The running sums of a Welch estimate over the bins of a band (Bendat & Piersol, Random
/// Data, 4th ed. 2010, §11.5): each segment is Hann-windowed and transformed, and its
/// |X|², |Y_c|² and Y_c conj(X) are added per bin. The sums are kept as they are so that an
/// interrupted estimate continues exactly (a checkpoint holds them).
struct WelchSums {
    int segments = 0;                                      ///< segments added [-]
    std::vector<double> reference;                         ///< Σ|X|² per bin
    std::vector<std::vector<double>> response;             ///< per channel: Σ|Y|² per bin
    std::vector<std::vector<std::complex<double>>> cross;  ///< per channel: Σ Y conj(X) per bin
};

/// Welch spectra of segments of `segment_samples` samples at `sample_rate_hz`, kept on the
/// bins from `low_hz` to `high_hz` (inclusive, rounded outward to whole bins of
/// sample_rate / segment_samples). H1 = G_xy/G_xx is unbiased by noise on the responses
/// (such as a bouncing sphere's impacts uncorrelated with the drive); the coherence says how
/// much of each response the reference explains linearly.
class WelchSpectra {
  public:
    /// Throws std::invalid_argument for fewer than 8 samples, a band outside (0, Nyquist) or
    /// no response channel.
    WelchSpectra(int segment_samples, double sample_rate_hz, double low_hz, double high_hz,
                 int channels);

    /// Adds one segment: `reference` and each of `responses` hold segment_samples samples.
    /// The mean of each is removed before the window.
    void add_segment(std::span<const double> reference,
                     const std::vector<std::span<const double>>& responses);

    [[nodiscard]] int segment_samples() const { return segment_samples_; }
    [[nodiscard]] int segments() const { return sums_.segments; }
    [[nodiscard]] int channels() const { return static_cast<int>(sums_.response.size()); }
    [[nodiscard]] int bins() const { return static_cast<int>(sums_.reference.size()); }
    [[nodiscard]] double resolution_hz() const { return sample_rate_hz_ / segment_samples_; }
    [[nodiscard]] double frequency_hz(int bin) const {
        return (first_bin_ + bin) * resolution_hz();
    }

    /// H1 of channel c at a bin [response unit / reference unit].
    [[nodiscard]] std::complex<double> h1(int channel, int bin) const;
    /// Ordinary coherence |G_xy|² / (G_xx G_yy) [-], 1 for a noise-free linear system.
    [[nodiscard]] double coherence(int channel, int bin) const;
    /// One-sided power spectral densities [unit²/Hz] (Hann window, its power Σw² divided
    /// out): their sum over the band times resolution_hz() is the band's mean square.
    [[nodiscard]] double reference_psd(int bin) const;
    [[nodiscard]] double response_psd(int channel, int bin) const;

    [[nodiscard]] const WelchSums& sums() const { return sums_; }
    /// Forgets every segment added.
    void clear();
    /// Continues from sums of an estimate with the same segment, band and channels; throws
    /// std::invalid_argument when they do not fit.
    void restore(WelchSums sums);

  private:
    [[nodiscard]] double psd_scale() const;

    int segment_samples_;
    double sample_rate_hz_;
    int first_bin_;
    std::vector<double> window_;
    double window_power_ = 0.0;  ///< Σ w²
    WelchSums sums_;
};

}  // namespace sb::identification

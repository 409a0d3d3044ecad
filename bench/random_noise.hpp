// Band-limited Gaussian noise: the drive of a random test.
#pragma once

#include <cstdint>
#include <vector>

namespace sb::bench {

/// Gaussian noise of unit RMS whose spectrum is flat between low_hz and high_hz and zero
/// outside, as a random test's source makes it (Bendat & Piersol 2010, §5.2: band-limited
/// white noise). Synthesised once in the frequency domain: every line of the band gets a
/// complex Gaussian amplitude (a Rayleigh magnitude, a uniform phase), the inverse FFT gives
/// a record `duration_s` long, which repeats after it (a run no longer than the record sees
/// no repetition). Read between its samples (16 per period of the band's top) by linear
/// interpolation: a droop of 1.3 % at the top, and the reference channel records the force
/// the structure gets, so H1 is not affected.
class BandLimitedNoise {
  public:
    /// The same seed gives the same record on every machine: the generator is
    /// std::mt19937_64 (fixed by the standard) with Box-Muller written out, where
    /// std::normal_distribution's algorithm is the library's own.
    BandLimitedNoise(double low_hz, double high_hz, double duration_s, std::uint64_t seed);

    /// The noise at time t [s] (t >= 0), unit RMS.
    [[nodiscard]] double operator()(double t_s) const;
    [[nodiscard]] double sample_rate_hz() const { return sample_rate_hz_; }
    [[nodiscard]] const std::vector<double>& samples() const { return samples_; }

  private:
    double sample_rate_hz_;
    std::vector<double> samples_;
};

}  // namespace sb::bench

// The abstract plant the amplitude controller drives, one excitation period per call.
#pragma once

#include <complex>
#include <vector>

namespace sb::control {

/// What the plant measured on the control channel over one whole excitation period.
struct PeriodResult {
    /// RMS of the control channel over the period with its mean removed [channel unit].
    double rms = 0.0;
    /// Complex harmonics of the control channel over the period as the plant reports them
    /// (index 0 = fundamental); the controller only stores them [channel unit].
    std::vector<std::complex<double>> harmonics{};
};

/// A structure on a shaker that the controller can drive. The plant keeps its own dynamic
/// state between calls: the structure goes on vibrating across amplitude and frequency
/// changes, as on a real shaker. One virtual call per period.
class Plant {
  public:
    virtual ~Plant() = default;
    /// Advances the plant by exactly one period of a sine of `amplitude` [input unit] at
    /// `frequency_hz` [Hz] and reports the control channel over that period.
    virtual PeriodResult run_period(double amplitude, double frequency_hz) = 0;
};

}  // namespace sb::control

// Exact SDOF and 2-DOF FRFs for the estimator tests (closed forms, no identification code).
#pragma once

#include <complex>
#include <vector>

#include "core/units.hpp"
#include "identification/frf.hpp"

namespace sb::identification::testing {

/// One mode of a receptance: A/(ωn² − ω² + 2iζωnω).
struct Mode {
    double frequency_hz;
    double damping_ratio;
    double modal_constant;  ///< A [1/kg]
};

/// Sum of modes in receptance, returned as accelerance −ω² α(ω) (what the rig measures).
inline Frf modal_accelerance(const std::vector<double>& frequency_hz,
                             const std::vector<Mode>& modes) {
    Frf frf{frequency_hz, {}, FrfForm::accelerance};
    for (double f : frequency_hz) {
        const double w = hz_to_rad_s(f);
        std::complex<double> alpha = 0.0;
        for (const auto& m : modes) {
            const double wn = hz_to_rad_s(m.frequency_hz);
            alpha += m.modal_constant /
                     std::complex<double>(wn * wn - w * w, 2.0 * m.damping_ratio * wn * w);
        }
        frf.value.push_back(-w * w * alpha);
    }
    return frf;
}

/// n points evenly spaced over f_n (1 ± span ζ) [Hz] (span in half-bandwidths), offset by
/// `shift` of a step so that the peak does not fall on a grid point.
inline std::vector<double> grid_around(double fn, double zeta, int n, double span, double shift) {
    const double lo = fn * (1.0 - span * zeta);
    const double hi = fn * (1.0 + span * zeta);
    const double step = (hi - lo) / (n - 1);
    std::vector<double> f;
    for (int i = 0; i < n; ++i) f.push_back(lo + (i + shift) * step);
    return f;
}

}  // namespace sb::identification::testing

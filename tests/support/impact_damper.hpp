// The closed-form describing function of a plastic impact damper: a particle in a gap, no
// gravity, shaken sinusoidally along the gap (the Masri-type impact damper with e = 0). The
// characterisation tests check the DEM against it; the diagnosis tests use it as a particle
// damper whose damping falls with the level, in a describing-function table.
#pragma once

#include <cmath>
#include <complex>

#include "core/units.hpp"

namespace sb::test {

/// The impact phase psi of a plastic particle in a gap D shaken as a = A sin(w t),
/// X = A / w^2: it leaves one wall when the acceleration changes sign, flies at the wall's
/// largest speed A / w, and meets the other wall when its relative travel
/// X (psi - sin psi) equals D.
inline double impact_phase(double gap_over_amplitude) {
    double lo = 0.0;
    double hi = kPi;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (mid - std::sin(mid) < gap_over_amplitude ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// Apparent mass of a plastic (e = 0) particle of mass m in a gap, no gravity, while
/// D / X < pi (the flight ends within the half period). Per half period: flight from 0 to
/// psi (no force), an impact whose impulse on the wall is -m A/w (1 - cos psi), then the
/// particle rides the wall, F = -m A sin(phi), until pi; the other half is the mirror image.
/// Q1 = (2/pi) [ -m A int_psi^pi sin(phi) e^{-i phi} dphi - m A (1 - cos psi) e^{-i psi} ],
/// M = -Q1 / a1 with a1 = -i A. psi -> 0 gives M = m; -Im M = m (1 - cos psi)^2 / pi, which
/// is the two impacts' energy loss m (A/w)^2 (1 - cos psi)^2 per period as a power.
inline std::complex<double> plastic_particle_apparent_mass(double m, double gap_over_amplitude) {
    const double psi = impact_phase(gap_over_amplitude);
    const std::complex<double> i(0.0, 1.0);
    const std::complex<double> integral =
        1.0 / (2.0 * i) * ((kPi - psi) + (1.0 - std::exp(-2.0 * i * psi)) / (2.0 * i));
    return m * (2.0 * i / kPi) * (integral + (1.0 - std::cos(psi)) * std::exp(-i * psi));
}

}  // namespace sb::test

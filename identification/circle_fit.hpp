// Circle fit of the mobility near resonance (Kennedy–Pancu; Ewins' damping from angle pairs).
#pragma once

#include <complex>
#include <vector>

#include "identification/frf.hpp"
#include "identification/modal_estimate.hpp"
#include "identification/residual.hpp"

namespace sb::identification {

/// A circle in the complex plane.
struct Circle {
    std::complex<double> centre;  ///< centre [FRF units]
    double radius = 0.0;          ///< radius [FRF units]
};

/// Least-squares circle through points: Kåsa's algebraic fit (x a1 + y a2 + a3 = −(x² + y²))
/// as a start, then Levenberg–Marquardt (Eigen's unsupported module) on the geometric
/// distances Σ(|z − c| − R)². Throws std::invalid_argument for fewer than 3 points.
Circle fit_circle(const std::vector<std::complex<double>>& points);

/// Options of circle_fit.
struct CircleFitOptions {
    /// Points used: the contiguous run around the peak with |T| >= this × |T|max [-]
    /// (note §3.2: about half the maximum spans more than 180° of arc).
    double min_relative_magnitude = 0.5;
    /// Fewest points accepted (3 define the circle, one more checks it) [-]. When the run
    /// above min_relative_magnitude is shorter, it is widened to this many points nearest the
    /// peak: a grid with 3 points in the half-power band still gets a circle.
    int min_points = 4;
    /// Residual of other modes, fitted and subtracted before the circle (residual.hpp).
    ResidualOptions residual;
};

/// Circle-fit damping. The FRF is converted to mobility, where a viscous SDOF is an exact
/// circle. The resonance is first placed where the angle about the centre sweeps fastest
/// (dθ/dω², interpolated) and then refined by fitting θ(ω) = θr + 2 atan((ω² − ωn²)/(2ζωnω))
/// to the angles; damping is the mean over all pairs either side of
/// ζ = (ωa² − ωb²)/(2ωr(ωa tan(θa/2) + ωb tan(θb/2))) (note §3.2, step 4), with the standard
/// deviation over pairs in damping_spread.
ModalEstimate circle_fit(const Frf& frf, const CircleFitOptions& options = {});

}  // namespace sb::identification

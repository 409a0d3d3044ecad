// Single-mode rational-fraction least squares (Richardson & Formenti) with SK reweighting.
#pragma once

#include "identification/frf.hpp"
#include "identification/modal_estimate.hpp"
#include "identification/residual.hpp"

namespace sb::identification {

/// Options of rational_fraction_fit.
struct RationalFractionOptions {
    /// Points used: the contiguous run around the peak with |T| >= this × |T|max [-]. Lower
    /// than the circle fit's because the fit needs no arc, only enough shape.
    double min_relative_magnitude = 0.25;
    /// Fewest points accepted: 5 real unknowns need 3 complex points; 5 leave redundancy [-].
    int min_points = 5;
    /// Sanathanan–Koerner iterations reweighting Levy's linearisation by 1/|den| [-].
    int iterations = 8;
    /// Residual of other modes, fitted and subtracted before the fit (residual.hpp); the
    /// numerator alone absorbs only a residual that is constant in the FRF's form.
    ResidualOptions residual;
};

/// Fits T(s) = (a0 + a1 s + a2 s²)/(s² + b1 s + b0), s = iω/ω_ref, to the points near the peak
/// (note §3.4); ωn = ω_ref √b0 and ζ = b1/(2√b0). A second-order numerator covers receptance,
/// mobility and accelerance of one mode plus a slowly varying residual of the others, so the
/// FRF is used in the form given.
ModalEstimate rational_fraction_fit(const Frf& frf, const RationalFractionOptions& options = {});

}  // namespace sb::identification

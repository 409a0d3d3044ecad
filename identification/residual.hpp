// The residual of the modes outside the band, fitted and subtracted before a single-mode
// estimate (the "residual terms" of Ewins, Modal Testing, 2000).
#pragma once

#include <complex>
#include <functional>
#include <string>

#include "identification/frf.hpp"
#include "identification/modal_estimate.hpp"

namespace sb::identification {

/// How the single-mode estimators treat the other modes.
struct ResidualOptions {
    /// Fit and subtract the residual of the other modes before estimating.
    bool compensate = true;
    /// Points of the residual fit: the contiguous run around the peak with |mobility| >= this
    /// × the largest [-]. Low, so that the flanks (where the residual shows) take part.
    double min_relative_magnitude = 0.1;
    /// Refuse with status residual_dominates when the fitted residual at f_n exceeds this many
    /// times the mode's own response there [-]: the response at the "resonance" is then mostly
    /// other modes and no single-mode estimate is trustworthy.
    double max_residual_ratio = 1.0;
};

/// One mode plus the residual of the others, in receptance:
/// α(ω) = A/(ωn² − ω² + 2iζωnω) + K + M (ωn/ω)².
/// K is the residual flexibility of the modes above (their stiffness lines), M (ωn/ω)² the
/// mass line of the modes below; both complex, so a neighbour's damping phase is absorbed.
struct ResidualFit {
    bool ok = false;
    std::string message;                  ///< why not, when !ok
    double natural_frequency_hz = 0.0;    ///< of the fitted mode [Hz]
    double damping_ratio = 0.0;           ///< of the fitted mode [-]
    std::complex<double> modal_constant;  ///< A [receptance × rad²/s²]
    std::complex<double> stiffness_term;  ///< K [receptance units]
    std::complex<double> mass_term;       ///< M [receptance units]
    double residual_ratio = 0.0;  ///< |K + M| / |A/(2iζωn²)|: residual over response at f_n [-]
    int points_used = 0;
};

/// Fits the model of ResidualFit to the points around the peak of `frf` (any form; the fit is
/// done on the mobility, unweighted). A, K and M enter linearly and are solved by least
/// squares for every (ωn, ζ) (variable projection, Golub & Pereyra 1973); ωn and ζ are found
/// by Levenberg–Marquardt (Eigen's unsupported module) from the given start. Needs 5 points.
ResidualFit fit_residual(const Frf& frf, double start_frequency_hz, double start_damping_ratio,
                         double min_relative_magnitude);

/// The FRF with the fitted residual K + M (ωn/ω)² (converted to the FRF's form) removed.
Frf subtract_residual(const Frf& frf, const ResidualFit& fit);

/// Runs `estimate` on the FRF with the residual of the other modes removed. The residual is
/// fitted around a start mode: `estimate` on the raw FRF if it succeeds, otherwise `start`
/// (the estimators pass the plain rational-fraction fit). Without a start the raw estimate is
/// returned. With options.compensate false, `estimate(frf)` is returned as it is.
ModalEstimate estimate_with_residual(const Frf& frf, const ResidualOptions& options,
                                     const std::function<ModalEstimate(const Frf&)>& estimate,
                                     const std::function<ModalEstimate(const Frf&)>& start);

}  // namespace sb::identification

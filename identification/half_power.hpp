// Half-power (-3 dB) bandwidth damping with interpolated peak and crossings.
#pragma once

#include "identification/frf.hpp"
#include "identification/modal_estimate.hpp"
#include "identification/residual.hpp"

namespace sb::identification {

/// Which FRF form the half-power points are taken on (research note §3.1).
enum class HalfPowerForm {
    mobility,    ///< ζ = (ω2 − ω1)/(2ωn), ωn = √(ω1ω2): exact for viscous SDOF (default)
    receptance,  ///< ζ = sin(½ atan R), R = (ω2² − ω1²)/(ω2² + ω1²): exact
    accelerance,  ///< same R relation with ω → 1/ω: exact
};

/// Half-power damping of the mode at the largest |FRF|, any input form (it is converted).
///
/// Other modes: unless residual.compensate is false, the residual of the other modes (a
/// residual flexibility and a mass line, residual.hpp) is fitted around the peak and
/// subtracted first, so the half-power points are those of this mode alone; a mode whose
/// response at f_n is smaller than the residual is refused (residual_dominates).
///
/// Peak and crossings are interpolated with the exact SDOF shape of the chosen form: on the
/// points from the last one below |T|max/√2 under the peak to the first one below it above,
/// ω^{2j}/|T|² is fitted in least squares by a quadratic in ω² (j = 0 receptance, 1 mobility,
/// 2 accelerance), which is exact for a viscous SDOF; the peak is the minimum of 1/|T|² and
/// the crossings are the roots of 1/|T|² = 2/|T|²peak. Statuses: peak_at_grid_edge,
/// no_lower_crossing, no_upper_crossing, too_few_points_in_band (fewer than
/// kHalfPowerMinPointsInBand grid points between the crossings), fit_failed.
ModalEstimate half_power(const Frf& frf, HalfPowerForm form = HalfPowerForm::mobility,
                         const ResidualOptions& residual = {});

/// Fewest grid points strictly inside the interpolated half-power band: with 3 the step is
/// below the half-bandwidth ζ f_n, so the interpolating quadratic rests on points inside the
/// band and on both flanks.
inline constexpr int kHalfPowerMinPointsInBand = 3;

}  // namespace sb::identification

// Tolerances, grids and the resolution criterion shared by the estimator tests.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "identification/half_power.hpp"
#include "identification/modal_estimate.hpp"

namespace sb::identification::testing {

/// The acceptance bound: damping within 2 % (relative) wherever the grid resolves the mode.
constexpr double kDampingTolerance = 0.02;
/// Natural frequency on 2-DOF data, in half-bandwidths ζ f_n: the residual model (flexibility
/// and mass line) leaves frequency errors of up to 3.2 % of ζ f_n at modes a factor 5 apart
/// with ζ = 20 %; 5 % of the half-bandwidth is a tenth of the spacing of a 10-point-per-band
/// grid and well inside what the damping bound implies.
constexpr double kFrequencyToleranceInBandwidths = 0.05;
/// On exact SDOF data every estimator is exact up to round-off and the iterative fits'
/// stopping rules: 1e-6 relative, for ζ and for f_n in half-bandwidths.
constexpr double kExactTolerance = 1e-6;
/// Modes closer than a factor 5 (or a factor 5 with a ten times stronger upper mode): the
/// residual model leaves up to 4.8 % on ζ at ζ = 20 % (measured over this test's grids).
constexpr double kCloseModesDampingTolerance = 0.05;
/// ... and up to 6 % of ζ f_n on the frequency.
constexpr double kCloseModesFrequencyToleranceInBandwidths = 0.1;

inline const std::vector<double> kDampingRatios = {0.001, 0.003, 0.01, 0.03, 0.1, 0.2};
inline const std::vector<int> kGridSizes = {5, 7, 9, 11, 15, 21, 31, 50};
/// Offsets of the grid (in steps) so that the peak falls on, between and near grid points.
inline const std::vector<double> kGridShifts = {0.0, 0.37, 0.5, 0.81};

/// The resolution criterion every estimator is held to: at least 3 grid points strictly
/// inside the half-power band and a grid point outside it on each side (the band is
/// bracketed, so the peak is not at the grid edge). The band is that of the form the
/// half-power points are taken on (note §3.1): mobility f_n(√(1+ζ²) ∓ ζ); receptance
/// (f/f_n)² = 1 − 2ζ² ∓ 2ζ√(1−ζ²); accelerance the same with f → 1/f.
inline bool grid_resolves(const std::vector<double>& f, double fn, double zeta,
                          HalfPowerForm form = HalfPowerForm::mobility) {
    double f1 = fn * (std::sqrt(1.0 + zeta * zeta) - zeta);
    double f2 = fn * (std::sqrt(1.0 + zeta * zeta) + zeta);
    const double lo = 1.0 - 2.0 * zeta * zeta - 2.0 * zeta * std::sqrt(1.0 - zeta * zeta);
    const double hi = 1.0 - 2.0 * zeta * zeta + 2.0 * zeta * std::sqrt(1.0 - zeta * zeta);
    if (form == HalfPowerForm::receptance) {
        f1 = fn * std::sqrt(lo);
        f2 = fn * std::sqrt(hi);
    } else if (form == HalfPowerForm::accelerance) {
        f1 = fn / std::sqrt(hi);
        f2 = fn / std::sqrt(lo);
    }
    int inside = 0;
    bool below = false, above = false;
    for (double x : f) {
        if (x > f1 && x < f2) ++inside;
        below = below || x < f1;
        above = above || x > f2;
    }
    return inside >= 3 && below && above;
}

struct Tolerance {
    double damping;               ///< relative
    double frequency_bandwidths;  ///< |f − f_n| / (ζ f_n)
};

struct Outcome {
    int resolved = 0;
    int unresolved = 0;
};

/// An estimate must be ok when `must_resolve`; when ok it must be within tolerance; when not
/// ok it must say why.
inline void check(const ModalEstimate& e, double fn, double zeta, Tolerance tol, bool must_resolve,
                  Outcome& out, const std::string& what) {
    if (must_resolve) {
        EXPECT_TRUE(e.ok()) << what << " refused although resolved: " << e.message;
    }
    if (!e.ok()) {
        ++out.unresolved;
        EXPECT_FALSE(e.message.empty()) << what;
        return;
    }
    ++out.resolved;
    EXPECT_NEAR(e.damping_ratio / zeta, 1.0, tol.damping) << what << " spread " << e.damping_spread;
    EXPECT_NEAR((e.natural_frequency_hz - fn) / (zeta * fn), 0.0, tol.frequency_bandwidths) << what;
}

inline std::string label(const char* method, double zeta, int n, double shift) {
    return std::string(method) + " zeta=" + std::to_string(zeta) + " n=" + std::to_string(n) +
           " shift=" + std::to_string(shift);
}

}  // namespace sb::identification::testing

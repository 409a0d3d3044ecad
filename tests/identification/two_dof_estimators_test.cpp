// Both modes of 2-DOF systems: the residual of the other mode fitted and subtracted, every
// method, all damping ratios and grids of the SDOF test (validation: ~8000 estimates).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <string>

#include "core/units.hpp"
#include "estimator_checks.hpp"
#include "identification/circle_fit.hpp"
#include "identification/half_power.hpp"
#include "identification/rational_fraction.hpp"
#include "identification/residual.hpp"
#include "sdof_frf.hpp"

namespace sb::identification {
namespace {

using namespace testing;

/// Two modes f_lower < f_upper with modal constants (receptance numerators) a_lower, a_upper.
struct TwoDof {
    double f_lower_hz;
    double f_upper_hz;
    double a_lower;
    double a_upper;
};

/// Residual of the other mode at f_n over this mode's response there (exact) [-].
double residual_ratio(const TwoDof& s, bool upper, double zeta) {
    const double wn = hz_to_rad_s(upper ? s.f_upper_hz : s.f_lower_hz);
    const double wo = hz_to_rad_s(upper ? s.f_lower_hz : s.f_upper_hz);
    const double ao = upper ? s.a_lower : s.a_upper;
    const double an = upper ? s.a_upper : s.a_lower;
    const double other =
        std::abs(ao / std::complex<double>(wo * wo - wn * wn, 2.0 * zeta * wo * wn));
    return other / (std::abs(an) / (2.0 * zeta * wn * wn));
}

/// Runs every method on both modes of `s` over all damping ratios, grid sizes and shifts. The
/// grid spans ±4 half-bandwidths, but never more than half-way to the other mode (a grid
/// "around the peak"). Returns the outcomes per method.
std::array<Outcome, 3> check_two_dof(const TwoDof& s, Tolerance tol) {
    const ResidualOptions defaults;
    std::array<Outcome, 3> out;
    for (bool upper : {false, true}) {
        const double fn = upper ? s.f_upper_hz : s.f_lower_hz;
        const double other = upper ? s.f_lower_hz : s.f_upper_hz;
        for (double zeta : kDampingRatios) {
            const double span = std::min(4.0, 0.5 * std::abs(other - fn) / (zeta * fn));
            const double ratio = residual_ratio(s, upper, zeta);
            for (int n : kGridSizes) {
                for (double shift : kGridShifts) {
                    const auto f = grid_around(fn, zeta, n, span, shift);
                    const auto frf = modal_accelerance(
                        f, {{s.f_lower_hz, zeta, s.a_lower}, {s.f_upper_hz, zeta, s.a_upper}});
                    const bool resolved = grid_resolves(f, fn, zeta);
                    const std::string what =
                        "modes " + std::to_string(s.f_lower_hz) + "/" +
                        std::to_string(s.f_upper_hz) + " constants " + std::to_string(s.a_lower) +
                        "/" + std::to_string(s.a_upper) + (upper ? " upper " : " lower ") +
                        "residual ratio " + std::to_string(ratio);
                    const ModalEstimate e[3] = {half_power(frf), circle_fit(frf),
                                                rational_fraction_fit(frf)};
                    const char* names[3] = {"hp", "circle", "rfp"};
                    for (std::size_t k = 0; k < 3; ++k) {
                        const std::string where = label(names[k], zeta, n, shift) + " " + what;
                        // Well below the limit the mode must resolve; well above it must be
                        // refused as dominated by the other mode (the fitted ratio is within
                        // 10 % of the exact one here, hence the margins).
                        if (ratio > 1.5 * defaults.max_residual_ratio && resolved) {
                            EXPECT_EQ(e[k].status, EstimateStatus::residual_dominates) << where;
                        }
                        check(e[k], fn, zeta, tol,
                              resolved && ratio < 0.8 * defaults.max_residual_ratio, out[k], where);
                    }
                }
            }
        }
    }
    return out;
}

TEST(Estimators, RecoverBothModesOfWellSeparatedTwoDofSystemsWithinTwoPercent) {
    // Modes a factor 10 and 5 apart, equal, opposite and 10:1 modal constants. The residual
    // of the other mode (up to 4 times the resonant response) is fitted and subtracted; where
    // it exceeds the response the estimators say so (residual-dominates).
    const Tolerance tol{kDampingTolerance, kFrequencyToleranceInBandwidths};
    for (const TwoDof& s : {TwoDof{10.0, 100.0, 1.0, 1.0}, TwoDof{10.0, 100.0, 1.0, 10.0},
                            TwoDof{10.0, 100.0, 10.0, 1.0}, TwoDof{10.0, 100.0, 1.0, -1.0},
                            TwoDof{10.0, 50.0, 1.0, 1.0}, TwoDof{10.0, 50.0, 1.0, -1.0},
                            TwoDof{10.0, 50.0, 10.0, 1.0}}) {
        for (const Outcome& o : check_two_dof(s, tol)) {
            EXPECT_GT(o.resolved, 0);
            EXPECT_GT(o.unresolved, 0);
        }
    }
}

TEST(Estimators, StayWithinFivePercentForModesAFactorThreeApart) {
    // Outside the well-separated range the residual model is an approximation: documented
    // bound, so that a regression shows.
    const Tolerance tol{kCloseModesDampingTolerance, kCloseModesFrequencyToleranceInBandwidths};
    for (const TwoDof& s : {TwoDof{10.0, 30.0, 1.0, 1.0}, TwoDof{10.0, 50.0, 1.0, 10.0}}) {
        for (const Outcome& o : check_two_dof(s, tol)) EXPECT_GT(o.resolved, 0);
    }
}

}  // namespace
}  // namespace sb::identification

// Half-power, circle fit and rational fraction on exact SDOF and 2-DOF FRFs.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <vector>

#include "estimator_checks.hpp"
#include "identification/circle_fit.hpp"
#include "identification/half_power.hpp"
#include "identification/rational_fraction.hpp"
#include "identification/residual.hpp"
#include "sdof_frf.hpp"

namespace sb::identification {
namespace {

using testing::grid_around;
using testing::modal_accelerance;
using testing::Mode;
using namespace testing;

TEST(Estimators, RecoverSdofDampingExactlyWheneverTheGridResolvesThePeak) {
    const double fn = 6.37;
    const Tolerance exact{kExactTolerance, kExactTolerance};
    Outcome hp, cf, rf;
    for (double zeta : kDampingRatios) {
        for (int n : kGridSizes) {
            for (double shift : kGridShifts) {
                // Grid spanning ±4 half-bandwidths.
                const auto f = grid_around(fn, zeta, n, 4.0, shift);
                const bool must = grid_resolves(f, fn, zeta);
                const auto frf = modal_accelerance(f, {{fn, zeta, 1.0}});
                check(half_power(frf), fn, zeta, exact, must, hp, label("hp-mob", zeta, n, shift));
                check(half_power(frf, HalfPowerForm::accelerance), fn, zeta, exact,
                      grid_resolves(f, fn, zeta, HalfPowerForm::accelerance), hp,
                      label("hp-acc", zeta, n, shift));
                check(half_power(frf, HalfPowerForm::receptance), fn, zeta, exact,
                      grid_resolves(f, fn, zeta, HalfPowerForm::receptance), hp,
                      label("hp-rec", zeta, n, shift));
                check(circle_fit(frf), fn, zeta, exact, must, cf, label("circle", zeta, n, shift));
                check(rational_fraction_fit(frf), fn, zeta, exact, must, rf,
                      label("rfp", zeta, n, shift));
            }
        }
    }
    // Both paths are exercised: the coarse grids are refused, the fine ones resolved.
    for (const Outcome* o : {&hp, &cf, &rf}) {
        EXPECT_GT(o->resolved, 0);
        EXPECT_GT(o->unresolved, 0);
    }
}

TEST(HalfPower, SubtractsTheLowerModesResidualAtTheUpperMode) {
    // The upper mode of modes a decade apart, ζ = 10 %, 21 points over ±4 half-bandwidths:
    // the lower mode's mass line skews the half-power points; without the residual the
    // estimate is outside the bound, with it inside.
    const double zeta = 0.1;
    const auto frf = modal_accelerance(grid_around(100.0, zeta, 21, 4.0, 0.37),
                                       {{10.0, zeta, 1.0}, {100.0, zeta, 1.0}});
    ResidualOptions off;
    off.compensate = false;
    const auto raw = half_power(frf, HalfPowerForm::mobility, off);
    ASSERT_TRUE(raw.ok()) << raw.message;
    EXPECT_GT(std::abs(raw.damping_ratio / zeta - 1.0), 2.0 * kDampingTolerance)
        << raw.damping_ratio;
    EXPECT_EQ(raw.residual_ratio, 0.0);
    const auto compensated = half_power(frf);
    ASSERT_TRUE(compensated.ok()) << compensated.message;
    EXPECT_NEAR(compensated.damping_ratio / zeta, 1.0, kDampingTolerance);
    // The lower mode's receptance at 100 Hz over the upper mode's: 2ζ (f2²/(f2² − f1²)).
    EXPECT_NEAR(compensated.residual_ratio, 2.0 * zeta * 100.0 / 99.0, 0.1 * 2.0 * zeta);
}

TEST(Residual, FitsNoResidualToAnSdofAndTheOtherModeToATwoDof) {
    const auto f = grid_around(20.0, 0.05, 31, 4.0, 0.2);
    const auto sdof = fit_residual(modal_accelerance(f, {{20.0, 0.05, 2.0}}), 20.3, 0.04, 0.1);
    ASSERT_TRUE(sdof.ok) << sdof.message;
    EXPECT_NEAR(sdof.natural_frequency_hz, 20.0, 20.0 * 0.05 * kExactTolerance);
    EXPECT_NEAR(sdof.damping_ratio, 0.05, 0.05 * kExactTolerance);
    EXPECT_LT(sdof.residual_ratio, kExactTolerance);
    // A stiffness-line residual: a mode far above contributes ≈ A/ω_far² (real, constant).
    const auto two = fit_residual(modal_accelerance(f, {{20.0, 0.05, 2.0}, {400.0, 0.05, 2.0}}),
                                  20.3, 0.04, 0.1);
    ASSERT_TRUE(two.ok) << two.message;
    const double stiffness_line = 2.0 / std::pow(hz_to_rad_s(400.0), 2);
    EXPECT_NEAR(std::abs(two.stiffness_term + two.mass_term) / stiffness_line, 1.0, 0.01);
    EXPECT_NEAR(two.damping_ratio / 0.05, 1.0, kDampingTolerance);
}

TEST(HalfPower, SaysSoWhenOnlyOnePointLiesInsideTheBand) {
    // Five points over ±4 half-bandwidths: step 2ζf_n, one point inside the band.
    const auto frf = modal_accelerance(grid_around(50.0, 0.02, 5, 4.0, 0.0), {{50.0, 0.02, 1.0}});
    const auto e = half_power(frf);
    EXPECT_EQ(e.status, EstimateStatus::too_few_points_in_band) << e.message;
    EXPECT_NE(e.message.find("half-power band"), std::string::npos);
}

TEST(HalfPower, SaysSoWhenTheGridStopsAboveTheLowerCrossing) {
    auto f = grid_around(50.0, 0.02, 21, 4.0, 0.0);
    f.erase(f.begin(), f.begin() + 8);  // starts at f_n(1 − 0.8ζ): inside the band
    const auto e = half_power(modal_accelerance(f, {{50.0, 0.02, 1.0}}));
    EXPECT_EQ(e.status, EstimateStatus::no_lower_crossing) << e.message;
}

TEST(HalfPower, SaysSoWhenTheGridStopsBelowTheUpperCrossing) {
    auto f = grid_around(50.0, 0.02, 21, 4.0, 0.0);
    f.resize(13);
    const auto e = half_power(modal_accelerance(f, {{50.0, 0.02, 1.0}}));
    EXPECT_EQ(e.status, EstimateStatus::no_upper_crossing) << e.message;
}

TEST(HalfPower, SaysSoWhenThePeakIsAtTheGridEdge) {
    const auto e = half_power(modal_accelerance({40.0, 42.0, 44.0}, {{50.0, 0.02, 1.0}}));
    EXPECT_EQ(e.status, EstimateStatus::peak_at_grid_edge);
}

TEST(HalfPower, PlainAccelerancePeakEstimateWouldBeBiasedWhichTheExactRelationAvoids) {
    // Note §3.1: (ω2 − ω1)/(2ωp) on accelerance is +20.6 % at ζ = 0.2; ours is exact.
    const auto frf = modal_accelerance(grid_around(10.0, 0.2, 41, 3.0, 0.1), {{10.0, 0.2, 1.0}});
    const auto e = half_power(frf, HalfPowerForm::accelerance);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_NEAR(e.damping_ratio, 0.2, 0.2 * kExactTolerance);
}

TEST(CircleFit, FitsACircleThroughPointsOnACircle) {
    std::vector<std::complex<double>> z;
    for (int i = 0; i < 7; ++i)
        z.push_back(std::complex<double>(3.0, -2.0) + 1.5 * std::polar(1.0, 0.4 * i));
    const auto c = fit_circle(z);
    EXPECT_NEAR(c.centre.real(), 3.0, 1e-12);
    EXPECT_NEAR(c.centre.imag(), -2.0, 1e-12);
    EXPECT_NEAR(c.radius, 1.5, 1e-12);
}

TEST(CircleFit, ReportsSmallSpreadOnExactDataAndSaysSoWithTooFewPoints) {
    const auto good =
        circle_fit(modal_accelerance(grid_around(20.0, 0.05, 31, 3.0, 0.2), {{20.0, 0.05, 1.0}}));
    ASSERT_TRUE(good.ok()) << good.message;
    EXPECT_LT(good.damping_spread, 1e-8);
    const auto bad =
        circle_fit(modal_accelerance(grid_around(20.0, 0.05, 5, 6.0, 0.0), {{20.0, 0.05, 1.0}}));
    EXPECT_EQ(bad.status, EstimateStatus::too_few_points) << bad.message;
}

TEST(CircleFit, TakesTheStepsBackThatNoiseOnAFineGridMakes) {
    // A random test's H1: 401 lines over +-6 half-bandwidths, each with 4 % complex noise.
    // The angle about the centre steps back here and there; the angle fit and the pairs
    // average the noise out.
    Frf frf = modal_accelerance(grid_around(20.0, 0.02, 401, 6.0, 0.0), {{20.0, 0.02, 1.0}});
    std::mt19937_64 rng(11);
    std::normal_distribution<double> noise(0.0, 0.04);
    for (auto& v : frf.value) v *= std::complex<double>(1.0 + noise(rng), noise(rng));
    const auto e = circle_fit(frf);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_NEAR(e.natural_frequency_hz, 20.0, 0.002 * 20.0);
    EXPECT_NEAR(e.damping_ratio, 0.02, 0.05 * 0.02);
}

}  // namespace
}  // namespace sb::identification

// FRF forms, phase conventions and transmissibility.
#include "identification/frf.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/units.hpp"
#include "identification/circle_fit.hpp"
#include "identification/half_power.hpp"
#include "identification/rational_fraction.hpp"
#include "sdof_frf.hpp"

namespace sb::identification {
namespace {

/// Closed-form comparisons: round-off only.
constexpr double kRoundOff = 1e-12;
/// Exact data through iterative fits.
constexpr double kExactTolerance = 1e-6;

TEST(Frf, ReceptanceAndMobilityFollowFromAccelerance) {
    const double fn = 10.0, zeta = 0.05, f = 9.0;
    const auto acc = testing::modal_accelerance({f}, {{fn, zeta, 1.0}});
    const double w = hz_to_rad_s(f), wn = hz_to_rad_s(fn);
    const std::complex<double> alpha =
        1.0 / std::complex<double>(wn * wn - w * w, 2.0 * zeta * wn * w);
    EXPECT_NEAR(std::abs(convert(acc, FrfForm::receptance).value[0] - alpha), 0.0,
                kRoundOff * std::abs(alpha));
    const std::complex<double> mobility = std::complex<double>(0.0, w) * alpha;
    EXPECT_NEAR(std::abs(convert(acc, FrfForm::mobility).value[0] - mobility), 0.0,
                kRoundOff * std::abs(mobility));
    const auto back = convert(convert(acc, FrfForm::receptance), FrfForm::accelerance);
    EXPECT_NEAR(std::abs(back.value[0] - acc.value[0]), 0.0, kRoundOff * std::abs(acc.value[0]));
}

TEST(Frf, PhaseAtResonanceIsMinusNinetyForReceptanceAndPlusNinetyForAccelerance) {
    // With x(t) = Re{X e^{iωt}} (research note §5, pyFRF #14: test the sign).
    const auto acc = testing::modal_accelerance({10.0}, {{10.0, 0.02, 1.0}});
    EXPECT_NEAR(std::arg(acc.value[0]), kPi / 2.0, kRoundOff);
    EXPECT_NEAR(std::arg(convert(acc, FrfForm::receptance).value[0]), -kPi / 2.0, kRoundOff);
    EXPECT_NEAR(std::arg(convert(acc, FrfForm::mobility).value[0]), 0.0, kRoundOff);
}

TEST(Frf, RelativeTransmissibilityOfABaseExcitedSdofGivesItsExactDamping) {
    const double fn = 30.0, zeta = 0.08;
    const auto f = testing::grid_around(fn, zeta, 25, 4.0, 0.3);
    std::vector<std::complex<double>> table, mass;
    for (double fi : f) {
        const double w = hz_to_rad_s(fi), wn = hz_to_rad_s(fn);
        const std::complex<double> yb(0.3, -0.1);  // table acceleration amplitude [m/s²]
        // Absolute transmissibility (ωn² + 2iζωnω)/(ωn² − ω² + 2iζωnω).
        const std::complex<double> t = std::complex<double>(wn * wn, 2.0 * zeta * wn * w) /
                                       std::complex<double>(wn * wn - w * w, 2.0 * zeta * wn * w);
        table.push_back(yb);
        mass.push_back(t * yb);
    }
    const auto tr = transmissibility(f, mass, table);
    EXPECT_NEAR(std::abs(tr.value[0] - mass[0] / table[0]), 0.0, kRoundOff);
    const auto rel = relative_transmissibility(f, mass, table);
    for (const auto& e : {half_power(rel), circle_fit(rel), rational_fraction_fit(rel)}) {
        ASSERT_TRUE(e.ok()) << e.message;
        EXPECT_NEAR(e.damping_ratio / zeta, 1.0, kExactTolerance);
        EXPECT_NEAR(e.natural_frequency_hz / fn, 1.0, kExactTolerance);
    }
}

TEST(Frf, AbsoluteTransmissibilityGivesTheExactDampingOnceItsConstantIsSubtracted) {
    // T = 1 + ω²/(ωn² − ω² + 2iζωnω): accelerance shape plus 1, i.e. a mass-line residual.
    const double fn = 30.0, zeta = 0.08;
    const auto f = testing::grid_around(fn, zeta, 25, 4.0, 0.3);
    std::vector<std::complex<double>> table, mass;
    for (double fi : f) {
        const double w = hz_to_rad_s(fi), wn = hz_to_rad_s(fn);
        const std::complex<double> yb(0.3, -0.1);
        table.push_back(yb);
        mass.push_back(yb * std::complex<double>(wn * wn, 2.0 * zeta * wn * w) /
                       std::complex<double>(wn * wn - w * w, 2.0 * zeta * wn * w));
    }
    const auto tr = transmissibility(f, mass, table);
    EXPECT_EQ(tr.form, FrfForm::accelerance);
    for (const auto& e : {half_power(tr), circle_fit(tr), rational_fraction_fit(tr)}) {
        ASSERT_TRUE(e.ok()) << e.message;
        EXPECT_NEAR(e.damping_ratio / zeta, 1.0, kExactTolerance);
        EXPECT_NEAR((e.natural_frequency_hz - fn) / (zeta * fn), 0.0, kExactTolerance);
    }
    // Without the residual the constant skews the half-power points.
    ResidualOptions off;
    off.compensate = false;
    const auto raw = half_power(tr, HalfPowerForm::mobility, off);
    ASSERT_TRUE(raw.ok()) << raw.message;
    EXPECT_GT(std::abs(raw.damping_ratio / zeta - 1.0), 0.01);
}

TEST(Frf, RejectsUnsortedFrequencies) {
    const Frf bad{{2.0, 1.0}, {1.0, 1.0}, FrfForm::accelerance};
    EXPECT_THROW(check_frf(bad), std::invalid_argument);
}

}  // namespace
}  // namespace sb::identification

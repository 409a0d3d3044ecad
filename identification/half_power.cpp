// Half-power bandwidth, research note control-identification.md §3.1 (exact relations).
#include "identification/half_power.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/units.hpp"
#include "identification/rational_fraction.hpp"

namespace sb::identification {

namespace {

FrfForm frf_form(HalfPowerForm form) {
    switch (form) {
        case HalfPowerForm::mobility:
            return FrfForm::mobility;
        case HalfPowerForm::receptance:
            return FrfForm::receptance;
        case HalfPowerForm::accelerance:
            return FrfForm::accelerance;
    }
    return FrfForm::mobility;
}

int shift(HalfPowerForm form) {  // j in ω^{2j}/|T|² = p0 + p1 s + p2 s², s = ω²
    switch (form) {
        case HalfPowerForm::receptance:
            return 0;
        case HalfPowerForm::mobility:
            return 1;
        case HalfPowerForm::accelerance:
            return 2;
    }
    return 1;
}

std::string hz(double f) {
    std::ostringstream s;
    s.precision(6);
    s << f << " Hz";
    return s.str();
}

/// Half-power on the FRF as given (no residual handling).
ModalEstimate half_power_of(const Frf& input, HalfPowerForm form) {
    const Frf frf = convert(input, frf_form(form));
    const std::size_t n = frf.value.size();
    if (n < 3) return failed_estimate(EstimateStatus::too_few_points, "fewer than 3 grid points");
    std::vector<double> mag(n);
    for (std::size_t i = 0; i < n; ++i) mag[i] = std::abs(frf.value[i]);
    const auto peak = static_cast<std::size_t>(
        std::distance(mag.begin(), std::max_element(mag.begin(), mag.end())));
    if (peak == 0 || peak + 1 == n) {
        return failed_estimate(EstimateStatus::peak_at_grid_edge,
                               "largest |FRF| at the grid edge (" + hz(frf.frequency_hz[peak]) +
                                   "): the peak is not bracketed");
    }
    // The sampled maximum is below the true one, so a point under max/√2 is surely outside.
    const double level = mag[peak] / std::sqrt(2.0);
    std::size_t lo = peak;
    while (lo > 0 && mag[lo] >= level) --lo;
    if (mag[lo] >= level) {
        return failed_estimate(EstimateStatus::no_lower_crossing,
                               "no grid point below the half-power level under the peak at " +
                                   hz(frf.frequency_hz[peak]));
    }
    std::size_t hi = peak;
    while (hi + 1 < n && mag[hi] >= level) ++hi;
    if (mag[hi] >= level) {
        return failed_estimate(EstimateStatus::no_upper_crossing,
                               "no grid point below the half-power level above the peak at " +
                                   hz(frf.frequency_hz[peak]));
    }

    // Least squares: ω^{2j}/|T|² = p0 + p1 s + p2 s², s = (ω/ω_peak)² for conditioning.
    const int j = shift(form);
    const double w_ref = hz_to_rad_s(frf.frequency_hz[peak]);
    const auto m = static_cast<Eigen::Index>(hi - lo + 1);
    Eigen::MatrixXd a(m, 3);
    Eigen::VectorXd b(m);
    for (Eigen::Index r = 0; r < m; ++r) {
        const std::size_t i = lo + static_cast<std::size_t>(r);
        const double s = std::pow(hz_to_rad_s(frf.frequency_hz[i]) / w_ref, 2);
        a(r, 0) = 1.0;
        a(r, 1) = s;
        a(r, 2) = s * s;
        b(r) = std::pow(s, j) / (mag[i] * mag[i]) * (mag[peak] * mag[peak]);
    }
    const Eigen::Vector3d p = a.colPivHouseholderQr().solve(b);
    // Minimum of g(s) = q(s)/s^j.
    double sp = 0.0;
    if (j == 0) sp = -p(1) / (2.0 * p(2));
    if (j == 1) sp = std::sqrt(p(0) / p(2));
    if (j == 2) sp = -2.0 * p(0) / p(1);
    const double s_lo = std::pow(hz_to_rad_s(frf.frequency_hz[lo]) / w_ref, 2);
    const double s_hi = std::pow(hz_to_rad_s(frf.frequency_hz[hi]) / w_ref, 2);
    const double g_min = (p(0) + p(1) * sp + p(2) * sp * sp) / std::pow(sp, j);
    if (!std::isfinite(sp) || !(sp > s_lo && sp < s_hi) || !(g_min > 0.0)) {
        return failed_estimate(EstimateStatus::fit_failed,
                               "the SDOF interpolation has no peak inside the bracketing points");
    }
    // Crossings: q(s) − 2 g_min s^j = 0.
    Eigen::Vector3d c = p;
    c(j) -= 2.0 * g_min;
    const double disc = c(1) * c(1) - 4.0 * c(0) * c(2);
    if (!(disc > 0.0) || c(2) == 0.0) {
        return failed_estimate(EstimateStatus::fit_failed, "no real half-power crossings");
    }
    // Numerically stable quadratic roots (Numerical Recipes §5.6).
    const double qq = -0.5 * (c(1) + std::copysign(std::sqrt(disc), c(1)));
    double s1 = qq / c(2);
    double s2 = c(0) / qq;
    if (s1 > s2) std::swap(s1, s2);
    if (!(s1 > 0.0 && s1 < sp && s2 > sp)) {
        return failed_estimate(EstimateStatus::fit_failed,
                               "half-power crossings not around the peak");
    }
    const double w1 = w_ref * std::sqrt(s1);
    const double w2 = w_ref * std::sqrt(s2);
    int inside = 0;
    for (double f : frf.frequency_hz) {
        const double w = hz_to_rad_s(f);
        if (w > w1 && w < w2) ++inside;
    }
    if (inside < kHalfPowerMinPointsInBand) {
        return failed_estimate(EstimateStatus::too_few_points_in_band,
                               "only " + std::to_string(inside) +
                                   " grid point(s) inside the half-power band [" + hz(w1 / kTwoPi) +
                                   ", " + hz(w2 / kTwoPi) + "]; need " +
                                   std::to_string(kHalfPowerMinPointsInBand) +
                                   ": refine the grid (step <= 2 zeta f_n / 5)");
    }
    ModalEstimate e;
    e.status = EstimateStatus::ok;
    e.points_used = static_cast<int>(m);
    e.frequencies_used_hz.assign(frf.frequency_hz.begin() + static_cast<long>(lo),
                                 frf.frequency_hz.begin() + static_cast<long>(hi) + 1);
    double wn = 0.0;
    if (form == HalfPowerForm::mobility) {
        // Mobility: ω1ω2 = ωn², ζ = (ω2 − ω1)/(2ωn) exactly.
        wn = std::sqrt(w1 * w2);
        e.damping_ratio = (w2 - w1) / (2.0 * wn);
    } else {
        // Receptance/accelerance: ζ = sin(½ atan R), R = (ω2² − ω1²)/(ω2² + ω1²) (note §3.1).
        const double r = (w2 * w2 - w1 * w1) / (w2 * w2 + w1 * w1);
        const double two_theta = std::atan(r);
        e.damping_ratio = std::sin(0.5 * two_theta);
        // ωp² = ωn² cos 2θ with ωp² = (ω1² + ω2²)/2 (receptance); ω → 1/ω for accelerance.
        if (form == HalfPowerForm::receptance) {
            wn = std::sqrt((w1 * w1 + w2 * w2) / (2.0 * std::cos(two_theta)));
        } else {
            wn = 1.0 / std::sqrt((1.0 / (w1 * w1) + 1.0 / (w2 * w2)) / (2.0 * std::cos(two_theta)));
        }
    }
    e.natural_frequency_hz = wn / kTwoPi;
    return e;
}

}  // namespace

ModalEstimate half_power(const Frf& frf, HalfPowerForm form, const ResidualOptions& residual) {
    RationalFractionOptions plain;
    plain.residual.compensate = false;
    return estimate_with_residual(
        frf, residual, [form](const Frf& f) { return half_power_of(f, form); },
        [&plain](const Frf& f) { return rational_fraction_fit(f, plain); });
}

}  // namespace sb::identification

// Rational-fraction polynomial fit, research note control-identification.md §3.4
// (Richardson & Formenti, IMAC 1982; Sanathanan & Koerner, IEEE TAC 1963).
#include "identification/rational_fraction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/units.hpp"

namespace sb::identification {

namespace {

ModalEstimate rational_fraction_of(const Frf& frf, const RationalFractionOptions& options) {
    check_frf(frf);
    const std::size_t n = frf.value.size();
    if (n < 3) return failed_estimate(EstimateStatus::too_few_points, "fewer than 3 grid points");
    std::vector<double> mag(n);
    for (std::size_t i = 0; i < n; ++i) mag[i] = std::abs(frf.value[i]);
    const auto peak = static_cast<std::size_t>(
        std::distance(mag.begin(), std::max_element(mag.begin(), mag.end())));
    if (peak == 0 || peak + 1 == n) {
        return failed_estimate(EstimateStatus::peak_at_grid_edge,
                               "largest |FRF| at the grid edge: the peak is not bracketed");
    }
    const double level = options.min_relative_magnitude * mag[peak];
    std::size_t lo = peak;
    while (lo > 0 && mag[lo - 1] >= level) --lo;
    std::size_t hi = peak;
    while (hi + 1 < n && mag[hi + 1] >= level) ++hi;
    const int count = static_cast<int>(hi - lo + 1);
    if (count < options.min_points) {
        return failed_estimate(EstimateStatus::too_few_points,
                               std::to_string(count) + " point(s) with |FRF| >= " +
                                   std::to_string(options.min_relative_magnitude) +
                                   " x peak; need " + std::to_string(options.min_points));
    }
    const double w_ref = hz_to_rad_s(frf.frequency_hz[peak]);
    const double t_ref = mag[peak];
    const auto m = static_cast<Eigen::Index>(count);
    std::vector<double> weight(static_cast<std::size_t>(count), 1.0);
    Eigen::VectorXd x(5);  // b0, b1, a0, a1, a2
    for (int it = 0; it <= options.iterations; ++it) {
        Eigen::MatrixXd a(2 * m, 5);
        Eigen::VectorXd rhs(2 * m);
        for (Eigen::Index r = 0; r < m; ++r) {
            const std::size_t i = lo + static_cast<std::size_t>(r);
            const std::complex<double> s(0.0, hz_to_rad_s(frf.frequency_hz[i]) / w_ref);
            const std::complex<double> t = frf.value[i] / t_ref;
            const double wt = weight[static_cast<std::size_t>(r)];
            // Levy: T (b0 + b1 s) − (a0 + a1 s + a2 s²) = −T s².
            const std::complex<double> cols[5] = {t, t * s, -1.0, -s, -s * s};
            const std::complex<double> right = -t * s * s;
            for (int c = 0; c < 5; ++c) {
                a(2 * r, c) = wt * cols[c].real();
                a(2 * r + 1, c) = wt * cols[c].imag();
            }
            rhs(2 * r) = wt * right.real();
            rhs(2 * r + 1) = wt * right.imag();
        }
        x = a.colPivHouseholderQr().solve(rhs);
        for (Eigen::Index r = 0; r < m; ++r) {
            const std::size_t i = lo + static_cast<std::size_t>(r);
            const std::complex<double> s(0.0, hz_to_rad_s(frf.frequency_hz[i]) / w_ref);
            weight[static_cast<std::size_t>(r)] = 1.0 / std::abs(s * s + x(1) * s + x(0));
        }
    }
    if (!(x(0) > 0.0) || !(x(1) > 0.0) || !std::isfinite(x(0)) || !std::isfinite(x(1))) {
        return failed_estimate(EstimateStatus::fit_failed,
                               "the fitted denominator has no damped oscillating pole");
    }
    ModalEstimate e;
    e.status = EstimateStatus::ok;
    e.natural_frequency_hz = w_ref * std::sqrt(x(0)) / kTwoPi;  // ωn² = b0 (note §3.4)
    e.damping_ratio = x(1) / (2.0 * std::sqrt(x(0)));           // 2ζωn = b1
    e.points_used = count;
    e.frequencies_used_hz.assign(frf.frequency_hz.begin() + static_cast<long>(lo),
                                 frf.frequency_hz.begin() + static_cast<long>(hi) + 1);
    if (!(e.damping_ratio < 1.0)) {
        return failed_estimate(EstimateStatus::fit_failed, "fitted damping ratio >= 1");
    }
    return e;
}

}  // namespace

ModalEstimate rational_fraction_fit(const Frf& frf, const RationalFractionOptions& options) {
    const auto plain = [&options](const Frf& f) { return rational_fraction_of(f, options); };
    return estimate_with_residual(frf, options.residual, plain, plain);
}

}  // namespace sb::identification

// Circle fit, research note control-identification.md §3.2 (Maia & Silva 1997; Ewins 2000).
#include "identification/circle_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace sb::identification {

namespace {
/// Gauss–Newton iterations of the geometric circle fit; it converges in a handful from Kåsa.
constexpr int kGeometricIterations = 20;
/// Levenberg–Marquardt iterations of the angle model; 3 unknowns, converges in < 20.
constexpr int kAngleIterations = 50;
}  // namespace

Circle fit_circle(const std::vector<std::complex<double>>& points) {
    const auto n = static_cast<Eigen::Index>(points.size());
    if (n < 3) throw std::invalid_argument("fit_circle: need at least 3 points");
    // Scale to O(1) for conditioning.
    double scale = 0.0;
    for (const auto& z : points) scale = std::max(scale, std::abs(z));
    if (!(scale > 0.0)) throw std::invalid_argument("fit_circle: all points are zero");
    Eigen::MatrixXd a(n, 3);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto z = points[static_cast<std::size_t>(i)] / scale;
        a(i, 0) = z.real();
        a(i, 1) = z.imag();
        a(i, 2) = 1.0;
        b(i) = -std::norm(z);
    }
    const Eigen::Vector3d k = a.colPivHouseholderQr().solve(b);
    double xc = -k(0) / 2.0;
    double yc = -k(1) / 2.0;
    double r = std::sqrt(xc * xc + yc * yc - k(2));
    for (int it = 0; it < kGeometricIterations; ++it) {
        Eigen::MatrixXd j(n, 3);
        Eigen::VectorXd res(n);
        for (Eigen::Index i = 0; i < n; ++i) {
            const auto z = points[static_cast<std::size_t>(i)] / scale;
            const double dx = z.real() - xc;
            const double dy = z.imag() - yc;
            const double d = std::hypot(dx, dy);
            if (d == 0.0) return {std::complex<double>(xc, yc) * scale, r * scale};
            res(i) = d - r;
            j(i, 0) = -dx / d;
            j(i, 1) = -dy / d;
            j(i, 2) = -1.0;
        }
        const Eigen::Vector3d step = j.colPivHouseholderQr().solve(-res);
        xc += step(0);
        yc += step(1);
        r += step(2);
        if (step.norm() < 1e-15) break;
    }
    return {std::complex<double>(xc, yc) * scale, std::abs(r) * scale};
}

ModalEstimate circle_fit(const Frf& input, const CircleFitOptions& options) {
    const Frf frf = convert(input, FrfForm::mobility);
    const std::size_t n = frf.value.size();
    if (n < 3) return failed_estimate(EstimateStatus::too_few_points, "fewer than 3 grid points");
    std::vector<double> mag(n);
    for (std::size_t i = 0; i < n; ++i) mag[i] = std::abs(frf.value[i]);
    const auto peak = static_cast<std::size_t>(
        std::distance(mag.begin(), std::max_element(mag.begin(), mag.end())));
    if (peak == 0 || peak + 1 == n) {
        return failed_estimate(EstimateStatus::peak_at_grid_edge,
                               "largest |mobility| at the grid edge: resonance not bracketed");
    }
    const double level = options.min_relative_magnitude * mag[peak];
    std::size_t lo = peak;
    while (lo > 0 && mag[lo - 1] >= level) --lo;
    std::size_t hi = peak;
    while (hi + 1 < n && mag[hi + 1] >= level) ++hi;
    const int count = static_cast<int>(hi - lo + 1);
    if (count < options.min_points || lo == peak || hi == peak) {
        return failed_estimate(EstimateStatus::too_few_points,
                               std::to_string(count) + " point(s) with |mobility| >= " +
                                   std::to_string(options.min_relative_magnitude) +
                                   " x peak; need " + std::to_string(options.min_points) +
                                   " with at least one either side of the peak");
    }
    std::vector<std::complex<double>> z(frf.value.begin() + static_cast<long>(lo),
                                        frf.value.begin() + static_cast<long>(hi) + 1);
    std::vector<double> w(z.size());
    for (std::size_t i = 0; i < z.size(); ++i) w[i] = hz_to_rad_s(frf.frequency_hz[lo + i]);
    const Circle circle = fit_circle(z);

    // Angles about the centre, unwrapped, oriented to increase with frequency.
    std::vector<double> a(z.size());
    for (std::size_t i = 0; i < z.size(); ++i) {
        a[i] = std::arg(z[i] - circle.centre);
        if (i > 0) {
            while (a[i] - a[i - 1] > kPi) a[i] -= kTwoPi;
            while (a[i] - a[i - 1] < -kPi) a[i] += kTwoPi;
        }
    }
    if (a.back() < a.front()) {
        for (auto& v : a) v = -v;
    }
    // Start: fastest sweep dθ/dω² between neighbours, refined by a parabola through the rates.
    const std::size_t m = z.size();
    std::vector<double> rate(m - 1);
    std::vector<double> s_mid(m - 1);
    for (std::size_t i = 0; i + 1 < m; ++i) {
        rate[i] = (a[i + 1] - a[i]) / (w[i + 1] * w[i + 1] - w[i] * w[i]);
        s_mid[i] = 0.5 * (w[i + 1] * w[i + 1] + w[i] * w[i]);
    }
    const auto k = static_cast<std::size_t>(
        std::distance(rate.begin(), std::max_element(rate.begin(), rate.end())));
    double sr = s_mid[k];
    if (k > 0 && k + 1 < rate.size()) {
        const double x0 = s_mid[k - 1], x1 = s_mid[k], x2 = s_mid[k + 1];
        const double y0 = rate[k - 1], y1 = rate[k], y2 = rate[k + 1];
        const double d1 = (y1 - y0) / (x1 - x0), d2 = (y2 - y1) / (x2 - x1);
        const double c2 = (d2 - d1) / (x2 - x0);
        if (c2 < 0.0) sr = std::clamp(0.5 * (x0 + x1) - d1 / (2.0 * c2), x0, x2);
    }
    double ar = a[0];
    for (std::size_t i = 0; i + 1 < m; ++i) {
        const double s0 = w[i] * w[i], s1 = w[i + 1] * w[i + 1];
        if (sr >= s0 && sr <= s1) ar = a[i] + (a[i + 1] - a[i]) * (sr - s0) / (s1 - s0);
    }
    // Initial ζωn from the sweep rate at resonance: dθ/dω² = 1/(ζωn²) there.
    double zw = 1.0 / (rate[k] * std::sqrt(sr));
    // Refine (θr, ωn², ζωn) by Levenberg–Marquardt on θ_i = θr + 2 atan((ω_i² − ωn²)/(2ζωnω_i)).
    Eigen::Vector3d x(ar, sr, zw);
    const double s_scale = sr;
    auto residuals = [&](const Eigen::Vector3d& p, Eigen::VectorXd& res, Eigen::MatrixXd* jac) {
        for (std::size_t i = 0; i < m; ++i) {
            const auto r = static_cast<Eigen::Index>(i);
            const double u = (w[i] * w[i] - p(1)) / (2.0 * p(2) * w[i]);
            res(r) = p(0) + 2.0 * std::atan(u) - a[i];
            if (jac != nullptr) {
                const double g = 2.0 / (1.0 + u * u);
                (*jac)(r, 0) = 1.0;
                (*jac)(r, 1) = g * (-1.0 / (2.0 * p(2) * w[i])) * s_scale;
                (*jac)(r, 2) = g * (-u / p(2)) * p(2);
            }
        }
    };
    Eigen::VectorXd res(static_cast<Eigen::Index>(m));
    Eigen::MatrixXd jac(static_cast<Eigen::Index>(m), 3);
    residuals(x, res, &jac);
    double cost = res.squaredNorm();
    double lambda = 1e-3;
    for (int it = 0; it < kAngleIterations && cost > 0.0; ++it) {
        const Eigen::Matrix3d jtj = jac.transpose() * jac;
        const Eigen::Vector3d g = jac.transpose() * res;
        Eigen::Matrix3d damped = jtj;
        damped.diagonal() *= (1.0 + lambda);
        const Eigen::Vector3d dn = damped.ldlt().solve(-g);
        // Parameters 1 and 2 were scaled in the Jacobian: undo the scaling in the step.
        Eigen::Vector3d trial = x;
        trial(0) += dn(0);
        trial(1) += dn(1) * s_scale;
        trial(2) *= std::exp(std::clamp(dn(2), -1.0, 1.0));  // keeps ζωn > 0
        Eigen::VectorXd res_t(static_cast<Eigen::Index>(m));
        residuals(trial, res_t, nullptr);
        const double cost_t = res_t.squaredNorm();
        if (std::isfinite(cost_t) && cost_t < cost) {
            const bool converged = cost - cost_t < 1e-30 + 1e-16 * cost;
            x = trial;
            residuals(x, res, &jac);
            cost = cost_t;
            lambda = std::max(lambda * 0.3, 1e-12);
            if (converged) break;
        } else {
            lambda *= 10.0;
            if (lambda > 1e12) break;
        }
    }
    const double wr = std::sqrt(x(1));
    if (!std::isfinite(wr) || !(x(1) > w.front() * w.front() && x(1) < w.back() * w.back())) {
        return failed_estimate(EstimateStatus::fit_failed,
                               "the resonance of the circle lies outside the fitted points");
    }
    // Ewins' pair formula (note §3.2, step 4): all pairs b below, a above ωr.
    std::vector<double> zetas;
    for (std::size_t ib = 0; ib < m; ++ib) {
        if (!(w[ib] < wr)) continue;
        const double tb = std::tan(std::abs(a[ib] - x(0)) / 2.0);
        for (std::size_t ia = 0; ia < m; ++ia) {
            if (!(w[ia] > wr)) continue;
            const double ta = std::tan(std::abs(a[ia] - x(0)) / 2.0);
            zetas.push_back((w[ia] * w[ia] - w[ib] * w[ib]) /
                            (2.0 * wr * (w[ia] * ta + w[ib] * tb)));
        }
    }
    if (zetas.empty()) {
        return failed_estimate(EstimateStatus::too_few_points,
                               "no point pair either side of the circle's resonance");
    }
    double mean = 0.0;
    for (double v : zetas) mean += v;
    mean /= static_cast<double>(zetas.size());
    double var = 0.0;
    for (double v : zetas) var += (v - mean) * (v - mean);
    ModalEstimate e;
    e.status = EstimateStatus::ok;
    e.natural_frequency_hz = wr / kTwoPi;
    e.damping_ratio = mean;
    e.damping_spread =
        zetas.size() > 1 ? std::sqrt(var / static_cast<double>(zetas.size() - 1)) : 0.0;
    e.points_used = static_cast<int>(m);
    if (!(mean > 0.0) || !std::isfinite(mean)) {
        return failed_estimate(EstimateStatus::fit_failed, "non-positive circle-fit damping");
    }
    return e;
}

}  // namespace sb::identification

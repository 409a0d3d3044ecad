// Circle fit, research note control-identification.md §3.2 (Maia & Silva 1997; Ewins 2000).
#include "identification/circle_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unsupported/Eigen/LevenbergMarquardt>

#include "core/units.hpp"
#include "identification/rational_fraction.hpp"

namespace sb::identification {

namespace {

/// Largest angle about the centre between neighbouring points. With 3 points in the
/// half-power band no step exceeds 4 atan(1/2) = 106°; near 180° the unwrapping (shorter way
/// round) can go either way, so 120° is the limit.
constexpr double kMaxAngleStep = 2.0 * kPi / 3.0;

/// Geometric circle fit: residuals |z_i − c| − R for x = (xc, yc, R), analytic Jacobian.
struct CircleDistances : Eigen::DenseFunctor<double> {
    const std::vector<std::complex<double>>* z;
    explicit CircleDistances(const std::vector<std::complex<double>>& points)
        : Eigen::DenseFunctor<double>(3, static_cast<int>(points.size())), z(&points) {}
    int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
        for (std::size_t i = 0; i < z->size(); ++i) {
            f(static_cast<Eigen::Index>(i)) =
                std::abs((*z)[i] - std::complex<double>(x(0), x(1))) - x(2);
        }
        return 0;
    }
    int df(const Eigen::VectorXd& x, Eigen::MatrixXd& j) const {
        for (std::size_t i = 0; i < z->size(); ++i) {
            const auto r = static_cast<Eigen::Index>(i);
            const std::complex<double> d = (*z)[i] - std::complex<double>(x(0), x(1));
            const double a = std::max(std::abs(d), std::numeric_limits<double>::min());
            j(r, 0) = -d.real() / a;
            j(r, 1) = -d.imag() / a;
            j(r, 2) = -1.0;
        }
        return 0;
    }
};

/// Angle model of a viscous mode on its circle, x = (θr, ωn²/s_ref, ln ζωn):
/// θ_i = θr + 2 atan((ω_i² − ωn²)/(2ζωnω_i)) (note §3.2, exact for viscous mobility).
struct AngleModel : Eigen::DenseFunctor<double> {
    const std::vector<double>* w;
    const std::vector<double>* angle;
    double s_ref;
    AngleModel(const std::vector<double>& omega, const std::vector<double>& theta, double s)
        : Eigen::DenseFunctor<double>(3, static_cast<int>(omega.size())),
          w(&omega),
          angle(&theta),
          s_ref(s) {}
    double u(const Eigen::VectorXd& x, std::size_t i) const {
        const double wi = (*w)[i];
        return (wi * wi - x(1) * s_ref) / (2.0 * std::exp(x(2)) * wi);
    }
    int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
        for (std::size_t i = 0; i < w->size(); ++i) {
            f(static_cast<Eigen::Index>(i)) = x(0) + 2.0 * std::atan(u(x, i)) - (*angle)[i];
        }
        return 0;
    }
    int df(const Eigen::VectorXd& x, Eigen::MatrixXd& j) const {
        for (std::size_t i = 0; i < w->size(); ++i) {
            const auto r = static_cast<Eigen::Index>(i);
            const double ui = u(x, i);
            const double g = 2.0 / (1.0 + ui * ui);
            j(r, 0) = 1.0;
            j(r, 1) = g * (-s_ref / (2.0 * std::exp(x(2)) * (*w)[i]));
            j(r, 2) = g * (-ui);
        }
        return 0;
    }
};

}  // namespace

Circle fit_circle(const std::vector<std::complex<double>>& points) {
    const auto n = static_cast<Eigen::Index>(points.size());
    if (n < 3) throw std::invalid_argument("fit_circle: need at least 3 points");
    // Scale to O(1) for conditioning.
    double scale = 0.0;
    for (const auto& z : points) scale = std::max(scale, std::abs(z));
    if (!(scale > 0.0)) throw std::invalid_argument("fit_circle: all points are zero");
    std::vector<std::complex<double>> z(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) z[i] = points[i] / scale;
    Eigen::MatrixXd a(n, 3);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto zi = z[static_cast<std::size_t>(i)];
        a(i, 0) = zi.real();
        a(i, 1) = zi.imag();
        a(i, 2) = 1.0;
        b(i) = -std::norm(zi);
    }
    const Eigen::Vector3d k = a.colPivHouseholderQr().solve(b);
    Eigen::VectorXd x(3);
    x << -k(0) / 2.0, -k(1) / 2.0, 0.0;
    x(2) = std::sqrt(x(0) * x(0) + x(1) * x(1) - k(2));
    CircleDistances distances(z);
    Eigen::LevenbergMarquardt<CircleDistances> lm(distances);
    lm.setXtol(1e-15);
    lm.setFtol(1e-15);
    lm.minimize(x);
    return {std::complex<double>(x(0), x(1)) * scale, std::abs(x(2)) * scale};
}

namespace {

ModalEstimate circle_fit_of(const Frf& input, const CircleFitOptions& options) {
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
    // Widen a short run by the larger neighbour until it has min_points.
    while (static_cast<int>(hi - lo + 1) < options.min_points && (lo > 0 || hi + 1 < n)) {
        if (hi + 1 >= n || (lo > 0 && mag[lo - 1] >= mag[hi + 1])) {
            --lo;
        } else {
            ++hi;
        }
    }
    const int count = static_cast<int>(hi - lo + 1);
    if (count < options.min_points || lo == peak || hi == peak) {
        return failed_estimate(EstimateStatus::too_few_points,
                               std::to_string(count) + " grid point(s) around the peak; need " +
                                   std::to_string(options.min_points) +
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
    // A step back is noise on the FRF (a random test's H1, a measured point): the angle fit
    // below takes it. A step too large leaves the arc unknown between the points.
    for (std::size_t i = 1; i < a.size(); ++i) {
        const double step = a[i] - a[i - 1];
        if (!(std::abs(step) <= kMaxAngleStep)) {
            return failed_estimate(
                EstimateStatus::too_few_points,
                "the arc is too coarsely sampled: " +
                    std::to_string(static_cast<int>(std::round(std::abs(step) * 180.0 / kPi))) +
                    " deg between neighbouring points (at most 120): "
                    "refine the grid near the peak");
        }
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
    // Refine (θr, ωn², ζωn) by Levenberg–Marquardt on the angle model.
    AngleModel model(w, a, sr);
    Eigen::LevenbergMarquardt<AngleModel> lm(model);
    lm.setXtol(1e-15);
    lm.setFtol(1e-15);
    Eigen::VectorXd x(3);
    x << ar, 1.0, std::log(zw);
    lm.minimize(x);
    x(1) *= sr;
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
    e.frequencies_used_hz.assign(frf.frequency_hz.begin() + static_cast<long>(lo),
                                 frf.frequency_hz.begin() + static_cast<long>(hi) + 1);
    if (!(mean > 0.0) || !std::isfinite(mean)) {
        return failed_estimate(EstimateStatus::fit_failed, "non-positive circle-fit damping");
    }
    return e;
}

}  // namespace

ModalEstimate circle_fit(const Frf& frf, const CircleFitOptions& options) {
    RationalFractionOptions plain;
    plain.residual.compensate = false;
    return estimate_with_residual(
        frf, options.residual, [&options](const Frf& f) { return circle_fit_of(f, options); },
        [&plain](const Frf& f) { return rational_fraction_fit(f, plain); });
}

}  // namespace sb::identification

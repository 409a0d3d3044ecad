#include "correlation/scaling_law.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/significant_text.hpp"

namespace sb::correlation {
namespace {

constexpr double kMinExponent = -3.0;
constexpr double kMaxExponent = 3.0;

/// The weighted least-squares coefficient of Δ = c A^p and its χ².
ScalingFit fit_exponent(const std::vector<LevelResidual>& r, double p) {
    double sgg = 0.0;
    double sdg = 0.0;
    for (const auto& x : r) {
        const double g = std::pow(x.level, p) / x.sigma;
        sgg += g * g;
        sdg += g * x.residual / x.sigma;
    }
    ScalingFit fit;
    fit.exponent = p;
    fit.coefficient = sgg > 0.0 ? sdg / sgg : 0.0;
    for (const auto& x : r) {
        const double e = (x.residual - fit.coefficient * std::pow(x.level, p)) / x.sigma;
        fit.chi2 += e * e;
    }
    return fit;
}

/// The exponent of least χ²: a grid over the interval, then golden-section search around the
/// best grid point (χ²(p) is smooth; the grid keeps the search off a local minimum).
double best_exponent(const std::vector<LevelResidual>& r) {
    constexpr int kGrid = 121;
    double best = kMinExponent;
    double least = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kGrid; ++k) {
        const double p = kMinExponent + (kMaxExponent - kMinExponent) * k / (kGrid - 1);
        const double c = fit_exponent(r, p).chi2;
        if (c < least) {
            least = c;
            best = p;
        }
    }
    const double step = (kMaxExponent - kMinExponent) / (kGrid - 1);
    double a = std::max(kMinExponent, best - step);
    double b = std::min(kMaxExponent, best + step);
    const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int i = 0; i < 60; ++i) {
        const double x1 = b - golden * (b - a);
        const double x2 = a + golden * (b - a);
        if (fit_exponent(r, x1).chi2 < fit_exponent(r, x2).chi2) {
            b = x2;
        } else {
            a = x1;
        }
    }
    return 0.5 * (a + b);
}

/// Where χ²(p) rises by `rise` above its minimum at `p0`, walking towards `end`.
double crossing(const std::vector<LevelResidual>& r, double p0, double end, double rise) {
    const double target = fit_exponent(r, p0).chi2 + rise;
    if (fit_exponent(r, end).chi2 <= target) return end;
    double inside = p0;
    double outside = end;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (inside + outside);
        (fit_exponent(r, mid).chi2 > target ? outside : inside) = mid;
    }
    return 0.5 * (inside + outside);
}

}  // namespace

std::string scaling_shape_name(ScalingShape shape) {
    switch (shape) {
        case ScalingShape::none:
            return "none";
        case ScalingShape::constant:
            return "constant";
        case ScalingShape::linear:
            return "∝ A";
        case ScalingShape::inverse:
            return "∝ 1/A";
        case ScalingShape::quadratic:
            return "∝ A²";
        case ScalingShape::power:
            return "∝ A^χ";
    }
    return "?";
}

std::vector<ScalingFit> fit_scaling(const std::vector<LevelResidual>& residuals) {
    if (residuals.empty()) throw std::invalid_argument("fit_scaling: no level");
    for (const auto& r : residuals) {
        if (!(r.level > 0.0) || !std::isfinite(r.level)) {
            throw std::invalid_argument("fit_scaling: a level must be > 0");
        }
        if (!(r.sigma > 0.0) || !std::isfinite(r.sigma) || !std::isfinite(r.residual)) {
            throw std::invalid_argument(
                "fit_scaling: a residual and its sigma (> 0) must be finite");
        }
    }
    const double log_n = std::log(static_cast<double>(residuals.size()));
    std::vector<ScalingFit> fits;
    ScalingFit none;
    for (const auto& r : residuals) none.chi2 += std::pow(r.residual / r.sigma, 2);
    none.bic = none.chi2;
    fits.push_back(none);
    const std::pair<ScalingShape, double> fixed[] = {{ScalingShape::constant, 0.0},
                                                     {ScalingShape::linear, 1.0},
                                                     {ScalingShape::inverse, -1.0},
                                                     {ScalingShape::quadratic, 2.0}};
    for (const auto& [shape, p] : fixed) {
        ScalingFit fit = fit_exponent(residuals, p);
        fit.shape = shape;
        fit.parameters = 1;
        fit.bic = fit.chi2 + log_n;
        fits.push_back(fit);
    }
    // A free exponent needs at least three levels to say more than a fixed one.
    if (residuals.size() >= 3) {
        ScalingFit fit = fit_exponent(residuals, best_exponent(residuals));
        fit.shape = ScalingShape::power;
        fit.parameters = 2;
        fit.bic = fit.chi2 + 2.0 * log_n;
        fit.exponent_lo = crossing(residuals, fit.exponent, kMinExponent, 1.0);
        fit.exponent_hi = crossing(residuals, fit.exponent, kMaxExponent, 1.0);
        fits.push_back(fit);
    }
    std::stable_sort(fits.begin(), fits.end(),
                     [](const ScalingFit& a, const ScalingFit& b) { return a.bic < b.bic; });
    return fits;
}

std::string describe_scaling(const ScalingFit& fit) {
    switch (fit.shape) {
        case ScalingShape::none:
            return "is within the noise at every level";
        case ScalingShape::constant:
            return "is the same at every level (" + significant_text(fit.coefficient, 3) + ")";
        case ScalingShape::linear:
            return "grows in proportion to the level (" + significant_text(fit.coefficient, 3) +
                   " A)";
        case ScalingShape::inverse:
            return "falls as the level rises (" + significant_text(fit.coefficient, 3) + " / A)";
        case ScalingShape::quadratic:
            return "grows with the square of the level (" + significant_text(fit.coefficient, 3) +
                   " A²)";
        case ScalingShape::power:
            return "varies like A^" + significant_text(fit.exponent, 3) + " (" +
                   significant_text(fit.exponent_lo, 3) + " to " +
                   significant_text(fit.exponent_hi, 3) + ", 68 %)";
    }
    return "";
}

}  // namespace sb::correlation

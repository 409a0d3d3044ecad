#include "correlation/two_fidelity.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "correlation/emulator.hpp"
#include "correlation/gaussian_process.hpp"
#include "correlation/space_filling.hpp"

namespace sb::correlation {
namespace {

/// The discrepancy coupled − predicted of each feature over the unit cube (Kennedy and
/// O'Hagan 2001, §4.3): a Gaussian process on the coupled points' differences from the
/// prediction's emulated mean, its nugget the coupled values' own scatter (their fillings),
/// so it passes through deterministic coupled values and smooths a DEM's jitter. It carries
/// the slopes where the coupled points resolve them (a stencil's central differences) and
/// tends to their mean away from them. With fewer than 3 coupled points: their mean.
struct Discrepancy {
    std::vector<std::optional<GaussianProcess>> process;
    std::vector<double> constant;
    std::vector<double> sigma;  ///< the coupled values' scatter

    [[nodiscard]] double at(std::size_t feature, const std::vector<double>& u) const {
        if (!process[feature]) return constant[feature];
        return process[feature]
            ->predict(
                Eigen::Map<const Eigen::VectorXd>(u.data(), static_cast<Eigen::Index>(u.size())))
            .mean;
    }
};

Discrepancy fit_discrepancy(const FeatureEmulator& low, std::size_t features,
                            const std::vector<FreeParameter>& free,
                            const std::vector<Evaluation>& high_points) {
    const auto d = static_cast<Eigen::Index>(free.size());
    Discrepancy delta;
    delta.process.resize(features);
    delta.constant.assign(features, 0.0);
    delta.sigma.assign(features, 0.0);
    // Per distinct coupled point: its unit-cube place and the prediction's emulated mean.
    struct Point {
        std::vector<double> u;
        std::vector<double> low_mean;
        const Evaluation* high;
    };
    std::vector<Point> points;
    for (const auto& e : high_points) {
        if (!e.error.empty() || e.simulated.value.size() != features) continue;
        const bool seen = std::any_of(points.begin(), points.end(),
                                      [&](const Point& p) { return p.high->key == e.key; });
        if (seen) continue;
        Point p{to_unit(free, e.values), {}, &e};
        std::vector<double> variance;
        low.predict(p.u, p.low_mean, variance);
        points.push_back(std::move(p));
    }
    for (std::size_t i = 0; i < features; ++i) {
        std::vector<const Point*> used;
        double sigma2 = 0.0;
        for (const auto& p : points) {
            if (std::isfinite(p.high->simulated.value[i]) && std::isfinite(p.low_mean[i])) {
                used.push_back(&p);
                sigma2 += std::pow(p.high->simulated.sigma[i], 2);
            }
        }
        if (used.empty()) continue;
        const auto n = static_cast<Eigen::Index>(used.size());
        delta.sigma[i] = std::sqrt(sigma2 / static_cast<double>(n));
        Eigen::MatrixXd x(n, d);
        Eigen::VectorXd y(n);
        for (Eigen::Index k = 0; k < n; ++k) {
            const Point& p = *used[static_cast<std::size_t>(k)];
            for (Eigen::Index j = 0; j < d; ++j) x(k, j) = p.u[static_cast<std::size_t>(j)];
            y(k) = p.high->simulated.value[i] - p.low_mean[i];
        }
        delta.constant[i] = y.mean();
        if (n < 3) continue;
        const double spread = (y.array() - y.mean()).square().sum() / static_cast<double>(n - 1);
        if (spread <= 0.0) continue;  // a constant discrepancy
        GpFitOptions options;
        // The nugget is the coupled values' known scatter (standardised), not fitted: a few
        // points cannot tell it from the signal.
        options.noise_variance = std::clamp(sigma2 / static_cast<double>(n) / spread, 1e-8,
                                            GaussianProcess::kMaxNoiseVariance);
        try {
            delta.process[i] = GaussianProcess::fit(x, y, options);
        } catch (const std::exception&) {
            // the mean then stands for it
        }
    }
    return delta;
}

/// The low fidelity's evaluations with the discrepancy added at each one's point, compared
/// again: its uncertainty is that of the low fidelity's value and of the coupled means the
/// discrepancy rests on.
std::vector<Evaluation> corrected(const Evaluator& low, const std::vector<Evaluation>& history,
                                  const Discrepancy& delta) {
    std::vector<Evaluation> out;
    for (const auto& e : history) {
        if (!e.error.empty() || e.simulated.value.size() != delta.constant.size()) continue;
        Evaluation c = e;
        const auto u = to_unit(low.free(), e.values);
        for (std::size_t i = 0; i < delta.constant.size(); ++i) {
            c.simulated.value[i] += delta.at(i, u);
            c.simulated.sigma[i] = std::hypot(c.simulated.sigma[i], delta.sigma[i]);
        }
        low.compare(c);
        out.push_back(std::move(c));
    }
    return out;
}

std::vector<std::vector<double>> stencil(const std::vector<FreeParameter>& free,
                                         const std::vector<double>& u) {
    std::vector<std::vector<double>> points{to_values(free, u)};
    for (const auto& v : axis_stencil(u, kTwoFidelityStep)) points.push_back(to_values(free, v));
    return points;
}

}  // namespace

TwoFidelityOutcome two_fidelity_search(Evaluator& low, Evaluator& high,
                                       const SearchOptions& options) {
    TwoFidelityOutcome out;
    out.low_search = search(low, options);
    const auto& free = low.free();
    auto u = least_emulated_misfit(FeatureEmulator(low.measurement(), free, low.history()), free,
                                   to_unit(free, out.low_search.best_values));
    out.corrected_history = low.history();
    out.stopped = "no correction";
    // The first correction simulates a whole stencil (the discrepancy's slopes); a later one
    // only its new centre when that lies within reach of the points so far, else a new stencil.
    auto batch = stencil(free, u);
    for (int k = 0; k < kTwoFidelityCorrections; ++k) {
        // The low fidelity at the same points too: its emulator, which the corrected one
        // rests on, is then as well resolved around the answer as the coupled points are.
        high.evaluate(batch);
        low.evaluate(batch);
        ++out.corrections;
        const FeatureEmulator low_emulator(low.measurement(), free, low.history());
        const Discrepancy delta =
            fit_discrepancy(low_emulator, low.measurement().features.size(), free, high.history());
        out.corrected_history = corrected(low, low.history(), delta);
        const FeatureEmulator corrected_emulator(low.measurement(), free, out.corrected_history);
        const auto next = least_emulated_misfit(corrected_emulator, free, u);
        double moved = 0.0;
        for (std::size_t j = 0; j < u.size(); ++j)
            moved = std::max(moved, std::abs(next[j] - u[j]));
        u = next;
        std::ostringstream why;
        why << "the last correction moved the answer by " << moved << " of the intervals";
        if (moved <= kTwoFidelityConverged) {
            out.stopped = why.str() + ", converged";
            break;
        }
        out.stopped = why.str() + " after " + std::to_string(out.corrections) +
                      " corrections, the most allowed";
        batch = moved <= 2.0 * kTwoFidelityStep
                    ? std::vector<std::vector<double>>{to_values(free, u)}
                    : stencil(free, u);
    }
    out.best_values = to_values(free, u);
    return out;
}

}  // namespace sb::correlation

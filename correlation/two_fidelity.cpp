#include "correlation/two_fidelity.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "correlation/emulator.hpp"

namespace sb::correlation {
namespace {

/// Distance in the unit cube over which a coupled point informs the discrepancy's slopes: its
/// weight exp(-½ (r / scale)²) [-]. Two stencil steps: a stencil around an earlier centre
/// still counts when the answer moved little, hardly when it moved far.
constexpr double kDiscrepancyScale = 2.0 * kTwoFidelityStep;

/// The discrepancy high − low of each feature as an affine function of the unit-cube point,
/// c + g·(u − centre): c the discrepancy at the centre, g fitted by weighted least squares to
/// the other coupled points (none where they do not span every direction), and the scatter
/// of the coupled means it carries.
struct Discrepancy {
    std::vector<double> constant;
    std::vector<Eigen::VectorXd> slope;
    std::vector<double> sigma;
    std::vector<double> centre;

    [[nodiscard]] double at(std::size_t feature, const std::vector<double>& u) const {
        double v = constant[feature];
        for (std::size_t j = 0; j < centre.size(); ++j) {
            v += slope[feature](static_cast<Eigen::Index>(j)) * (u[j] - centre[j]);
        }
        return v;
    }
};

Discrepancy fit_discrepancy(const FeatureEmulator& low, std::size_t features,
                            const std::vector<FreeParameter>& free,
                            const std::vector<Evaluation>& high_points,
                            const std::vector<double>& centre) {
    const auto d = static_cast<Eigen::Index>(free.size());
    Discrepancy delta;
    delta.centre = centre;
    delta.constant.assign(features, 0.0);
    delta.slope.assign(features, Eigen::VectorXd::Zero(d));
    delta.sigma.assign(features, 0.0);
    // Per coupled point: its unit-cube place, weight and the low fidelity's emulated mean.
    struct Point {
        std::vector<double> u;
        double weight;
        std::vector<double> low_mean;
        const Evaluation* high;
    };
    std::vector<Point> points;
    for (const auto& e : high_points) {
        if (!e.error.empty() || e.simulated.value.size() != features) continue;
        Point p{to_unit(free, e.values), 0.0, {}, &e};
        double r2 = 0.0;
        for (Eigen::Index j = 0; j < d; ++j) r2 += std::pow(p.u[j] - centre[j], 2);
        p.weight = std::exp(-0.5 * r2 / (kDiscrepancyScale * kDiscrepancyScale));
        std::vector<double> variance;
        low.predict(p.u, p.low_mean, variance);
        points.push_back(std::move(p));
    }
    for (std::size_t i = 0; i < features; ++i) {
        std::vector<const Point*> used;
        for (const auto& p : points) {
            if (std::isfinite(p.high->simulated.value[i]) && std::isfinite(p.low_mean[i])) {
                used.push_back(&p);
            }
        }
        if (used.empty()) continue;
        double sigma2 = 0.0;
        double weights = 0.0;
        for (const Point* p : used) {
            sigma2 += p->weight * std::pow(p->high->simulated.sigma[i], 2);
            weights += p->weight;
        }
        delta.sigma[i] = weights > 0.0 ? std::sqrt(sigma2 / weights) : 0.0;
        // Through the coupled value at the centre when it was simulated (the corrected model
        // then equals the coupled one there: zeroth-order consistency), else a weighted mean.
        const Point* at_centre = nullptr;
        for (const Point* p : used) {
            double r2 = 0.0;
            for (Eigen::Index j = 0; j < d; ++j) r2 += std::pow(p->u[j] - centre[j], 2);
            if (r2 < 1e-18) at_centre = p;
        }
        double sum = 0.0;
        double wsum = 0.0;
        for (const Point* p : used) {
            sum += p->weight * (p->high->simulated.value[i] - p->low_mean[i]);
            wsum += p->weight;
        }
        delta.constant[i] = at_centre != nullptr
                                ? at_centre->high->simulated.value[i] - at_centre->low_mean[i]
                                : sum / wsum;
        // The slopes by weighted least squares on the other points (first-order consistency:
        // central differences over a stencil); none when they do not span every direction.
        std::vector<const Point*> others;
        for (const Point* p : used) {
            if (p != at_centre) others.push_back(p);
        }
        const auto n = static_cast<Eigen::Index>(others.size());
        if (n < d) continue;
        Eigen::MatrixXd a(n, d);
        Eigen::VectorXd b(n);
        for (Eigen::Index k = 0; k < n; ++k) {
            const Point& p = *others[static_cast<std::size_t>(k)];
            const double w = std::sqrt(p.weight);
            for (Eigen::Index j = 0; j < d; ++j) a(k, j) = w * (p.u[j] - centre[j]);
            b(k) = w * (p.high->simulated.value[i] - p.low_mean[i] - delta.constant[i]);
        }
        Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
        qr.setThreshold(1e-6);
        if (qr.rank() == d) delta.slope[i] = qr.solve(b);
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
    for (std::size_t j = 0; j < u.size(); ++j) {
        for (const double sign : {-1.0, 1.0}) {
            auto v = u;
            v[j] = std::clamp(u[j] + sign * kTwoFidelityStep, 0.0, 1.0);
            if (v != u) points.push_back(to_values(free, v));
        }
    }
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
        const Discrepancy delta = fit_discrepancy(low_emulator, low.measurement().features.size(),
                                                  free, high.history(), u);
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

#include "correlation/identifiability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlopt.hpp>
#include <utility>

#include "correlation/space_filling.hpp"

namespace sb::correlation {
namespace {

constexpr int kInnerCandidates = 32;
constexpr double kStep = 0.02;  ///< central difference of the emulator mean, unit cube

std::string text(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.4g", v);
    return buffer;
}

std::size_t level_of(const Measurement& m, const Feature& f) {
    for (std::size_t s = 0; s < m.selection.sweeps.size(); ++s) {
        const auto& sweep = m.selection.sweeps[s];
        if (sweep.arrangement == f.arrangement &&
            std::abs(sweep.level_g - f.level_g) <= 1e-9 * std::max(1.0, f.level_g)) {
            return s;
        }
    }
    return 0;
}

/// The profile misfit at u_j = t: the least emulated misfit over the other coordinates.
struct ProfileSearch {
    const FeatureEmulator* emulator;
    int j;
    int d;
    const std::vector<std::vector<double>>& inner;

    [[nodiscard]] std::vector<double> point(double t, const std::vector<double>& others) const {
        std::vector<double> u(static_cast<std::size_t>(d));
        for (int i = 0, k = 0; i < d; ++i) u[i] = i == j ? t : others[k++];
        return u;
    }

    /// `warm` (the others' coordinates) is where the local search starts and is left at the
    /// minimum found; the best point's others and a space-filling set are tried as starts.
    double at(double t, std::vector<double>& warm, const std::vector<double>& at_best) const {
        if (d == 1) return emulator->misfit({t});
        std::vector<double> start = warm;
        double least = emulator->misfit(point(t, warm));
        for (const auto* candidate : {&at_best}) {
            const double m = emulator->misfit(point(t, *candidate));
            if (m < least) {
                least = m;
                start = *candidate;
            }
        }
        for (const auto& z : inner) {
            const double m = emulator->misfit(point(t, z));
            if (m < least) {
                least = m;
                start = z;
            }
        }
        struct Data {
            const ProfileSearch* search;
            double t;
        } data{this, t};
        nlopt::opt opt(d - 1 >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_COBYLA,
                       static_cast<unsigned>(d - 1));
        opt.set_lower_bounds(std::vector<double>(static_cast<std::size_t>(d - 1), 0.0));
        opt.set_upper_bounds(std::vector<double>(static_cast<std::size_t>(d - 1), 1.0));
        opt.set_min_objective(
            [](const std::vector<double>& others, std::vector<double>& /*gradient*/, void* p) {
                const auto* dd = static_cast<const Data*>(p);
                return dd->search->emulator->misfit(dd->search->point(dd->t, others));
            },
            &data);
        opt.set_maxeval(300);
        opt.set_xtol_abs(1e-6);
        opt.set_initial_step(0.01);
        std::vector<double> x = start;
        double value = least;
        try {
            opt.optimize(x, value);
        } catch (const std::exception&) {
            // keep the best start
        }
        if (value < least) {
            least = value;
            start = x;
        }
        warm = start;
        return least;
    }
};

}  // namespace

std::vector<ParameterFinding> assess_identifiability(const FeatureEmulator& emulator,
                                                     const Measurement& measurement,
                                                     const std::vector<FreeParameter>& free,
                                                     const std::vector<double>& best_u) {
    const int d = static_cast<int>(free.size());
    const auto inner = d > 1 ? halton(kInnerCandidates, d - 1) : std::vector<std::vector<double>>{};
    const auto best_values = to_values(free, best_u);

    // Sensitivities of the residuals at the best point (the emulator's mean, so the seed
    // scatter does not enter): J_kj = ∂r_k/∂u_j.
    const std::size_t features = measurement.features.size();
    std::vector<std::vector<double>> jacobian(features, std::vector<double>(free.size()));
    for (int j = 0; j < d; ++j) {
        auto up = best_u;
        auto down = best_u;
        up[j] = std::min(1.0, best_u[j] + kStep);
        down[j] = std::max(0.0, best_u[j] - kStep);
        const auto r_up = emulator.residuals(up);
        const auto r_down = emulator.residuals(down);
        for (std::size_t k = 0; k < features; ++k) {
            jacobian[k][j] = (r_up[k] - r_down[k]) / (up[j] - down[j]);
        }
    }

    std::vector<ParameterFinding> findings;
    for (int j = 0; j < d; ++j) {
        ParameterFinding f;
        f.parameter = free[j];
        f.value = best_values[j];
        // Profile: from the best value outwards in steps that double, each value's least
        // misfit over the others (a local search warm-started from the previous value's),
        // until the misfit rises kProfileThreshold above its minimum; the crossing is then
        // bisected. A well-identified value has a valley far narrower than any fixed grid.
        ProfileSearch search{&emulator, j, d, inner};
        std::vector<double> others_at_best;
        for (int i = 0; i < d; ++i) {
            if (i != j) others_at_best.push_back(best_u[i]);
        }
        auto warm = others_at_best;
        double minimum = search.at(best_u[j], warm, others_at_best);
        std::vector<std::pair<double, double>> points{{best_u[j], minimum}};
        double ends[2] = {0.0, 1.0};
        for (int side = 0; side < 2; ++side) {
            const double sign = side == 0 ? -1.0 : 1.0;
            double inside = best_u[j];
            warm = others_at_best;
            double step = 1e-4;
            ends[side] = side == 0 ? 0.0 : 1.0;
            while (true) {
                const double t = std::clamp(best_u[j] + sign * step, 0.0, 1.0);
                const double m = search.at(t, warm, others_at_best);
                points.emplace_back(t, m);
                minimum = std::min(minimum, m);
                if (m > minimum + kProfileThreshold) {
                    double a = inside;
                    double b = t;
                    auto w = warm;
                    for (int k = 0; k < 14; ++k) {
                        const double mid = 0.5 * (a + b);
                        (search.at(mid, w, others_at_best) > minimum + kProfileThreshold ? b : a) =
                            mid;
                    }
                    ends[side] = 0.5 * (a + b);
                    break;
                }
                if (t <= 0.0 || t >= 1.0) break;
                inside = t;
                step *= 2.0;
            }
        }
        std::sort(points.begin(), points.end());
        for (const auto& [t, m] : points) {
            f.profile.values.push_back(free[j].value_at(t));
            f.profile.misfit.push_back(m);
        }
        f.lo95 = free[j].value_at(ends[0]);
        f.hi95 = free[j].value_at(ends[1]);
        // The share of the search interval, in the coordinates it was searched in.
        const double share = ends[1] - ends[0];
        // An interval that reaches an end of the search interval is a bound, not a value: the
        // data do not exclude that end (nor, perhaps, what lies beyond it).
        const bool at_an_end = ends[0] <= kAtAnEnd || ends[1] >= 1.0 - kAtAnEnd;
        const double value = free[j].value_at(best_u[j]);
        const double relative = value != 0.0 ? 0.5 * (f.hi95 - f.lo95) / std::abs(value)
                                             : std::numeric_limits<double>::infinity();
        f.identifiable =
            share <= kIdentifiableShare && !at_an_end && relative <= kIdentifiableRelative;
        if (f.identifiable) {
            f.reason = "the data confine it to [" + text(f.lo95) + ", " + text(f.hi95) +
                       "] (95 %), " + text(100.0 * share) + " % of its search interval";
        } else if (share <= kIdentifiableShare && !at_an_end) {
            f.reason = "the data only loosely bound it: values from " + text(f.lo95) + " to " +
                       text(f.hi95) + " fit within the uncertainty, ±" + text(100.0 * relative) +
                       " % about " + text(value) + " (more than ±" +
                       text(100.0 * kIdentifiableRelative) + " %), so no value is given";
        } else if (share <= kIdentifiableShare) {
            f.reason = "the data only bound it: values from " + text(f.lo95) + " to " +
                       text(f.hi95) + " fit within the uncertainty, and the interval reaches " +
                       (ends[0] <= kAtAnEnd ? "the lower" : "the upper") +
                       " end of its search interval, so no value is given";
        } else {
            f.reason = "the data cannot identify it: values from " + text(f.lo95) + " to " +
                       text(f.hi95) + " (" + text(100.0 * share) +
                       " % of its search interval) fit as well within the uncertainty";
        }

        // Which levels inform it: the Fisher information J_kj² split by level.
        f.information_share.assign(measurement.selection.sweeps.size(), 0.0);
        double total = 0.0;
        for (std::size_t k = 0; k < features; ++k) {
            const double info = jacobian[k][j] * jacobian[k][j];
            f.information_share[level_of(measurement, measurement.features[k])] += info;
            total += info;
        }
        // Information below 1 means a standard deviation beyond the whole search interval
        // (σ_u = 1/sqrt(F) in the unit cube): no level informs it, all shares are 0.
        for (auto& s : f.information_share) s = total >= 1.0 ? s / total : 0.0;
        findings.push_back(f);
    }
    return findings;
}

}  // namespace sb::correlation

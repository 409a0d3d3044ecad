#include "correlation/identifiability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "correlation/space_filling.hpp"

namespace sb::correlation {
namespace {

constexpr int kProfilePoints = 41;
constexpr int kInnerCandidates = 96;
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
        // Profile: for each value of u_j the least misfit over the others, searched on a
        // space-filling set and at the best point's other coordinates.
        for (int p = 0; p < kProfilePoints; ++p) {
            const double uj = static_cast<double>(p) / (kProfilePoints - 1);
            auto u = best_u;
            u[j] = uj;
            double least = emulator.misfit(u);
            for (const auto& z : inner) {
                std::vector<double> v(d);
                for (int i = 0, k = 0; i < d; ++i) v[i] = i == j ? uj : z[k++];
                least = std::min(least, emulator.misfit(v));
            }
            f.profile.values.push_back(free[j].lo + uj * (free[j].hi - free[j].lo));
            f.profile.misfit.push_back(least);
        }
        const double minimum = *std::min_element(f.profile.misfit.begin(), f.profile.misfit.end());
        f.lo95 = std::numeric_limits<double>::infinity();
        f.hi95 = -std::numeric_limits<double>::infinity();
        for (int p = 0; p < kProfilePoints; ++p) {
            if (f.profile.misfit[p] - minimum <= kProfileThreshold) {
                f.lo95 = std::min(f.lo95, f.profile.values[p]);
                f.hi95 = std::max(f.hi95, f.profile.values[p]);
            }
        }
        const double width = free[j].hi - free[j].lo;
        const double share = (f.hi95 - f.lo95) / width;
        f.identifiable = share <= kIdentifiableShare;
        f.reason = f.identifiable
                       ? "the data confine it to [" + text(f.lo95) + ", " + text(f.hi95) +
                             "] (95 %), " + text(100.0 * share) + " % of its search interval"
                       : "the data cannot identify it: values from " + text(f.lo95) + " to " +
                             text(f.hi95) + " (" + text(100.0 * share) +
                             " % of its search interval) fit as well within the uncertainty";

        // Which levels inform it: the Fisher information J_kj² split by level.
        f.information_share.assign(measurement.selection.sweeps.size(), 0.0);
        double total = 0.0;
        for (std::size_t k = 0; k < features; ++k) {
            const double info = jacobian[k][j] * jacobian[k][j];
            f.information_share[level_of(measurement, measurement.features[k])] += info;
            total += info;
        }
        for (auto& s : f.information_share) s = total > 1e-12 ? s / total : 0.0;
        findings.push_back(f);
    }
    return findings;
}

}  // namespace sb::correlation

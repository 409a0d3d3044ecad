#include "correlation/mismatch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/significant_text.hpp"
#include "identification/damping_curve.hpp"

namespace sb::correlation {
namespace {

constexpr double kMissingFeature = std::numeric_limits<double>::quiet_NaN();

std::size_t index(LevelFeature f) { return static_cast<std::size_t>(f); }

/// One filling's features at one level.
std::array<double, kLevelFeatures> filling_values(const identification::Recording& recording,
                                                  const identification::LevelIdentification& l) {
    std::array<double, kLevelFeatures> v;
    v.fill(kMissingFeature);
    const auto& estimate = l.circle_fit.ok() ? l.circle_fit : l.half_power;
    if (estimate.ok()) {
        v[index(LevelFeature::natural_frequency)] = estimate.natural_frequency_hz;
        v[index(LevelFeature::damping_ratio)] = estimate.damping_ratio;
    }
    if (l.frf.value.empty()) return v;
    std::size_t peak = 0;
    for (std::size_t k = 1; k < l.frf.value.size(); ++k) {
        if (std::abs(l.frf.value[k]) > std::abs(l.frf.value[peak])) peak = k;
    }
    v[index(LevelFeature::peak_magnitude)] = std::abs(l.frf.value[peak]);
    v[index(LevelFeature::peak_phase)] = std::arg(l.frf.value[peak]);
    const double f = l.frf.frequency_hz[peak];
    const auto response = recording.channel_index(l.channel);
    const auto reference = recording.reference_index();
    // The point at the peak (the first of its repeats): its harmonics and its drive.
    for (const auto& p : recording.points) {
        if (p.arrangement != l.arrangement || !same_level(p.level_g, l.level_g) ||
            p.filling != l.filling || std::abs(p.frequency_hz - f) > 1e-9 * f) {
            continue;
        }
        if (response < p.values.size()) {
            v[index(LevelFeature::h2_ratio)] = p.values[response].h2_ratio;
            v[index(LevelFeature::h3_ratio)] = p.values[response].h3_ratio;
        }
        if (reference < p.values.size()) {
            v[index(LevelFeature::drive)] = std::abs(p.values[reference].amplitude);
        }
        break;
    }
    return v;
}

double stated_sigma(LevelFeature f, double value, const StatedUncertainty& stated) {
    switch (f) {
        case LevelFeature::natural_frequency:
            return stated.frequency_relative * std::abs(value);
        case LevelFeature::damping_ratio:
            return stated.damping_relative * std::abs(value);
        case LevelFeature::peak_magnitude:
        case LevelFeature::drive:
            return stated.frf_relative * std::abs(value);
        case LevelFeature::peak_phase:
            return stated.frf_relative;
        case LevelFeature::h2_ratio:
        case LevelFeature::h3_ratio:
            return std::max(kHarmonicFloor, stated.frf_relative * std::abs(value));
    }
    return 0.0;
}

std::string level_list(const std::vector<double>& levels) {
    std::string out;
    for (std::size_t i = 0; i < levels.size(); ++i) {
        out += (i == 0                   ? ""
                : i + 1 == levels.size() ? " and "
                                         : ", ") +
               significant_text(levels[i], 3);
    }
    return out + " g";
}

}  // namespace

std::string level_feature_name(LevelFeature feature) {
    switch (feature) {
        case LevelFeature::natural_frequency:
            return "natural frequency";
        case LevelFeature::damping_ratio:
            return "damping ratio";
        case LevelFeature::peak_magnitude:
            return "peak |H|";
        case LevelFeature::peak_phase:
            return "phase at the peak";
        case LevelFeature::h2_ratio:
            return "H2/H1";
        case LevelFeature::h3_ratio:
            return "H3/H1";
        case LevelFeature::drive:
            return "drive at the peak";
    }
    return "?";
}

std::vector<LevelFeatureValues> level_feature_values(const identification::Recording& recording,
                                                     const StatedUncertainty& stated) {
    const auto levels = identification::identify_recording(recording);
    std::vector<LevelFeatureValues> out;
    std::vector<std::vector<std::array<double, kLevelFeatures>>> per_filling;
    for (const auto& l : levels) {
        auto it = std::find_if(out.begin(), out.end(), [&](const LevelFeatureValues& v) {
            return v.arrangement == l.arrangement && same_level(v.level_g, l.level_g);
        });
        if (it == out.end()) {
            out.push_back({l.arrangement, l.level_g, 0, {}, {}});
            per_filling.emplace_back();
            it = out.end() - 1;
        }
        per_filling[static_cast<std::size_t>(it - out.begin())].push_back(
            filling_values(recording, l));
    }
    for (std::size_t k = 0; k < out.size(); ++k) {
        out[k].fillings = static_cast<int>(per_filling[k].size());
        for (std::size_t f = 0; f < kLevelFeatures; ++f) {
            std::vector<double> xs;
            for (const auto& values : per_filling[k]) {
                if (std::isfinite(values[f])) xs.push_back(values[f]);
            }
            if (xs.empty()) {
                out[k].value[f] = kMissingFeature;
                out[k].sigma[f] = kMissingFeature;
                continue;
            }
            double mean = 0.0;
            for (double x : xs) mean += x;
            mean /= static_cast<double>(xs.size());
            double scatter = 0.0;
            if (xs.size() > 1) {
                double s = 0.0;
                for (double x : xs) s += (x - mean) * (x - mean);
                scatter = std::sqrt(s / static_cast<double>(xs.size() - 1) /
                                    static_cast<double>(xs.size()));
            }
            out[k].value[f] = mean;
            out[k].sigma[f] =
                std::max(scatter, stated_sigma(static_cast<LevelFeature>(f), mean, stated));
        }
    }
    return out;
}

double chi2_quantile(double p, int dof) {
    // The standard normal quantile by bisection on its distribution function.
    double lo = -10.0;
    double hi = 10.0;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
    }
    const double z = 0.5 * (lo + hi);
    const double k = static_cast<double>(dof);
    const double a = 2.0 / (9.0 * k);
    return k * std::pow(1.0 - a + z * std::sqrt(a), 3);
}

std::vector<FeatureMismatch> locate_mismatch(const std::vector<LevelFeatureValues>& measured,
                                             const std::vector<LevelFeatureValues>& simulated) {
    std::vector<std::string> arrangements;
    for (const auto& m : measured) {
        if (std::find(arrangements.begin(), arrangements.end(), m.arrangement) ==
            arrangements.end()) {
            arrangements.push_back(m.arrangement);
        }
    }
    std::vector<FeatureMismatch> out;
    for (const auto& arrangement : arrangements) {
        for (std::size_t f = 0; f < kLevelFeatures; ++f) {
            FeatureMismatch fm;
            fm.arrangement = arrangement;
            fm.feature = static_cast<LevelFeature>(f);
            for (const auto& m : measured) {
                if (m.arrangement != arrangement) continue;
                const auto s = std::find_if(
                    simulated.begin(), simulated.end(), [&](const LevelFeatureValues& v) {
                        return v.arrangement == arrangement && same_level(v.level_g, m.level_g);
                    });
                if (s == simulated.end() || !std::isfinite(m.value[f]) ||
                    !std::isfinite(s->value[f])) {
                    continue;
                }
                double delta = m.value[f] - s->value[f];
                if (fm.feature == LevelFeature::peak_phase) {
                    delta = std::remainder(delta, 2.0 * M_PI);
                }
                const double sigma = std::hypot(m.sigma[f], s->sigma[f]);
                if (!(sigma > 0.0)) continue;
                fm.residuals.push_back({m.level_g, delta, sigma});
                fm.chi2 += std::pow(delta / sigma, 2);
                if (std::abs(delta / sigma) > kLevelBeyond) fm.levels_beyond.push_back(m.level_g);
            }
            if (fm.residuals.empty()) continue;
            const int n = static_cast<int>(fm.residuals.size());
            fm.beyond_noise = fm.chi2 > chi2_quantile(0.99, n);
            fm.scaling = fit_scaling(fm.residuals);
            std::ostringstream s;
            s << arrangement << ": the " << level_feature_name(fm.feature);
            if (!fm.beyond_noise) {
                s << " agrees within the noise at its " << n << " level(s) (χ² "
                  << significant_text(fm.chi2, 3) << " for " << n << ")";
            } else {
                s << " disagrees beyond the noise (χ² " << significant_text(fm.chi2, 3) << " for "
                  << n << " levels";
                if (!fm.levels_beyond.empty()) {
                    s << "; beyond 3 σ at " << level_list(fm.levels_beyond);
                }
                s << "); measured − simulated " << describe_scaling(fm.scaling.front());
            }
            fm.sentence = s.str();
            out.push_back(std::move(fm));
        }
    }
    std::stable_sort(out.begin(), out.end(),
                     [](const FeatureMismatch& a, const FeatureMismatch& b) {
                         if (a.beyond_noise != b.beyond_noise) return a.beyond_noise;
                         return a.beyond_noise && a.chi2 > b.chi2;
                     });
    return out;
}

}  // namespace sb::correlation

#include "correlation/band_residuals.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "correlation/report_text.hpp"

namespace sb::correlation {
namespace {

constexpr double kNoiseProbability = 0.01;

/// What governs the FRF in a band, for the report's sentence.
const char* governed_by(FrfBand band) {
    switch (band) {
        case FrfBand::below:
            return "where the stiffness governs the FRF";
        case FrfBand::resonance:
            return "where the damping governs it";
        case FrfBand::above:
            return "where the mass governs it";
    }
    return "";
}

/// "6.2 % above" or "3.1 % below": measured |H| against the simulation's, from the mean
/// log ratio.
std::string above_or_below(double log_ratio) {
    const double percent = 100.0 * (std::exp(log_ratio) - 1.0);
    return num(std::abs(percent), 2) + (percent >= 0.0 ? " % above" : " % below");
}

}  // namespace

std::string frf_band_name(FrfBand band) {
    switch (band) {
        case FrfBand::below:
            return "below the resonance";
        case FrfBand::resonance:
            return "around the resonance";
        case FrfBand::above:
            return "above the resonance";
    }
    return "";
}

std::vector<BandResidual> band_residuals(const Measurement& measurement,
                                         const SimulatedFeatures& simulated,
                                         const std::vector<LevelFeatureValues>& measured_levels) {
    const auto& features = measurement.features;
    std::vector<BandResidual> out;
    const auto fn_index = static_cast<std::size_t>(LevelFeature::natural_frequency);
    const auto zeta_index = static_cast<std::size_t>(LevelFeature::damping_ratio);
    for (const auto& level : measured_levels) {
        const double fn = level.value[fn_index];
        const double zeta = level.value[zeta_index];
        if (!std::isfinite(fn) || !std::isfinite(zeta) || !(fn > 0.0) || !(zeta > 0.0)) continue;
        BandResidual bands[3];
        for (int b = 0; b < 3; ++b) {
            bands[b].arrangement = level.arrangement;
            bands[b].level_g = level.level_g;
            bands[b].band = static_cast<FrfBand>(b);
        }
        for (std::size_t i = 0; i < features.size() && i < simulated.value.size(); ++i) {
            const auto& f = features[i];
            if (f.arrangement != level.arrangement || !same_level(f.level_g, level.level_g)) {
                continue;
            }
            if (f.kind != FeatureKind::log_magnitude && f.kind != FeatureKind::phase) continue;
            const double s = simulated.value[i];
            if (!std::isfinite(s) || !(f.sigma > 0.0)) continue;
            const FrfBand band = f.frequency_hz < fn * (1.0 - zeta)   ? FrfBand::below
                                 : f.frequency_hz > fn * (1.0 + zeta) ? FrfBand::above
                                                                      : FrfBand::resonance;
            BandResidual& r = bands[static_cast<int>(band)];
            double delta = f.value - s;
            if (f.kind == FeatureKind::phase) {
                delta = std::remainder(delta, 2.0 * M_PI);
                r.chi2_phase += std::pow(delta / f.sigma, 2);
                r.mean_phase_rad += delta;
            } else {
                r.chi2_magnitude += std::pow(delta / f.sigma, 2);
                r.mean_log_ratio += delta;
                ++r.points;
            }
        }
        for (auto& r : bands) {
            if (r.points == 0) continue;
            r.mean_log_ratio /= r.points;
            r.mean_phase_rad /= r.points;
            out.push_back(r);
        }
    }
    const int compared = static_cast<int>(out.size());
    for (auto& r : out) {
        const double chi2 = r.chi2_magnitude + r.chi2_phase;
        const int dof = 2 * r.points;
        r.beyond_noise = chi2 > chi2_quantile(1.0 - kNoiseProbability / compared, dof);
        std::ostringstream s;
        s << r.arrangement << " " << num(r.level_g, 3) << " g, " << frf_band_name(r.band) << " ("
          << governed_by(r.band) << "): ";
        if (!r.beyond_noise) {
            s << "the FRF agrees within the noise (χ² " << num(chi2, 3) << " for " << dof
              << " values at " << r.points << " frequencies)";
        } else {
            s << "the FRF disagrees beyond the noise (χ² " << num(chi2, 3) << " for " << dof
              << " values at " << r.points << " frequencies): the measured |H| "
              << above_or_below(r.mean_log_ratio) << " the simulation's and its phase "
              << num(r.mean_phase_rad * 180.0 / M_PI, 2) << "° from it, on average";
        }
        r.sentence = s.str();
    }
    std::stable_sort(out.begin(), out.end(), [](const BandResidual& a, const BandResidual& b) {
        if (a.beyond_noise != b.beyond_noise) return a.beyond_noise;
        return a.beyond_noise && a.chi2_magnitude + a.chi2_phase > b.chi2_magnitude + b.chi2_phase;
    });
    return out;
}

}  // namespace sb::correlation

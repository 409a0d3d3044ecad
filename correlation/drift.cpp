#include "correlation/drift.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/significant_text.hpp"
#include "correlation/mismatch.hpp"

namespace sb::correlation {
namespace {

/// A 95 % interval's standard deviation, as if normal.
constexpr double kNormal95 = 3.92;

}  // namespace

Measurement level_measurement(const Measurement& measurement, const std::string& arrangement,
                              double level_g) {
    Measurement m = measurement;
    m.features.clear();
    m.selection.sweeps.clear();
    m.damping.clear();
    for (const auto& f : measurement.features) {
        if (f.arrangement == arrangement && same_level(f.level_g, level_g)) m.features.push_back(f);
    }
    for (const auto& s : measurement.selection.sweeps) {
        if (s.arrangement == arrangement && same_level(s.level_g, level_g)) {
            m.selection.sweeps.push_back(s);
        }
    }
    for (const auto& d : measurement.damping) {
        if (d.arrangement == arrangement && same_level(d.level_g, level_g)) m.damping.push_back(d);
    }
    return m;
}

DriftResult drift_test(const bench::CampaignConfig& config, const Measurement& measurement,
                       const FreeParameter& parameter, const CalibrationOptions& options,
                       const LevelRemote& level_remote) {
    DriftResult result;
    result.parameter = parameter;
    const auto& sweeps = measurement.selection.sweeps;
    for (std::size_t level = 0; level < sweeps.size(); ++level) {
        const auto& sweep = sweeps[level];
        const Measurement one = level_measurement(measurement, sweep.arrangement, sweep.level_g);
        CalibrationOptions at_level = options;
        if (level_remote) {
            at_level.remote = [&level_remote, level](const std::vector<std::string>& inputs) {
                return level_remote(level, inputs);
            };
        }
        const CalibrationResult r = calibrate(config, one, {parameter}, at_level);
        LevelValue v;
        v.arrangement = sweep.arrangement;
        v.level_g = sweep.level_g;
        v.value = r.best.values.front();
        v.simulations = r.simulations;
        if (!r.findings.empty()) {
            v.value = r.findings.front().value;
            v.lo95 = r.findings.front().lo95;
            v.hi95 = r.findings.front().hi95;
            v.identifiable = r.findings.front().identifiable;
        }
        result.levels.push_back(v);
    }
    // Weighted least squares of value = a + b A over the identifiable levels.
    double sw = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (const auto& v : result.levels) {
        const double sigma = (v.hi95 - v.lo95) / kNormal95;
        if (!v.identifiable || !(sigma > 0.0)) continue;
        const double w = 1.0 / (sigma * sigma);
        sw += w;
        sx += w * v.level_g;
        sy += w * v.value;
        sxx += w * v.level_g * v.level_g;
        sxy += w * v.level_g * v.value;
        ++result.used;
    }
    std::ostringstream s;
    s << "`" << parameter.path << "` calibrated level by level: ";
    for (std::size_t k = 0; k < result.levels.size(); ++k) {
        const auto& v = result.levels[k];
        s << (k ? ", " : "") << significant_text(v.value, 3) << " at "
          << significant_text(v.level_g, 3) << " g";
        if (!v.identifiable) s << " (not identifiable)";
    }
    if (result.used < 2) {
        s << "; fewer than two levels identify it, so no trend can be tested";
        result.sentence = s.str();
        return result;
    }
    const double mean = sy / sw;
    for (const auto& v : result.levels) {
        const double sigma = (v.hi95 - v.lo95) / kNormal95;
        if (!v.identifiable || !(sigma > 0.0)) continue;
        result.constant_chi2 += std::pow((v.value - mean) / sigma, 2);
    }
    const double det = sw * sxx - sx * sx;
    if (det > 0.0) {
        result.slope = (sw * sxy - sx * sy) / det;
        result.slope_sigma = std::sqrt(sw / det);
    }
    result.drifts = result.constant_chi2 > chi2_quantile(0.99, result.used - 1);
    s << (result.drifts ? "; it drifts with the level (" : "; no drift beyond the noise (")
      << "slope " << significant_text(result.slope, 3) << " ± "
      << significant_text(result.slope_sigma, 3) << " per g, χ² of a constant "
      << significant_text(result.constant_chi2, 3) << " for " << result.used << " levels)";
    if (result.drifts) {
        s << ": the model misses a physics whose effect changes with the level, which this "
             "value absorbs";
    }
    result.sentence = s.str();
    return result;
}

}  // namespace sb::correlation

#include "correlation/calibration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "correlation/emulator.hpp"

namespace sb::correlation {
namespace {

bool same_level(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, b); }

double level_misfit(const Evaluation& e, const Measurement& m, const std::string& arrangement,
                    double level_g, int& features) {
    double misfit = 0.0;
    features = 0;
    for (std::size_t k = 0; k < m.features.size(); ++k) {
        const auto& f = m.features[k];
        if (f.arrangement != arrangement || !same_level(f.level_g, level_g)) continue;
        ++features;
        const double r = k < e.residuals.size() ? e.residuals[k] : kMissingResidual;
        misfit += 0.5 * r * r;
    }
    return misfit;
}

}  // namespace

CalibrationResult calibrate(const bench::CampaignConfig& config, const Measurement& measurement,
                            const std::vector<FreeParameter>& free,
                            const CalibrationOptions& options) {
    const auto start_time = std::chrono::steady_clock::now();
    EvaluatorOptions eo;
    eo.threads = options.threads;
    eo.cache_dir = options.cache_dir;
    eo.progress = options.progress;
    eo.simulate = options.simulate;
    Evaluator evaluator(config, free, measurement, eo);

    CalibrationResult result;
    result.search = options.search;
    result.free = free;
    result.outcome = search(evaluator, options.search);
    result.history = evaluator.history();
    result.simulations = evaluator.simulations();
    const bool any_success = std::any_of(result.history.begin(), result.history.end(),
                                         [](const Evaluation& e) { return e.error.empty(); });
    if (!any_success) {
        throw std::runtime_error("every simulation of the calibration failed; the first: " +
                                 result.history.front().error);
    }
    result.start = result.history.front();
    for (const auto& e : result.history) {
        if (e.values == result.outcome.best_values) {
            result.best = e;
            break;
        }
    }
    result.calibrated = with_values(config, free, result.best.values);

    try {
        const FeatureEmulator emulator(measurement, free, result.history);
        result.findings =
            assess_identifiability(emulator, measurement, free, to_unit(free, result.best.values));
    } catch (const std::invalid_argument& e) {
        result.findings_note = std::string("no intervals: ") + e.what();
    }
    for (const auto& sweep : measurement.selection.sweeps) {
        LevelFit level;
        level.arrangement = sweep.arrangement;
        level.level_g = sweep.level_g;
        level.misfit_start = level_misfit(result.start, measurement, sweep.arrangement,
                                          sweep.level_g, level.features);
        level.misfit_best = level_misfit(result.best, measurement, sweep.arrangement, sweep.level_g,
                                         level.features);
        result.levels.push_back(level);
    }
    result.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    return result;
}

}  // namespace sb::correlation

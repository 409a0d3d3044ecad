#include "correlation/calibration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlopt.hpp>
#include <stdexcept>

#include "config/errors.hpp"
#include "correlation/emulator.hpp"
#include "correlation/space_filling.hpp"

namespace sb::correlation {
namespace {

/// Half-width of the stencil simulated around the emulator's minimum, in the unit cube.
constexpr double kStencilStep = 0.02;

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

/// The unit-cube point of least emulated misfit: a space-filling search and a cloud around
/// `near` (the search's best), then BOBYQA on the emulator (it costs microseconds).
std::vector<double> emulator_minimum(const FeatureEmulator& emulator,
                                     const std::vector<FreeParameter>& free,
                                     const std::vector<double>& near) {
    const int d = static_cast<int>(free.size());
    std::vector<double> best = near;
    double least = emulator.misfit(near);
    auto pool = halton(2048, d);
    for (const auto& z : halton(512, d, 4096)) {
        std::vector<double> u(z.size());
        for (int j = 0; j < d; ++j) u[j] = std::clamp(near[j] + 0.2 * (z[j] - 0.5), 0.0, 1.0);
        pool.push_back(u);
    }
    for (const auto& u : pool) {
        const double m = emulator.misfit(u);
        if (m < least) {
            least = m;
            best = u;
        }
    }
    nlopt::opt opt(d >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_COBYLA, static_cast<unsigned>(d));
    opt.set_lower_bounds(std::vector<double>(free.size(), 0.0));
    opt.set_upper_bounds(std::vector<double>(free.size(), 1.0));
    opt.set_min_objective(
        [](const std::vector<double>& u, std::vector<double>& /*gradient*/, void* data) {
            return static_cast<const FeatureEmulator*>(data)->misfit(u);
        },
        const_cast<FeatureEmulator*>(&emulator));
    opt.set_maxeval(400);
    opt.set_xtol_abs(1e-5);
    opt.set_initial_step(0.02);
    std::vector<double> u = best;
    double value = least;
    try {
        opt.optimize(u, value);
        if (value < least) best = u;
    } catch (const std::exception&) {
        // a failed local polish keeps the searched point
    }
    return best;
}

}  // namespace

CalibrationResult calibrate(const bench::CampaignConfig& config, const Measurement& measurement,
                            const std::vector<FreeParameter>& free,
                            const CalibrationOptions& options) {
    const auto start_time = std::chrono::steady_clock::now();
    // A DEM campaign's features jitter with the filling of the bed. Only the scatter over
    // several fillings per evaluation tells the emulator jitter from trend: with one, it took
    // the jitter of a collisional campaign for a narrow valley in the friction.
    const bool dem = std::any_of(
        config.campaign.dampers.begin(), config.campaign.dampers.end(),
        [](const bench::DamperSpec& d) { return d.model == bench::DamperSpec::Model::dem; });
    if (dem && config.campaign.seeds < 2) {
        throw config::ConfigException({config::ConfigError{
            config.source, 0, 0, "campaign.seeds", std::to_string(config.campaign.seeds),
            "must be at least 2 to calibrate a DEM damper: the seed scatter of the fillings is "
            "what separates the bed's chaos from the free values' effect (--set "
            "campaign.seeds=3)",
            "fillings of the bed per level"}});
    }
    EvaluatorOptions eo;
    eo.threads = options.threads;
    eo.cache_dir = options.cache_dir;
    eo.progress = options.progress;
    eo.simulate = options.simulate;
    // The search's budget, the stencil around the answer and its confirmation.
    eo.expected_evaluations = options.search.budget + 2 * static_cast<int>(free.size()) + 1;
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
    std::vector<double> best_values = result.outcome.best_values;
    try {
        // The answer is where the emulator, trained on every evaluation, puts the least
        // misfit: it averages the seed scatter that makes single evaluations of a DEM
        // campaign jitter. That point is simulated once more to confirm it (and to give the
        // residuals after), unless it was evaluated already.
        const FeatureEmulator global(measurement, free, result.history);
        auto u = emulator_minimum(global, free, to_unit(free, best_values));
        // A stencil of simulations around it (±kStencilStep of each interval) so that the
        // emulator resolves the misfit's valley there, which the search's points spread over
        // the whole box cannot: the intervals rest on it.
        std::vector<std::vector<double>> stencil;
        for (std::size_t j = 0; j < free.size(); ++j) {
            for (const double sign : {-1.0, 1.0}) {
                auto v = u;
                v[j] = std::clamp(u[j] + sign * kStencilStep, 0.0, 1.0);
                if (v != u) stencil.push_back(to_values(free, v));
            }
        }
        evaluator.evaluate(stencil);
        const FeatureEmulator emulator(measurement, free, evaluator.history());
        u = emulator_minimum(emulator, free, u);
        best_values = to_values(free, u);
        result.findings = assess_identifiability(emulator, measurement, free, u);
    } catch (const std::invalid_argument& e) {
        result.findings_note = std::string("no intervals: ") + e.what();
    }
    result.best = evaluator.evaluate(best_values);
    if (!result.best.error.empty()) {
        throw std::runtime_error("the simulation at the calibrated values failed: " +
                                 result.best.error);
    }
    result.history = evaluator.history();
    result.simulations = evaluator.simulations();
    result.calibrated = with_values(config, free, result.best.values);
    for (auto& f : result.findings) {
        for (std::size_t j = 0; j < free.size(); ++j) {
            if (free[j].path == f.parameter.path) f.value = result.best.values[j];
        }
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

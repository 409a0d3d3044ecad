#include "correlation/calibration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "config/errors.hpp"
#include "config/value.hpp"
#include "correlation/emulator.hpp"
#include "correlation/space_filling.hpp"
#include "correlation/two_fidelity.hpp"

namespace sb::correlation {
namespace {

/// Half-width of the stencil simulated around the emulator's minimum, in the unit cube.
constexpr double kStencilStep = 0.02;

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

constexpr const char* kCoupled = "coupled";
constexpr const char* kPrediction = "prediction";

/// options.remote for the evaluations of one fidelity: each input led by its name.
std::function<std::vector<std::string>(const std::vector<std::string>&)> remote_of(
    const CalibrationOptions& options, const std::string& fidelity) {
    if (!options.remote) return {};
    return [remote = options.remote, fidelity](const std::vector<std::string>& values) {
        std::vector<std::string> inputs;
        inputs.reserve(values.size());
        for (const auto& v : values) inputs.push_back(fidelity + "\n" + v);
        return remote(inputs);
    };
}

/// The low fidelity's evaluator options: those of the coupled one, another simulation.
EvaluatorOptions low_fidelity_options(const bench::CampaignConfig& config,
                                      const CalibrationOptions& options, EvaluatorOptions lo) {
    lo.fidelity = kPrediction;
    lo.expected_evaluations = options.search.budget;
    lo.simulate = options.low_fidelity_simulate;
    lo.remote = remote_of(options, kPrediction);
    if (!lo.simulate) {
        const auto folder =
            options.cache_dir.empty()
                ? std::filesystem::temp_directory_path() /
                      ("shakerbench-characterizations-" + stable_hash(config.source))
                : options.cache_dir / "characterizations";
        lo.simulate = describing_function_simulation(folder, options.characterization_frequencies);
    }
    return lo;
}

}  // namespace

std::function<std::string(const std::string&, int)> calibration_simulator(
    const bench::CampaignConfig& config, const Measurement& measurement,
    const std::vector<FreeParameter>& free, const CalibrationOptions& options) {
    EvaluatorOptions eo;
    eo.simulate = options.simulate;
    auto coupled = std::make_shared<const Evaluator>(config, free, measurement, eo);
    auto low = std::make_shared<const Evaluator>(config, free, measurement,
                                                 low_fidelity_options(config, options, eo));
    return [coupled, low](const std::string& input, int threads) {
        const auto newline = input.find('\n');
        const std::string fidelity = input.substr(0, newline);
        const std::string values = newline == std::string::npos ? "" : input.substr(newline + 1);
        if (fidelity == kCoupled) return coupled->simulate_text(values, threads);
        if (fidelity == kPrediction) return low->simulate_text(values, threads);
        throw std::invalid_argument("an evaluation of an unknown fidelity: " + fidelity);
    };
}

std::string fidelity_name(Fidelity fidelity) {
    return fidelity == Fidelity::coupled ? "coupled" : "two-fidelity";
}

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
    eo.remote = remote_of(options, kCoupled);
    const int stencil = 2 * static_cast<int>(free.size()) + 1;
    // The search's budget, the stencil around the answer and its confirmation; two-fidelity:
    // the start, the stencils and the confirmation.
    eo.expected_evaluations = options.fidelity == Fidelity::coupled
                                  ? options.search.budget + stencil
                                  : 2 + kTwoFidelityCorrections * stencil;
    Evaluator evaluator(config, free, measurement, eo);

    CalibrationResult result;
    result.search = options.search;
    result.free = free;
    result.fidelity = options.fidelity;
    std::vector<double> best_values;
    if (options.fidelity == Fidelity::two_fidelity) {
        EvaluatorOptions lo = low_fidelity_options(config, options, eo);
        Evaluator low(config, free, measurement, lo);
        // The residuals before, on the coupled simulation.
        std::vector<double> start(free.size());
        for (std::size_t j = 0; j < free.size(); ++j) start[j] = free[j].start;
        result.start = evaluator.evaluate(start);
        if (!result.start.error.empty()) {
            throw std::runtime_error("the coupled simulation at the config's values failed: " +
                                     result.start.error);
        }
        try {
            const TwoFidelityOutcome two = two_fidelity_search(low, evaluator, options.search);
            result.outcome = two.low_search;
            result.corrections = two.corrections;
            result.corrections_stopped = two.stopped;
            best_values = two.best_values;
            const FeatureEmulator emulator(measurement, free, two.corrected_history);
            result.findings =
                assess_identifiability(emulator, measurement, free, to_unit(free, best_values));
        } catch (const std::invalid_argument& e) {
            result.findings_note = std::string("no intervals: ") + e.what();
            best_values = result.start.values;
        }
        result.low_fidelity_history = low.history();
        result.low_fidelity_simulations = low.simulations();
    } else {
        result.outcome = search(evaluator, options.search);
        best_values = result.outcome.best_values;
        const auto& history = evaluator.history();
        const bool any_success = std::any_of(history.begin(), history.end(),
                                             [](const Evaluation& e) { return e.error.empty(); });
        if (!any_success) {
            throw std::runtime_error("every simulation of the calibration failed; the first: " +
                                     history.front().error);
        }
        result.start = history.front();
        try {
            // The answer is where the emulator, trained on every evaluation, puts the least
            // misfit: it averages the seed scatter that makes single evaluations of a DEM
            // campaign jitter. That point is simulated once more to confirm it (and to give
            // the residuals after), unless it was evaluated already.
            const FeatureEmulator global(measurement, free, history);
            auto u = least_emulated_misfit(global, free, to_unit(free, best_values));
            // A stencil of simulations around it (±kStencilStep of each interval) so that the
            // emulator resolves the misfit's valley there, which the search's points spread
            // over the whole box cannot: the intervals rest on it.
            std::vector<std::vector<double>> points;
            for (const auto& v : axis_stencil(u, kStencilStep))
                points.push_back(to_values(free, v));
            evaluator.evaluate(points);
            const FeatureEmulator emulator(measurement, free, evaluator.history());
            u = least_emulated_misfit(emulator, free, u);
            best_values = to_values(free, u);
            result.findings = assess_identifiability(emulator, measurement, free, u);
        } catch (const std::invalid_argument& e) {
            result.findings_note = std::string("no intervals: ") + e.what();
        }
    }
    result.best = evaluator.evaluate(best_values);
    if (!result.best.error.empty()) {
        throw std::runtime_error("the simulation at the calibrated values failed: " +
                                 result.best.error);
    }
    result.history = evaluator.history();
    result.simulations = evaluator.simulations();
    result.calibrated = with_values(config, free, result.best.values);
    if (result.best.misfit > result.start.misfit) {
        // The emulator's minimum, simulated, fits worse than the start: single simulations
        // scatter more than the free values move them (the bed's fillings), so neither point
        // is better than the other within that scatter.
        result.warnings.push_back(
            "the calibrated values, simulated, fit worse than the start (misfit " +
            std::to_string(result.best.misfit) + " against " + std::to_string(result.start.misfit) +
            "): the simulations scatter more than the free values move them; more fillings "
            "per evaluation (campaign.seeds) or other levels are needed");
        // The emulator's landscape did not hold where it mattered most, so its intervals
        // cannot be taken for what the data say: none is reported identifiable.
        for (auto& f : result.findings) {
            if (!f.identifiable) continue;
            f.identifiable = false;
            f.reason =
                "the emulated optimum, simulated, fit worse than the start, so the "
                "emulator's interval [" +
                config::number_text(f.lo95) + ", " + config::number_text(f.hi95) +
                "] is not what the data say: the simulations scatter more than this "
                "value moves them";
        }
    }
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

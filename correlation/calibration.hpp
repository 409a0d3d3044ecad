// Calibration as a function: free config values fitted to a measurement within a budget of
// simulations, with what the data can and cannot say about each (docs/calibration.md).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "correlation/evaluator.hpp"
#include "correlation/identifiability.hpp"
#include "correlation/search.hpp"

namespace sb::correlation {

struct CalibrationOptions {
    SearchOptions search;
    int threads = 0;                  ///< 0: the hardware's
    std::filesystem::path cache_dir;  ///< the evaluations kept; empty: memory only
    std::function<void(const std::string&)> progress;
    /// How a config is simulated (EvaluatorOptions::simulate); empty: the coupled campaign.
    std::function<bench::CampaignResult(const bench::CampaignConfig&, const bench::Selection&, int)>
        simulate;
};

/// The misfit of one arrangement and level before and after.
struct LevelFit {
    std::string arrangement;
    double level_g = 0.0;
    int features = 0;
    double misfit_start = 0.0;  ///< ½ Σ r² of its features at the config's values
    double misfit_best = 0.0;   ///< at the calibrated values
};

struct CalibrationResult {
    SearchOptions search;
    SearchOutcome outcome;
    std::vector<FreeParameter> free;
    Evaluation start;                        ///< at the config's values
    Evaluation best;                         ///< at the calibrated values
    std::vector<ParameterFinding> findings;  ///< per free parameter
    /// Why the findings are missing (too few successful evaluations); empty when they exist.
    std::string findings_note;
    std::vector<LevelFit> levels;
    int simulations = 0;  ///< evaluations simulated, not taken from the cache
    double wall_time_s = 0.0;
    std::vector<Evaluation> history;
    bench::CampaignConfig calibrated;  ///< the config with the calibrated values
};

/// Fits `free` of `config` to `measurement`: the search of options.search, then the emulator
/// trained on every evaluation for the profile intervals and the information per level.
/// Throws config::ConfigException when the config cannot simulate the measurement (an
/// arrangement it lacks), std::runtime_error when every evaluation failed.
CalibrationResult calibrate(const bench::CampaignConfig& config, const Measurement& measurement,
                            const std::vector<FreeParameter>& free,
                            const CalibrationOptions& options);

/// Writes calibration.toml (values, intervals, identifiability, evaluations), report.md,
/// calibrated.toml (the resolved config with the calibrated values, ready to run),
/// evaluations.csv and the plots (data, gnuplot script, SVGs when gnuplot is installed) into
/// out_dir. Throws sb::FileWriteError naming a file that cannot be written.
void write_calibration(const std::filesystem::path& out_dir, const CalibrationResult& result,
                       const Measurement& measurement, const std::string& command_line);

}  // namespace sb::correlation

// Calibration as a function: free config values fitted to a measurement within a budget of
// simulations, with what the data can and cannot say about each (docs/calibration.md).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "correlation/evaluator.hpp"
#include "correlation/identifiability.hpp"
#include "correlation/prediction_fidelity.hpp"
#include "correlation/search.hpp"

namespace sb::correlation {

/// What the search runs on: the coupled simulation alone, or the two-fidelity scheme
/// (correlation/two_fidelity.hpp): the search on the describing-function prediction, the
/// coupled simulation correcting and confirming it.
enum class Fidelity { coupled, two_fidelity };

/// "coupled", "two-fidelity".
std::string fidelity_name(Fidelity fidelity);

struct CalibrationOptions {
    SearchOptions search;  ///< two-fidelity: its budget counts low-fidelity evaluations
    Fidelity fidelity = Fidelity::coupled;
    int threads = 0;                  ///< 0: the hardware's
    std::filesystem::path cache_dir;  ///< the evaluations kept; empty: memory only
    std::function<void(const std::string&)> progress;
    /// How a config is simulated (EvaluatorOptions::simulate); empty: the coupled campaign.
    Simulation simulate;
    /// Two-fidelity: the low fidelity's simulation; empty: describing_function_simulation in
    /// cache_dir (else a temporary folder) on `characterization_frequencies` frequencies.
    Simulation low_fidelity_simulate;
    int characterization_frequencies = 3;
    /// Simulates evaluations in other processes (MPI ranks; distributed/rounds.hpp): each
    /// input is a fidelity's name and the values as text, answered by the text of
    /// calibration_simulator on another rank. Empty: this process's threads.
    std::function<std::vector<std::string>(const std::vector<std::string>& inputs)> remote;
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
    /// What the user must know about the answer (it fits worse than the start, ...).
    std::vector<std::string> warnings;
    std::vector<LevelFit> levels;
    int simulations = 0;  ///< evaluations simulated, not taken from the cache
    double wall_time_s = 0.0;
    std::vector<Evaluation> history;
    Fidelity fidelity = Fidelity::coupled;
    /// Two-fidelity: the low fidelity's evaluations, their simulations (not cached), the
    /// coupled stencils that corrected it and why the corrections ended.
    std::vector<Evaluation> low_fidelity_history;
    int low_fidelity_simulations = 0;
    int corrections = 0;
    std::string corrections_stopped;
    bench::CampaignConfig calibrated;  ///< the config with the calibrated values
};

/// Fits `free` of `config` to `measurement`: the search of options.search, then the emulator
/// trained on every evaluation for the profile intervals and the information per level.
/// Two-fidelity: the search on the low fidelity, corrected by coupled stencils, the
/// intervals from the corrected low-fidelity emulator; the answer confirmed coupled.
/// Throws config::ConfigException when the config cannot simulate the measurement (an
/// arrangement it lacks), std::runtime_error when every evaluation failed.
CalibrationResult calibrate(const bench::CampaignConfig& config, const Measurement& measurement,
                            const std::vector<FreeParameter>& free,
                            const CalibrationOptions& options);

/// What another process of a distributed calibration runs for each input of
/// CalibrationOptions::remote: the same config, measurement, free values and options as the
/// calibrating process (its remote and cache unused) give the same simulation.
std::function<std::string(const std::string& input, int threads)> calibration_simulator(
    const bench::CampaignConfig& config, const Measurement& measurement,
    const std::vector<FreeParameter>& free, const CalibrationOptions& options);

/// Writes calibration.toml (values, intervals, identifiability, evaluations), report.md,
/// calibrated.toml (the resolved config with the calibrated values, ready to run),
/// evaluations.csv and the plots (data, gnuplot script, SVGs when gnuplot is installed) into
/// out_dir. Throws sb::FileWriteError naming a file that cannot be written.
void write_calibration(const std::filesystem::path& out_dir, const CalibrationResult& result,
                       const Measurement& measurement, const std::string& command_line);

}  // namespace sb::correlation

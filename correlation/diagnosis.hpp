// A diagnosis as far as it goes today (docs/diagnosis.md): the config simulated on exactly
// what the measurement has, both reduced to the level features, the features that disagree
// beyond the noise with how they scale with the level, and the drift of values calibrated
// level by level; a verdict, diagnosis.toml and report.md.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bench/campaign.hpp"
#include "correlation/band_residuals.hpp"
#include "correlation/calibration.hpp"
#include "correlation/drift.hpp"
#include "correlation/features.hpp"
#include "correlation/hypotheses.hpp"
#include "correlation/mismatch.hpp"

namespace sb::correlation {

struct DiagnosisOptions {
    StatedUncertainty stated;  ///< of the measured values without repeats
    /// Values tested for drift (each calibrated level by level); empty: none.
    std::vector<FreeParameter> drift;
    /// The drift calibrations' search, threads and cache; its `simulate` (when set) also
    /// simulates the baseline.
    CalibrationOptions calibration;
    std::function<void(const std::string&)> progress;  ///< empty: none
    /// Catalogue physics fitted when a feature disagrees beyond the noise, at most; 0: none.
    int hypotheses = 3;
    int held_out_levels = 1;  ///< HypothesisOptions::held_out_levels
    bool confirm = false;     ///< HypothesisOptions::confirm
    /// What they are fitted on; empty: candidate_simulation(config) (the fast prediction
    /// where the config allows it, else the coupled campaign).
    Simulation hypothesis_simulate;
    /// Runs the baseline's sweeps when calibration.simulate is empty (the sweeps of an MPI
    /// run: distributed/campaign.hpp); null: this process's threads.
    bench::SweepExecutor* baseline_executor = nullptr;
    /// Simulates the drift calibrations' evaluations in other processes (MPI ranks;
    /// distributed/rounds.hpp): each input in the form diagnosis_simulator reads, answered by
    /// its text on another rank. Empty: this process's threads.
    std::function<std::vector<std::string>(const std::vector<std::string>& inputs)> remote;
};

struct DiagnosisResult {
    Measurement measurement;
    std::vector<LevelFeatureValues> measured;
    std::vector<LevelFeatureValues> simulated;
    /// The baseline's simulation reduced to the measurement's features (its FRF at the
    /// measured frequencies, its damping curve): for the report's plots.
    SimulatedFeatures baseline;
    std::vector<FeatureMismatch> mismatches;  ///< beyond the noise first
    /// The FRF per level below, around and above its resonance (measurements with points);
    /// beyond the noise first.
    std::vector<BandResidual> bands;
    std::vector<DriftResult> drifts;
    /// The catalogue ranked and its best candidates fitted (when a feature disagreed).
    std::optional<HypothesisTest> hypotheses;
    bool mismatch = false;  ///< a feature beyond the noise, or a value that drifts
    std::string verdict;    ///< "no significant mismatch", or what disagrees, in a sentence
    double wall_time_s = 0.0;
};

/// Diagnoses `config` against the recording directory `measured`. Throws what
/// read_measurement, the simulation and calibrate throw.
DiagnosisResult diagnose(const bench::CampaignConfig& config, const std::filesystem::path& measured,
                         const DiagnosisOptions& options);

/// What another process of a distributed diagnosis runs for each input of
/// DiagnosisOptions::remote (which drift value, which level, then the calibration's input):
/// the same config, measurement and options as the diagnosing process give the same
/// simulation. A bad input throws std::invalid_argument.
std::function<std::string(const std::string& input, int threads)> diagnosis_simulator(
    const bench::CampaignConfig& config, const Measurement& measurement,
    const DiagnosisOptions& options);

/// Writes diagnosis.toml (verdict, located residuals, drift tests, ranked candidates) and
/// report.md into out_dir, and improved.toml (the config with the winning physics at its
/// fitted values, ready to run) when a candidate explains the mismatch. Throws sb::FileWriteError
/// naming a file that cannot be written.
void write_diagnosis(const std::filesystem::path& out_dir, const DiagnosisResult& result,
                     const std::string& command_line);

}  // namespace sb::correlation

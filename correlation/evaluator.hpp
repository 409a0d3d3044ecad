// One evaluation of a calibration: the config with the free values set, its campaign simulated
// on exactly what the measurement has (in memory), reduced to the measurement's features and
// compared. Every evaluation is cached by the resolved config's hash and the measurement's
// feature layout, in memory and in a folder, so a calibration interrupted or run again reuses
// what was simulated.
#pragma once

#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "bench/campaign_config.hpp"
#include "correlation/features.hpp"
#include "correlation/free_parameters.hpp"

namespace sb::correlation {

/// The result of one evaluation.
struct Evaluation {
    std::vector<double> values;  ///< the free parameters' values
    std::string key;             ///< config hash + feature layout hash
    SimulatedFeatures simulated;
    std::vector<double> residuals;  ///< per feature, in standard deviations
    double misfit = 0.0;            ///< ½ Σ residual² (a negative log-likelihood)
    bool from_cache = false;
    double wall_time_s = 0.0;  ///< of the simulation (0 from the cache)
    std::string error;         ///< why the simulation failed; empty when it ran
};

/// Misfit given to an evaluation whose simulation failed: larger than any real one, finite so
/// that the optimisers keep going around it.
inline constexpr double kFailedMisfit = 1e12;

struct EvaluatorOptions {
    int threads = 0;  ///< shared by the evaluations of a batch; 0: the hardware's
    /// Where each evaluation's features are kept (one small file per key); empty: memory only.
    std::filesystem::path cache_dir;
    /// Receives one line per evaluation (values, misfit, best so far, time, ETA); empty: none.
    std::function<void(const std::string&)> progress;
    /// Evaluations expected in all, for the progress lines' ETA; 0: no ETA.
    int expected_evaluations = 0;
    /// Simulates a config on a measurement's selection: the coupled campaign by default
    /// (bench::run_campaign with no store); a test or the two-fidelity mode may give the
    /// describing-function prediction instead.
    std::function<bench::CampaignResult(const bench::CampaignConfig&, const bench::Selection&,
                                        int threads)>
        simulate;
    /// What `simulate` is, when it is not the coupled campaign ("prediction"): it enters the
    /// cache key (a prediction never stands in for a coupled run) and the progress lines.
    std::string fidelity;
    /// Simulates the evaluations that are not cached elsewhere (other processes, MPI ranks):
    /// given each one's values as text (Evaluator::simulate_text's input), returns each one's
    /// result as text (its output), in order. Empty: this process's threads simulate.
    std::function<std::vector<std::string>(const std::vector<std::string>& values_texts)> remote;
};

class Evaluator {
  public:
    Evaluator(bench::CampaignConfig config, std::vector<FreeParameter> free,
              Measurement measurement, EvaluatorOptions options);

    /// Evaluates each set of values (a batch runs in parallel, the threads shared among its
    /// simulations); a value set seen before comes from the cache.
    std::vector<Evaluation> evaluate(const std::vector<std::vector<double>>& values);
    Evaluation evaluate(const std::vector<double>& values);

    /// Every evaluation so far, in the order asked.
    [[nodiscard]] const std::vector<Evaluation>& history() const { return history_; }
    /// Evaluations simulated (not taken from the cache).
    [[nodiscard]] int simulations() const { return simulations_; }
    [[nodiscard]] const std::vector<FreeParameter>& free() const { return free_; }
    [[nodiscard]] const Measurement& measurement() const { return measurement_; }
    [[nodiscard]] const bench::CampaignConfig& config() const { return config_; }

    /// Residuals and misfit of simulated features against the measurement.
    void compare(Evaluation& evaluation) const;

    /// For another process of a distributed calibration: simulates the free values of
    /// `values_text` (numbers separated by spaces) without the cache and returns the result as
    /// the cache file's text. Throws std::invalid_argument for values that do not read.
    [[nodiscard]] std::string simulate_text(const std::string& values_text, int threads) const;

  private:
    /// The evaluation's values and key, and the config with the values set; false (the error
    /// set and compared) when the values cannot be set.
    bool prepare(const std::vector<double>& values, Evaluation& evaluation,
                 bench::CampaignConfig& changed) const;
    void simulate(const bench::CampaignConfig& changed, Evaluation& evaluation, int threads) const;
    Evaluation run_one(const std::vector<double>& values, int threads) const;
    std::vector<Evaluation> evaluate_remotely(const std::vector<std::vector<double>>& batch);
    /// Adds a batch's evaluations to the history and prints their progress lines.
    void record(const std::vector<Evaluation>& results);
    bool load(const std::string& key, Evaluation& evaluation) const;
    void store(const Evaluation& evaluation) const;

    bench::CampaignConfig config_;
    std::vector<FreeParameter> free_;
    Measurement measurement_;
    EvaluatorOptions options_;
    std::string layout_hash_;
    std::vector<Evaluation> history_;
    int simulations_ = 0;
};

/// The coupled campaign of `config` on `selection`, in memory and without a checkpoint store:
/// what an evaluation simulates unless told otherwise.
bench::CampaignResult coupled_simulation(const bench::CampaignConfig& config,
                                         const bench::Selection& selection, int threads);

/// An evaluation as text (the cache file's): its key, simulated features, error and time.
std::string evaluation_text(const Evaluation& evaluation);
/// Reads evaluation_text's output into `evaluation` (features, error, time, key); false when
/// it is not whole, not of `key` or has other than `features` features.
bool parse_evaluation_text(const std::string& text, const std::string& key, std::size_t features,
                           Evaluation& evaluation);

/// 16 hexadecimal digits of FNV-1a over `text`: stable across runs and machines.
std::string stable_hash(const std::string& text);

}  // namespace sb::correlation

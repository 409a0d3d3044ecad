// The stepped-sine campaign as a function: arrangements x levels x frequencies, each sweep
// driven by the RMS amplitude controller and checkpointed after every point, returned in
// memory; writing the recording directory is a separate call (campaign_output.hpp).
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/channels.hpp"
#include "bench/checkpoint_store.hpp"
#include "bench/sweep_runner.hpp"
#include "identification/damping_curve.hpp"
#include "identification/recording.hpp"

namespace sb::bench {

/// Runs the sweep tasks of a planned campaign, each with run_sweep against `store`, and
/// returns their results in task order; every task runs even when one fails, and then the
/// first failure (in task order) is thrown. run_campaign's default runs them on this process's
/// threads; a distributed executor hands them to other processes (distributed/), each sweep
/// reading and writing `store` and reporting to `progress` through the process that owns
/// them. The numbers do not depend on who runs a sweep.
class SweepExecutor {
  public:
    virtual ~SweepExecutor() = default;
    virtual std::vector<SweepResult> run(const CampaignConfig& config, const CampaignPlan& plan,
                                         const std::string& config_hash, CheckpointStore& store,
                                         SweepProgress& progress) = 0;
    /// Processes the sweeps run on (provenance.toml's `ranks`).
    [[nodiscard]] virtual int processes() const = 0;
    /// Sweeps each process runs at once (provenance.toml's `threads`).
    [[nodiscard]] virtual int threads() const = 0;
};

/// What a campaign run needs besides its config.
struct CampaignContext {
    int threads = 0;  ///< sweeps run in parallel; 0: OpenMP's default
    /// Receives progress lines (a point starts, a point ends); empty: none.
    std::function<void(const std::string&)> progress;
    /// Where checkpoints, settled beds and per-point files go; null: nothing is kept.
    CheckpointStore* store = nullptr;
    /// Forget what the store holds for this config and simulate everything.
    bool restart = false;
    /// The sweeps to run (and on which frequencies); empty: the whole config.
    Selection selection;
    /// Who runs the sweeps; null: this process, on `threads` threads.
    SweepExecutor* executor = nullptr;
};

struct CampaignSummary {
    int points = 0;          ///< points in the campaign
    int resumed_points = 0;  ///< taken from the store instead of simulated
    int converged = 0;
    int limit_cycle = 0;
    int closest = 0;
    long long periods_simulated = 0;
    double wall_time_s = 0.0;
};

/// Everything a campaign gives back.
struct CampaignResult {
    /// Channels and every point of every sweep (campaign order), as recording.toml and
    /// points.csv hold them; the damping rows of `levels` in `recording.damping`.
    identification::Recording recording;
    /// Per arrangement and level: the FRF and every estimator (points with status `closest`
    /// left out of the fits).
    std::vector<identification::LevelIdentification> levels;
    std::vector<SweepResult> sweeps;  ///< in campaign order
    CampaignSummary summary;
    std::string config_hash;                ///< of the resolved config (bench/resolved_config.hpp)
    int threads = 1;                        ///< sweeps run at once per process
    int ranks = 1;                          ///< processes the sweeps ran on
    std::vector<RecordedChannel> channels;  ///< after the reference, the control first
};

/// "H-0 2 g: 2 points with status closest left out of the fits (6.301, 6.412 Hz)": the line
/// a campaign prints for a level whose flagged points the fits left out (`unit`: a fixed
/// drive's level unit, "V" in "H-0 0.2 V: ...").
std::string skipped_points_line(const identification::LevelIdentification& level,
                                const std::string& unit = "g");

/// Identifies result.recording per arrangement, level and filling at the control point
/// (result.levels, result.recording.damping) and reports to `progress` (when set) each level
/// whose flagged points the fits left out: what a run and a prediction do alike.
void identify_campaign(const CampaignConfig& config,
                       const std::function<void(const std::string&)>& progress,
                       CampaignResult& result);

/// recording.toml's channels of a campaign of `config`: the reference ("force" or
/// "base_acc"), then `channels` (the control channel first).
identification::Recording campaign_recording(const CampaignConfig& config,
                                             const std::vector<RecordedChannel>& channels);

/// Runs (or resumes from context.store) the campaign of `config`. Sweeps are independent
/// tasks run on context.threads threads; the numbers do not depend on the thread count nor
/// on the store. Throws config::ConfigException when the config or the selection cannot run
/// (no level, no arrangement, an unknown arrangement) or when the store holds another
/// config's checkpoints (nothing simulated), dem::SimulationError when a DEM guard fires,
/// std::runtime_error otherwise.
CampaignResult run_campaign(const CampaignConfig& config, const CampaignContext& context);

/// The CLI's campaign: checkpoints in out_dir, the recording directory written there.
struct CampaignRunOptions {
    std::filesystem::path out_dir;     ///< the recording directory written (and resumed)
    int threads = 0;                   ///< sweeps run in parallel; 0: OpenMP's default
    std::ostream* progress = nullptr;  ///< progress lines, or none
    std::string config_text;           ///< the config as read, copied into the output
    std::string command_line;          ///< for the provenance file
    /// Discard the checkpoints and settled beds found in out_dir and start over; without it
    /// checkpoints of another config (another hash) are refused.
    bool restart = false;
    /// Who runs the sweeps; null: this process, on `threads` threads.
    SweepExecutor* executor = nullptr;
};

/// run_campaign with a FileCheckpointStore in options.out_dir, then write_campaign_output
/// there. Returns the summary; throws as run_campaign.
CampaignSummary run_campaign(const CampaignConfig& config, const CampaignRunOptions& options);

}  // namespace sb::bench

// A campaign's sweeps over the ranks of a run: rank 0 runs bench::run_campaign with a
// DistributedSweeps executor (it owns the store, prints the progress, writes the recording
// directory); every other rank calls serve_campaign and runs the sweeps it is handed.
#pragma once

#include "bench/campaign.hpp"
#include "distributed/transport.hpp"

namespace sb::distributed {

/// The executor of rank 0: sweeps are tasks of a queue (distributed/task_queue.hpp) handed
/// out to the threads of every rank, rank 0's own included; a sweep on another rank reads and
/// writes rank 0's store and reports to its progress through calls, and its result comes back
/// as exact text (bench/sweep_checkpoint.hpp), so the campaign is the same as one process's.
class DistributedSweeps : public bench::SweepExecutor {
  public:
    /// `transport` is rank 0's (null: alone); `threads` sweeps at once per rank (0: OpenMP's
    /// default).
    DistributedSweeps(Transport* transport, int threads);
    /// Releases the other ranks if run() never started (the campaign could not run) or its
    /// queue broke.
    ~DistributedSweeps() override;
    DistributedSweeps(const DistributedSweeps&) = delete;
    DistributedSweeps& operator=(const DistributedSweeps&) = delete;

    std::vector<bench::SweepResult> run(const bench::CampaignConfig& config,
                                        const bench::CampaignPlan& plan,
                                        const std::string& config_hash,
                                        bench::CheckpointStore& store,
                                        bench::SweepProgress& progress) override;
    [[nodiscard]] int processes() const override;
    [[nodiscard]] int threads() const override { return threads_; }
    /// Sweeps each rank ran in the last run() (index: rank).
    [[nodiscard]] const std::vector<int>& sweeps_per_rank() const { return per_rank_; }

  private:
    Transport* transport_;
    int threads_;
    bool started_ = false;
    std::vector<int> per_rank_;
};

/// Ranks other than 0: plans the campaign of `config` as rank 0 does (same config, same
/// selection) and runs the sweeps rank 0 hands out, `threads` at once (0: OpenMP's default),
/// until it says stop. Returns the number of sweeps this rank ran.
int serve_campaign(Transport& transport, const bench::CampaignConfig& config,
                   const bench::Selection& selection, int threads);

}  // namespace sb::distributed

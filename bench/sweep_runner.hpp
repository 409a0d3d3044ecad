// One sweep of a campaign, run (or resumed) on its own: the task a scheduler hands out.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/checkpoint_store.hpp"
#include "control/result.hpp"
#include "identification/recording.hpp"

namespace sb::bench {

/// One sweep's results, as the campaign returns them.
struct SweepResult {
    std::string key;
    std::string arrangement;
    double level_g = 0.0;
    double first_mode_hz = 0.0;
    std::vector<double> frequencies_hz;  ///< the sweep's grid, in the order stepped
    std::vector<std::string> settings;   ///< derived settings (stiffness, time step)
    std::vector<identification::PointRow> rows;
    std::vector<std::string> control_log;  ///< control.csv rows
    std::vector<std::string> energy_log;   ///< energy.csv rows (output.energy)
    /// A run from rest (campaign.transient): the time histories (`time_s,<channel>,...`
    /// rows) and the envelope per period (`period,start_s,<channel>_min,...,<channel>_max,...`
    /// rows), CSV text without the header; the headers come from `transient_channels`.
    std::vector<std::string> transient_series;
    std::vector<std::string> transient_envelope;
    std::vector<std::string> transient_channels;
    /// A random test (campaign.random): random/<sweep>.csv, its header first
    /// (random_spectra_text of bench/random_test.hpp), one line per row.
    std::vector<std::string> random_spectra;
    int resumed_points = 0;  ///< taken from the store, not simulated
    long long periods_simulated = 0;
};

/// What a sweep reports as it goes (thread-safe): the campaign's progress lines in this
/// process, or a proxy that forwards the events to the process that prints them.
class SweepProgress {
  public:
    virtual ~SweepProgress() = default;
    /// Point `index` of the sweep (0-based; beyond the task's grid: an added frequency).
    virtual void point_started(const SweepTask& task, int index, double frequency_hz) = 0;
    /// `count` points were taken from the store.
    virtual void points_resumed(int count) = 0;
    /// A sweep refined its grid by `count` frequencies.
    virtual void points_added(int count) = 0;
    /// A line of its own (a sweep that could not resolve its estimates).
    virtual void note(const std::string& line) = 0;
    virtual void point_finished(const SweepTask& task, double frequency_hz,
                                const control::PointResult& result) = 0;
};

/// Progress lines shared by the sweeps of a campaign (thread-safe).
class CampaignProgress : public SweepProgress {
  public:
    CampaignProgress(std::function<void(const std::string&)> sink, int points_total);
    void point_started(const SweepTask& task, int index, double frequency_hz) override;
    void points_resumed(int count) override;
    void points_added(int count) override;
    void note(const std::string& line) override;
    void point_finished(const SweepTask& task, double frequency_hz,
                        const control::PointResult& result) override;
    [[nodiscard]] long long periods() const { return periods_.load(); }

  private:
    std::function<void(const std::string&)> sink_;
    std::atomic<int> points_total_;
    std::mutex mutex_;
    std::atomic<int> points_done_{0};
    std::atomic<int> points_simulated_{0};
    std::atomic<long long> periods_{0};
    std::chrono::steady_clock::time_point start_;
};

/// Runs (or resumes from `store`) the sweep `task` of `config`, whose resolved config has the
/// hash `config_hash`. After every point the sweep's checkpoint goes to the store, and every
/// point starts from that checkpoint's text, so an interrupted sweep resumed from the store
/// gives exactly the numbers of an uninterrupted one. Throws dem::SimulationError when a DEM
/// guard fires.
SweepResult run_sweep(const CampaignConfig& config, const SweepTask& task,
                      const std::string& config_hash, CheckpointStore& store,
                      SweepProgress& progress);

}  // namespace sb::bench

// The stepped-sine campaign: arrangements x levels x frequencies, each sweep driven by the
// RMS amplitude controller, checkpointed after every point, written as a recording.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>

#include "bench/campaign_config.hpp"

namespace sb::bench {

struct CampaignRunOptions {
    std::filesystem::path out_dir;     ///< the recording directory written (and resumed)
    int threads = 0;                   ///< sweeps run in parallel; 0: OpenMP's default
    std::ostream* progress = nullptr;  ///< progress lines, or none
    std::string config_text;           ///< the config as read, copied into the output
    std::string command_line;          ///< for the provenance file
    /// Discard the checkpoints and settled beds found in out_dir and start over; without it
    /// checkpoints of another config (another hash) are refused.
    bool restart = false;
};

struct CampaignSummary {
    int points = 0;          ///< points in the campaign
    int resumed_points = 0;  ///< taken from checkpoints instead of simulated
    int converged = 0;
    int limit_cycle = 0;
    int closest = 0;
    long long periods_simulated = 0;
    double wall_time_s = 0.0;
};

/// The structure of an arrangement: gravity set, mounting blocks added at the damper points,
/// and the particles of rigid dampers (of every damper when all_particles_rigid) as rigid
/// masses at the centre of a settled bed.
structure::StructureSpec arrangement_structure(const CampaignConfig& config,
                                               const ArrangementSpec& arrangement,
                                               bool all_particles_rigid);

/// Runs (or resumes) the campaign of `config` into options.out_dir. Finished points found in
/// out_dir/checkpoints are not recomputed; the final files are the same as an uninterrupted
/// run's. Throws config::ConfigException when the config cannot run a campaign (no levels,
/// no arrangement) or when out_dir holds checkpoints of another config (nothing simulated),
/// dem::SimulationError when a guard fires, std::runtime_error otherwise.
CampaignSummary run_campaign(const CampaignConfig& config, const CampaignRunOptions& options);

}  // namespace sb::bench

// What a finished campaign writes: the recording directory (recording.toml, points.csv,
// damping.csv, series/), UFF58 transfer functions, the controller log, the config as read,
// provenance, and SVG plots when gnuplot is installed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/coupled_specimen.hpp"
#include "bench/specimen_plant.hpp"
#include "control/result.hpp"
#include "identification/recording.hpp"

namespace sb::bench {

/// One sweep's results and what was chosen for it.
struct SweepRecord {
    std::string key;
    double first_mode_hz = 0.0;
    std::vector<double> frequencies_hz;  ///< the sweep's grid, in the order stepped
    std::vector<std::string> log;        ///< derived settings (stiffness, time step)
    std::vector<identification::PointRow> rows;
    std::vector<std::string> control_log;  ///< control.csv rows
};

struct CampaignOutput {
    const CampaignConfig* config = nullptr;
    const CampaignRunOptions* options = nullptr;
    std::vector<std::string> channel_points;  ///< control point first
    std::vector<SweepRecord> sweeps;          ///< in campaign order
    int threads = 1;
    std::string config_hash;  ///< of the resolved config
};

/// Writes every output file of the campaign into options->out_dir.
void write_campaign_output(const CampaignOutput& output);

/// Writes the steady window of a point as series/<key>_<index>.csv; returns its path
/// relative to the recording directory.
std::string write_series(const std::filesystem::path& out_dir, const std::string& key, int index,
                         const CoupledSpecimen& specimen, const SpecimenPlant& plant,
                         const control::PointResult& result);

}  // namespace sb::bench

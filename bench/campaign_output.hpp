// What a finished campaign writes: the recording directory (recording.toml, points.csv,
// damping.csv), UFF58 transfer functions, the controller log, the energy per point, the config
// as read and as resolved, provenance, and SVG plots when gnuplot is installed.
#pragma once

#include <filesystem>
#include <string>

#include "bench/campaign.hpp"

namespace sb::bench {

/// Where and with what a recording directory is written.
struct RecordingDirectory {
    std::filesystem::path out_dir;
    std::string config_text;   ///< the config as read (config.toml)
    std::string command_line;  ///< for provenance.toml
};

/// Writes every file of `result` into directory.out_dir (series/ and vtk/ files are the
/// store's: a FileCheckpointStore in the same directory has written them).
void write_campaign_output(const CampaignConfig& config, const CampaignResult& result,
                           const RecordingDirectory& directory);

/// The header of energy.csv for dampers with `layers` dissipation layers.
std::string energy_csv_header(int layers);

}  // namespace sb::bench

// What a sweep has finished, and the state to go on from: written after every point.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/coupled_specimen.hpp"
#include "identification/recording.hpp"

namespace sb::bench {

struct SweepCheckpoint {
    int points_done = 0;          ///< finished frequencies of the sweep
    double next_amplitude = 0.0;  ///< the warm-start amplitude the last point ended with
    SpecimenState state;          ///< the specimen after the last finished point
    std::vector<identification::PointRow> rows;  ///< the finished points
    std::vector<std::string> control_log;        ///< per point: how the controller got there
};

/// Text form; every number as a hexadecimal float, so reading it back is exact.
std::string serialize_checkpoint(const SweepCheckpoint& checkpoint);

/// Reads serialize_checkpoint()'s text; a damaged file throws std::runtime_error naming the
/// file and line.
SweepCheckpoint parse_checkpoint(const std::string& text, const std::string& file_name);

/// Writes `text` to `file` through a temporary file and a rename, so an interruption leaves
/// either the old or the new file, never half of one.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

/// The whole content of a file.
std::string read_file(const std::filesystem::path& file);

}  // namespace sb::bench

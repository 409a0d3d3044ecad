// What a sweep has finished, and the state to go on from: written after every point.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "bench/coupled_specimen.hpp"
#include "bench/sweep_runner.hpp"
#include "dem/setup.hpp"
#include "identification/recording.hpp"
#include "identification/welch.hpp"

namespace sb::bench {

/// Where a random test (campaign.random) stands: bench/random_test.hpp.
struct RandomProgress {
    int level_segments = 0;   ///< segments run to bring the level in
    bool level_done = false;  ///< the averaging has begun
    double drive_rms = 0.0;   ///< the drive's RMS now [N]
    double level_rms = 0.0;   ///< the control channel's band RMS in the last level segment
    int halves = 0;           ///< half segments of the averaging run
    /// The last half segment's samples (the reference first, then every channel): the first
    /// half of the next segment, which overlaps it.
    std::vector<std::vector<double>> tail;
    identification::WelchSums sums;  ///< the averaging's spectra so far
};

struct SweepCheckpoint {
    /// Hash of the resolved config that wrote it (bench/resolved_config.hpp): a checkpoint
    /// is only ever resumed by the same config.
    std::string config_hash;
    /// The numbers the bench chose beyond the config (each DEM damper's automatic contact
    /// stiffness and time step, the coupled step's limit) as `key=value` words: a checkpoint
    /// resumes only where this build chooses the same (bench/sweep_runner.cpp).
    std::string numerics;
    int points_done = 0;  ///< finished frequencies of the sweep
    /// The warm-start amplitude: the drive the last point would still have needed for the
    /// target (its final drive for a fixed drive).
    double next_amplitude = 0.0;
    SpecimenState state;                         ///< the specimen after the last finished point
    std::vector<identification::PointRow> rows;  ///< the finished points
    std::vector<std::string> control_log;        ///< per point: how the controller got there
    std::vector<std::string> energy_log;         ///< energy.csv rows of the finished points
    /// A run from rest (no points): the periods it has run and their rows (SweepResult).
    int transient_periods = 0;
    std::vector<std::string> transient_series;
    std::vector<std::string> transient_envelope;
    /// A random test: where it stands (finished when `points_done` is its lines' count).
    std::optional<RandomProgress> random;
};

/// A checkpoint that cannot be resumed: truncated, corrupted (its checksum does not match its
/// content), of another format, or not a checkpoint. what() is `file:line: message` (line 0
/// when it is about the whole file).
class CheckpointError : public std::runtime_error {
  public:
    CheckpointError(std::string file, int line, std::string message);
    [[nodiscard]] const std::string& file() const noexcept { return file_; }
    [[nodiscard]] int line() const noexcept { return line_; }
    /// The message without the place.
    [[nodiscard]] const std::string& message() const noexcept { return message_; }

  private:
    std::string file_;
    int line_;
    std::string message_;
};

/// Text form; every number as a hexadecimal float, so reading it back is exact. A DEM
/// damper's state is written whole (particles, tangential contact springs, lock, clock), so a
/// resumed sweep continues exactly where the interrupted one was. The last line is the
/// checksum of everything before it (seal_checkpoint).
std::string serialize_checkpoint(const SweepCheckpoint& checkpoint);

/// A pour's progress (dem::PourProgress: the settling bed with its springs, the insertion
/// generator, where the settle stands) as text, every number exact, sealed with a checksum as
/// a sweep checkpoint is: a long pour continues from it bitwise (bench/settled_bed.hpp).
std::string serialize_pour_progress(const dem::PourProgress& progress);

/// Reads serialize_pour_progress()'s text; damage throws CheckpointError naming `file_name`.
dem::PourProgress parse_pour_progress(const std::string& text, const std::string& file_name);

/// Reads serialize_checkpoint()'s text. The checksum is checked first: a file cut short, a
/// changed byte, a file of an older format throw CheckpointError naming the file (and the
/// line where it applies); so does content that does not fit together (finished points
/// without their rows).
SweepCheckpoint parse_checkpoint(const std::string& text, const std::string& file_name);

/// `content` followed by its checksum line: `checksum fnv1a64 <16 hexadecimal digits>`, the
/// 64-bit FNV-1a of every byte before that line.
std::string seal_checkpoint(std::string_view content);

/// The text without its checksum line (the whole text when its last line is none).
std::string_view checkpoint_content(std::string_view text);

/// A finished sweep's results in the same text form (every number exact): how a sweep run in
/// another process comes back to the one that assembles the campaign.
std::string serialize_sweep_result(const SweepResult& result);

/// Reads serialize_sweep_result()'s text; damaged text throws std::runtime_error naming
/// `source` and the line.
SweepResult parse_sweep_result(const std::string& text, const std::string& source);

/// The config hash a checkpoint's text was written with; empty when the text has none (a
/// checkpoint of an older format, or not a checkpoint).
std::string checkpoint_config_hash(const std::string& text);

}  // namespace sb::bench

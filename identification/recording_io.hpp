// Readers and writers of the recording directory (formats.md): recording.toml, points.csv,
// damping.csv and series/*.csv. Every reader throws FileError (file:line:col: message).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "identification/recording.hpp"

namespace sb::identification {

/// Reads recording.toml, points.csv and damping.csv (if present) of a directory. Errors:
/// unknown keys, bad enumerations, not exactly one reference or more than one control channel
/// (recording.toml); missing, unknown or duplicated columns, cells that are not finite
/// numbers, bad status (points.csv). Every series a row names is loaded into
/// PointRow::history and checked: its path is relative and stays inside the directory, the
/// file exists, time_s increases uniformly, its columns are channels of recording.toml, it
/// spans a whole number of periods of the row's frequency with more than two samples per
/// period.
/// A channel whose three cells (C_rms, C_re, C_im) are all empty is computed from the series
/// (fundamental and rms over whole periods, ChannelValue::from_series), and so are its
/// harmonic ratios unless their cells hold numbers. The harmonic columns C_h2, C_h3 are
/// optional but come as a pair; an empty cell is NaN, a number must be finite and >= 0.
Recording read_recording(const std::filesystem::path& directory);

/// Reads recording.toml only (info and channels).
Recording read_recording_toml(const std::filesystem::path& file);

/// Reads points.csv against the channels of `recording` and appends to recording.points;
/// series paths are relative to the file's directory (see read_recording).
void read_points_csv(const std::filesystem::path& file, Recording& recording);

/// Reads damping.csv. points_used, frequencies_used_hz (';'-separated) and points_skipped are
/// optional (older files, other tools): absent or empty, they read as 0, none, 0.
std::vector<DampingRow> read_damping_csv(const std::filesystem::path& file);

/// Reads a time history: header `time_s,<channel>,...`, numbers, uniform increasing sampling
/// (a step differing from the mean by more than 1e-6 relative is an error). Lines starting
/// with `#` are comments.
TimeHistory read_time_history_csv(const std::filesystem::path& file);

/// The same, and every column after time_s must be one of `known_channels` (an error at the
/// header cell otherwise); an empty list accepts any name.
TimeHistory read_time_history_csv(const std::filesystem::path& file,
                                  const std::vector<std::string>& known_channels);

/// Writes recording.toml, points.csv, (if non-empty) damping.csv and the loaded series of the
/// points (PointRow::history, at PointRow::series); creates the directories. Every writer here
/// writes its file whole or not at all (through a rename) and throws sb::FileWriteError
/// (core/text_file.hpp) naming the file when it cannot be written.
/// Numbers are written with 17 significant digits so a write–read cycle is exact.
void write_recording(const std::filesystem::path& directory, const Recording& recording);

/// Writes recording.toml (info and channels, in order).
void write_recording_toml(const std::filesystem::path& file, const Recording& recording);

/// Writes points.csv: fixed columns, then C_rms, C_re, C_im per channel, then C_h2, C_h3 per
/// channel that has a finite harmonic ratio at any row (NaN as an empty cell).
void write_points_csv(const std::filesystem::path& file, const Recording& recording);

/// Writes damping.csv: arrangement, level_g, natural_frequency_hz, damping_ratio, method,
/// points_used, frequencies_used_hz (';'-separated), points_skipped.
void write_damping_csv(const std::filesystem::path& file, const std::vector<DampingRow>& rows);

/// Writes a time history CSV.
void write_time_history_csv(const std::filesystem::path& file, const TimeHistory& history);
/// The same as text.
std::string time_history_csv_text(const TimeHistory& history);

}  // namespace sb::identification

// The recording directory as a whole.
#include "identification/recording_io.hpp"

#include "core/text_file.hpp"
#include "identification/file_error.hpp"

namespace sb::identification {

std::size_t Recording::reference_index() const {
    for (std::size_t i = 0; i < channels.size(); ++i) {
        if (channels[i].role == ChannelRole::reference) return i;
    }
    return channels.size();
}

std::size_t Recording::channel_index(const std::string& name) const {
    for (std::size_t i = 0; i < channels.size(); ++i) {
        if (channels[i].name == name) return i;
    }
    return channels.size();
}

Recording read_recording(const std::filesystem::path& dir) {
    if (!std::filesystem::is_directory(dir)) throw FileError(dir.string(), 0, 0, "not a directory");
    Recording rec = read_recording_toml(dir / "recording.toml");
    const auto points = dir / "points.csv";
    const auto damping = dir / "damping.csv";
    if (std::filesystem::exists(points)) read_points_csv(points, rec);
    if (std::filesystem::exists(damping)) rec.damping = read_damping_csv(damping);
    if (rec.points.empty() && rec.damping.empty()) {
        throw FileError(points.string(), 0, 0, "neither points.csv nor damping.csv has any row");
    }
    return rec;
}

void write_recording(const std::filesystem::path& dir, const Recording& rec) {
    create_directories_for_writing(dir);
    write_recording_toml(dir / "recording.toml", rec);
    write_points_csv(dir / "points.csv", rec);
    if (!rec.damping.empty()) write_damping_csv(dir / "damping.csv", rec.damping);
    for (const auto& p : rec.points) {
        if (p.series.empty() || p.history.time_s.empty()) continue;
        const auto file = dir / p.series;
        create_directories_for_writing(file.parent_path());
        write_time_history_csv(file, p.history);
    }
}

}  // namespace sb::identification

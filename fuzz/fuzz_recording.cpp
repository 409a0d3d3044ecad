// Fuzz target: a recording directory, as `shakerbench identify DIR` reads it. The input is
// split at lines "@@@" into recording.toml, points.csv, damping.csv and series/s.csv (a part
// that is empty or not there is a file that is not there). A clean end is the recording or
// identification::FileError; every point must hold a finite value for every channel.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string_view>
#include <system_error>

#include "identification/file_error.hpp"
#include "identification/recording_io.hpp"
#include "scratch.hpp"

namespace {

constexpr std::string_view kSeparator = "\n@@@\n";
constexpr const char* kFiles[] = {"recording.toml", "points.csv", "damping.csv", "series/s.csv"};

[[noreturn]] void wrong(const char* what) {
    std::fprintf(stderr, "recording reader: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string_view rest(reinterpret_cast<const char*>(data), size);
    const auto dir = sb::fuzz::scratch_dir() / "recording";
    bool more = true;
    for (const char* name : kFiles) {
        const auto file = dir / name;
        const auto end = more ? rest.find(kSeparator) : 0;
        const std::string_view part = more ? rest.substr(0, end) : std::string_view();
        if (part.empty()) {
            std::error_code ignored;
            std::filesystem::remove(file, ignored);
        } else {
            sb::fuzz::write_bytes(file, part);
        }
        more = more && end != std::string_view::npos;
        if (more) rest.remove_prefix(end + kSeparator.size());
    }
    sb::identification::Recording recording;
    try {
        recording = sb::identification::read_recording(dir);
    } catch (const sb::identification::FileError&) {
        return 0;
    }
    for (const auto& point : recording.points) {
        if (point.values.size() != recording.channels.size()) wrong("a value per channel");
        for (const auto& v : point.values) {
            if (!std::isfinite(v.rms) || !std::isfinite(v.amplitude.real()) ||
                !std::isfinite(v.amplitude.imag())) {
                wrong("a value that is not finite");
            }
        }
    }
    return 0;
}

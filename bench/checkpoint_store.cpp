// The three checkpoint stores.
#include "bench/checkpoint_store.hpp"

#include <algorithm>
#include <system_error>

#include "bench/sweep_checkpoint.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"

namespace sb::bench {

namespace fs = std::filesystem;

FileCheckpointStore::FileCheckpointStore(fs::path directory) : directory_(std::move(directory)) {}

void FileCheckpointStore::open(const std::string& config_hash, bool restart) {
    hash_ = config_hash;
    if (restart) {
        // Everything computed for another config, or for this one from the start.
        for (const char* dir : {"checkpoints", "settled", "series", "vtk"}) {
            fs::remove_all(directory_ / dir);
        }
        return;
    }
    // Checkpoints another config wrote would be taken as this config's results.
    const fs::path dir = directory_ / "checkpoints";
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.is_regular_file() && entry.path().extension() == ".txt") {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    std::vector<config::ConfigError> problems;
    for (const auto& file : files) {
        const std::string found = checkpoint_config_hash(read_text_file(file));
        if (found == config_hash) continue;
        config::ConfigError e;
        e.file = file.string();
        e.key_path = "config_hash";
        e.value = found.empty() ? "(none: an older checkpoint format)" : "\"" + found + "\"";
        e.constraint =
            "was written by another config; this config's hash is \"" + config_hash + "\"";
        e.meaning = "nothing was simulated: run again with --restart to discard " +
                    directory_.string() + "'s checkpoints and settled beds, or give another --out";
        problems.push_back(std::move(e));
    }
    if (!problems.empty()) throw config::ConfigException(std::move(problems));
}

std::optional<std::string> FileCheckpointStore::load_checkpoint(const std::string& sweep_key) {
    const fs::path file = directory_ / "checkpoints" / (sweep_key + ".txt");
    if (!fs::exists(file)) return std::nullopt;
    return read_text_file(file);
}

void FileCheckpointStore::save_checkpoint(const std::string& sweep_key, const std::string& text) {
    save_file("checkpoints/" + sweep_key + ".txt", text);
}

std::optional<std::string> FileCheckpointStore::load_bed(const std::string& bed_key) {
    // The bed's file name carries the config's hash: no other config starts from it.
    const fs::path file = directory_ / "settled" / (bed_key + "_" + hash_ + ".csv");
    if (!fs::exists(file)) return std::nullopt;
    return read_text_file(file);
}

void FileCheckpointStore::save_bed(const std::string& bed_key, const std::string& text) {
    save_file("settled/" + bed_key + "_" + hash_ + ".csv", text);
}

void FileCheckpointStore::save_file(const std::string& relative_path, const std::string& text) {
    const fs::path file = directory_ / relative_path;
    fs::create_directories(file.parent_path());
    write_file_atomically(file, text);
}

void MemoryCheckpointStore::open(const std::string& config_hash, bool restart) {
    std::lock_guard<std::mutex> lock(mutex_);
    // Entries are keyed by the hash: one store serves many configs (a calibration's).
    hash_ = config_hash;
    if (restart) {
        const std::string prefix = hash_ + "/";
        for (auto* map : {&checkpoints_, &beds_, &files_}) {
            std::erase_if(*map, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
        }
    }
}

namespace {
std::optional<std::string> find(const std::map<std::string, std::string>& map,
                                const std::string& key) {
    const auto it = map.find(key);
    if (it == map.end()) return std::nullopt;
    return it->second;
}
}  // namespace

std::optional<std::string> MemoryCheckpointStore::load_checkpoint(const std::string& sweep_key) {
    std::lock_guard<std::mutex> lock(mutex_);
    return find(checkpoints_, hash_ + "/" + sweep_key);
}

void MemoryCheckpointStore::save_checkpoint(const std::string& sweep_key, const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    checkpoints_[hash_ + "/" + sweep_key] = text;
}

std::optional<std::string> MemoryCheckpointStore::load_bed(const std::string& bed_key) {
    std::lock_guard<std::mutex> lock(mutex_);
    return find(beds_, hash_ + "/" + bed_key);
}

void MemoryCheckpointStore::save_bed(const std::string& bed_key, const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    beds_[hash_ + "/" + bed_key] = text;
}

void MemoryCheckpointStore::save_file(const std::string& relative_path, const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    files_[hash_ + "/" + relative_path] = text;
}

std::map<std::string, std::string> MemoryCheckpointStore::files() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::map<std::string, std::string> out;
    const std::string prefix = hash_ + "/";
    for (const auto& [key, text] : files_) {
        if (key.rfind(prefix, 0) == 0) out[key.substr(prefix.size())] = text;
    }
    return out;
}

}  // namespace sb::bench

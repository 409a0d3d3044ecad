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
        for (const char* dir : {"checkpoints", "settled", "results", "series", "vtk"}) {
            std::error_code error;
            fs::remove_all(directory_ / dir, error);
            if (error) throw FileWriteError(directory_ / dir, error);
        }
    }
    check_writable();
    remove_partial_files();
    if (restart) return;
    // A checkpoint another config wrote would be taken as this config's results, a damaged
    // one would be resumed from whatever its damage left: both are refused before anything
    // runs, every file at once.
    const fs::path dir = directory_ / "checkpoints";
    std::vector<fs::path> files;
    std::error_code error;  // no folder: no checkpoint yet
    for (auto it = fs::directory_iterator(dir, error); !error && it != fs::directory_iterator();
         it.increment(error)) {
        if (it->is_regular_file() && it->path().extension() == ".txt") {
            files.push_back(it->path());
        }
    }
    std::sort(files.begin(), files.end());
    const std::string way_out = "nothing was simulated: run again with --restart to discard " +
                                directory_.string() + "'s checkpoints and settled beds, or give " +
                                "another --out";
    std::vector<config::ConfigError> problems;
    for (const auto& file : files) {
        config::ConfigError e;
        e.file = file.string();
        try {
            const SweepCheckpoint checkpoint =
                parse_checkpoint(read_text_file(file), file.string());
            if (checkpoint.config_hash == config_hash) continue;
            e.key_path = "config_hash";
            e.value = "\"" + checkpoint.config_hash + "\"";
            e.constraint =
                "was written by another config; this config's hash is \"" + config_hash + "\"";
            e.meaning = way_out;
        } catch (const CheckpointError& damaged) {
            e.key_path = "(checkpoint)";
            e.constraint = (damaged.line() > 0 ? "line " + std::to_string(damaged.line()) + ": "
                                               : std::string()) +
                           damaged.message();
            e.meaning = "cannot be resumed: delete " + file.string() +
                        " to compute that sweep again, or run again with --restart to discard " +
                        "every checkpoint of " + directory_.string();
        }
        problems.push_back(std::move(e));
    }
    if (!problems.empty()) throw config::ConfigException(std::move(problems));
}

void FileCheckpointStore::check_writable() const {
    // A directory that cannot take a checkpoint is refused before anything is simulated,
    // rather than after the first point.
    const fs::path dir = directory_ / "checkpoints";
    std::error_code ignored;
    const bool existed = fs::exists(dir, ignored);
    create_directories_for_writing(dir);
    const fs::path probe = dir / ".write-probe";
    try {
        write_file_atomically(probe, "");
    } catch (const FileWriteError& e) {
        throw FileWriteError(dir, e.reason());
    }
    fs::remove(probe, ignored);
    // A folder made only for the probe goes again (a characterisation keeps no sweep
    // checkpoints); the first save makes it again when needed.
    if (!existed) fs::remove(dir, ignored);
}

void FileCheckpointStore::remove_partial_files() const {
    // What a run killed while writing left in the store's folders: never read, and not part of
    // a recording. Only these folders: the recording directory may be any folder, whose other
    // .partial files are not ours (those of the recording's own files are overwritten by the
    // next write of the same file).
    std::vector<fs::path> partial;
    for (const char* dir : {"checkpoints", "settled", "results", "series", "vtk"}) {
        std::error_code error;
        for (auto it = fs::directory_iterator(directory_ / dir, error);
             !error && it != fs::directory_iterator(); it.increment(error)) {
            if (it->path().extension() == ".partial") partial.push_back(it->path());
        }
    }
    std::error_code ignored;
    for (const auto& file : partial) fs::remove(file, ignored);
}

std::string FileCheckpointStore::checkpoint_name(const std::string& sweep_key) const {
    return (directory_ / "checkpoints" / (sweep_key + ".txt")).string();
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
    std::error_code ignored;  // the progress is of no use once the bed is there
    fs::remove(progress_name(Unfinished::bed, bed_key), ignored);
}

std::string FileCheckpointStore::progress_file(Unfinished work, const std::string& key) const {
    return work == Unfinished::bed ? "settled/" + key + "_" + hash_ + ".settling.txt"
                                   : "results/" + key + "_" + hash_ + ".progress.txt";
}

std::string FileCheckpointStore::progress_name(Unfinished work, const std::string& key) const {
    return (directory_ / progress_file(work, key)).string();
}

std::optional<std::string> FileCheckpointStore::load_progress(Unfinished work,
                                                              const std::string& key) {
    const fs::path file = progress_name(work, key);
    if (!fs::exists(file)) return std::nullopt;
    return read_text_file(file);
}

void FileCheckpointStore::save_progress(Unfinished work, const std::string& key,
                                        const std::string& text) {
    save_file(progress_file(work, key), text);
}

std::string FileCheckpointStore::result_name(const std::string& result_key) const {
    return (directory_ / "results" / (result_key + "_" + hash_ + ".txt")).string();
}

std::optional<std::string> FileCheckpointStore::load_result(const std::string& result_key) {
    // As a bed's, the file name carries the config's hash.
    const fs::path file = result_name(result_key);
    if (!fs::exists(file)) return std::nullopt;
    return read_text_file(file);
}

void FileCheckpointStore::save_result(const std::string& result_key, const std::string& text) {
    save_file("results/" + result_key + "_" + hash_ + ".txt", text);
    std::error_code ignored;  // as a bed's: the run's progress is of no use once it has ended
    fs::remove(progress_name(Unfinished::result, result_key), ignored);
}

void FileCheckpointStore::save_file(const std::string& relative_path, const std::string& text) {
    const fs::path file = directory_ / relative_path;
    create_directories_for_writing(file.parent_path());
    write_file_atomically(file, text);
}

void MemoryCheckpointStore::open(const std::string& config_hash, bool restart) {
    std::lock_guard<std::mutex> lock(mutex_);
    // Entries are keyed by the hash: one store serves many configs (a calibration's).
    hash_ = config_hash;
    if (restart) {
        const std::string prefix = hash_ + "/";
        for (auto* map : {&checkpoints_, &beds_, &progress_, &results_, &files_}) {
            std::erase_if(*map, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
        }
    }
}

namespace {
/// Under the config's hash, as every entry (a restart drops them by it), then the kind.
std::string progress_key(const std::string& hash, Unfinished work, const std::string& key) {
    return hash + (work == Unfinished::bed ? "/bed/" : "/result/") + key;
}

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
    progress_.erase(progress_key(hash_, Unfinished::bed, bed_key));
}

std::optional<std::string> MemoryCheckpointStore::load_progress(Unfinished work,
                                                                const std::string& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    return find(progress_, progress_key(hash_, work, key));
}

void MemoryCheckpointStore::save_progress(Unfinished work, const std::string& key,
                                          const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    progress_[progress_key(hash_, work, key)] = text;
}

std::optional<std::string> MemoryCheckpointStore::load_result(const std::string& result_key) {
    std::lock_guard<std::mutex> lock(mutex_);
    return find(results_, hash_ + "/" + result_key);
}

void MemoryCheckpointStore::save_result(const std::string& result_key, const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    results_[hash_ + "/" + result_key] = text;
    progress_.erase(progress_key(hash_, Unfinished::result, result_key));
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

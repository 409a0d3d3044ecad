// Where a campaign keeps what it has finished: every sweep's checkpoint, the settled beds and
// the per-point files (series, bed snapshots). Files for the CLI, memory for callers that
// run campaigns in a loop (calibration), none when nothing needs to survive the call.
#pragma once

#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace sb::bench {

/// What a saved progress belongs to (CheckpointStore::load_progress).
enum class Unfinished {
    bed,     ///< a bed settling
    result,  ///< a characterisation run
};

/// A store is opened for one config (its hash) and then read and written by the sweeps,
/// possibly from several threads at once (each sweep its own keys). Texts are stored as
/// they are: a checkpoint and a bed are always read back through their text form, so a
/// resumed sweep repeats the arithmetic of an uninterrupted one.
class CheckpointStore {
  public:
    virtual ~CheckpointStore() = default;

    /// Before anything runs: with `restart`, forgets everything stored; otherwise refuses
    /// (config::ConfigException naming both hashes, nothing simulated) to resume what a config
    /// with another hash left.
    virtual void open(const std::string& config_hash, bool restart) = 0;

    /// The checkpoint text of a sweep, if one was saved.
    virtual std::optional<std::string> load_checkpoint(const std::string& sweep_key) = 0;
    virtual void save_checkpoint(const std::string& sweep_key, const std::string& text) = 0;

    /// A settled bed (CSV text), by sweep and damper.
    virtual std::optional<std::string> load_bed(const std::string& bed_key) = 0;
    virtual void save_bed(const std::string& bed_key, const std::string& text) = 0;

    /// Work long enough to save its progress as it goes, kept under the key of what it will
    /// give: a bed still settling (serialize_pour_progress()'s text, by the bed's key; saving
    /// the settled bed drops it) and a characterisation run between its periods
    /// (serialize_run_progress()'s text, by the result's key; saving the result drops it). An
    /// interrupted pour or run continues from it. A store that keeps none returns nothing.
    virtual std::optional<std::string> load_progress(Unfinished /*work*/,
                                                     const std::string& /*key*/) {
        return std::nullopt;
    }
    virtual void save_progress(Unfinished /*work*/, const std::string& /*key*/,
                               const std::string& /*text*/) {}
    /// How messages name a progress (its file, for a file store).
    [[nodiscard]] virtual std::string progress_name(Unfinished work, const std::string& key) const {
        return key + (work == Unfinished::bed ? " (settling)" : " (in progress)");
    }

    /// A finished unit of work that is not a sweep (a characterisation run: one grid point on
    /// one filling), as its result text, by key.
    virtual std::optional<std::string> load_result(const std::string& result_key) = 0;
    virtual void save_result(const std::string& result_key, const std::string& text) = 0;

    /// A file a point produces (a series, a bed snapshot), by its path relative to the
    /// recording directory ("series/H-0_1g_3.csv").
    virtual void save_file(const std::string& relative_path, const std::string& text) = 0;

    /// How messages name a sweep's checkpoint (its file, for a file store).
    [[nodiscard]] virtual std::string checkpoint_name(const std::string& sweep_key) const {
        return sweep_key;
    }
    /// How messages name a stored result (its file, for a file store).
    [[nodiscard]] virtual std::string result_name(const std::string& result_key) const {
        return result_key;
    }
};

/// Checkpoints in DIR/checkpoints/<sweep>.txt, beds in DIR/settled/<bed>_<hash>.csv (while
/// settling, DIR/settled/<bed>_<hash>.settling.txt), results in DIR/results/<key>_<hash>.txt
/// (while running, DIR/results/<key>_<hash>.progress.txt), files under DIR: the recording directory
/// the CLI writes. Every file goes through a rename, so a kill never leaves half of one; a file
/// that cannot be written throws sb::FileWriteError naming it, and the files written before stay as
/// they were.
class FileCheckpointStore : public CheckpointStore {
  public:
    explicit FileCheckpointStore(std::filesystem::path directory);
    /// Besides refusing another config's checkpoints: refuses (config::ConfigException, every
    /// file named, nothing simulated) a checkpoint that is damaged (bench::CheckpointError:
    /// cut short, corrupted, of another format); throws sb::FileWriteError when DIR/checkpoints
    /// cannot be written; removes the FILE.partial files a killed run left in checkpoints/,
    /// settled/, results/, series/ and vtk/.
    void open(const std::string& config_hash, bool restart) override;
    [[nodiscard]] std::string checkpoint_name(const std::string& sweep_key) const override;
    [[nodiscard]] std::string result_name(const std::string& result_key) const override;
    std::optional<std::string> load_checkpoint(const std::string& sweep_key) override;
    void save_checkpoint(const std::string& sweep_key, const std::string& text) override;
    std::optional<std::string> load_bed(const std::string& bed_key) override;
    void save_bed(const std::string& bed_key, const std::string& text) override;
    std::optional<std::string> load_progress(Unfinished work, const std::string& key) override;
    void save_progress(Unfinished work, const std::string& key, const std::string& text) override;
    [[nodiscard]] std::string progress_name(Unfinished work, const std::string& key) const override;
    std::optional<std::string> load_result(const std::string& result_key) override;
    void save_result(const std::string& result_key, const std::string& text) override;
    void save_file(const std::string& relative_path, const std::string& text) override;
    [[nodiscard]] const std::filesystem::path& directory() const { return directory_; }

  private:
    void check_writable() const;
    void remove_partial_files() const;
    /// A progress's file, relative to the directory.
    [[nodiscard]] std::string progress_file(Unfinished work, const std::string& key) const;

    std::filesystem::path directory_;
    std::string hash_;
};

/// Everything in memory: a second run with the same store resumes every finished sweep.
class MemoryCheckpointStore : public CheckpointStore {
  public:
    void open(const std::string& config_hash, bool restart) override;
    std::optional<std::string> load_checkpoint(const std::string& sweep_key) override;
    void save_checkpoint(const std::string& sweep_key, const std::string& text) override;
    std::optional<std::string> load_bed(const std::string& bed_key) override;
    void save_bed(const std::string& bed_key, const std::string& text) override;
    std::optional<std::string> load_progress(Unfinished work, const std::string& key) override;
    void save_progress(Unfinished work, const std::string& key, const std::string& text) override;
    std::optional<std::string> load_result(const std::string& result_key) override;
    void save_result(const std::string& result_key, const std::string& text) override;
    void save_file(const std::string& relative_path, const std::string& text) override;
    /// The files the points produced, by relative path.
    [[nodiscard]] std::map<std::string, std::string> files() const;

  private:
    mutable std::mutex mutex_;
    std::string hash_;
    std::map<std::string, std::string> checkpoints_;
    std::map<std::string, std::string> beds_;
    std::map<std::string, std::string> progress_;  ///< by kind, hash and key
    std::map<std::string, std::string> results_;
    std::map<std::string, std::string> files_;
};

/// Keeps nothing: every call simulates everything.
class NoCheckpointStore : public CheckpointStore {
  public:
    void open(const std::string&, bool) override {}
    std::optional<std::string> load_checkpoint(const std::string&) override { return {}; }
    void save_checkpoint(const std::string&, const std::string&) override {}
    std::optional<std::string> load_bed(const std::string&) override { return {}; }
    void save_bed(const std::string&, const std::string&) override {}
    std::optional<std::string> load_result(const std::string&) override { return {}; }
    void save_result(const std::string&, const std::string&) override {}
    void save_file(const std::string&, const std::string&) override {}
};

}  // namespace sb::bench

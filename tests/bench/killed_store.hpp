// Memory stores whose process "dies" while saving: for the tests of work that continues from
// its progress after a kill (a pour, a characterisation run) or from a sweep's checkpoint.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "bench/checkpoint_store.hpp"

namespace sb::bench::testing {

/// What a "killed" process throws.
struct Killed {};

/// Throws Killed right after its `kill_at`-th save of a progress of kind `work` (never for
/// 0), counting the saves.
class KilledAfterSaves : public MemoryCheckpointStore {
  public:
    explicit KilledAfterSaves(int kill_at, Unfinished work = Unfinished::bed)
        : kill_at_(kill_at), work_(work) {}
    void save_progress(Unfinished work, const std::string& key, const std::string& text) override {
        MemoryCheckpointStore::save_progress(work, key, text);
        if (work == work_ && ++saves == kill_at_) throw Killed{};
    }
    /// Dies again after the `kill_at`-th save counted from the first (0: never): the next
    /// process of a run killed several times over.
    void kill_at(int kill_at) { kill_at_ = kill_at; }
    int saves = 0;

  private:
    int kill_at_;
    Unfinished work_;
};

/// Fails (as a killed process would) before its `fail_at`-th sweep checkpoint lands (never
/// for -1), keeping every checkpoint that landed.
class InterruptedStore : public MemoryCheckpointStore {
  public:
    explicit InterruptedStore(int fail_at = -1) : fail_at_(fail_at) {}
    void save_checkpoint(const std::string& key, const std::string& text) override {
        if (++attempts_ == fail_at_) throw std::runtime_error("interrupted");
        MemoryCheckpointStore::save_checkpoint(key, text);
        saved.push_back(text);
        last_key_ = key;
    }
    void stop_failing() { fail_at_ = -1; }
    /// The sweep whose checkpoint landed last.
    [[nodiscard]] const std::string& last_key() const { return last_key_; }
    /// Every checkpoint that landed, in order.
    std::vector<std::string> saved;

  private:
    int fail_at_;
    int attempts_ = 0;
    std::string last_key_;
};

}  // namespace sb::bench::testing

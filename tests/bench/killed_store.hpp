// A memory store whose process "dies" while saving progress: for the tests of work that
// continues from its progress after a kill (a pour, a characterisation run).
#pragma once

#include <string>

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
    int saves = 0;

  private:
    int kill_at_;
    Unfinished work_;
};

}  // namespace sb::bench::testing

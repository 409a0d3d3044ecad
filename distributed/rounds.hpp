// Rounds of independent evaluations over the ranks of a run (a calibration's batches): rank 0
// decides each round's inputs as it goes, every rank (rank 0 included) evaluates some of them
// and rank 0 gets every result, as text, in input order. The ranks other than 0 wait between
// rounds until rank 0 says there are no more.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "distributed/transport.hpp"

namespace sb::distributed {

/// Evaluates one input (text) with `threads` threads and returns its result (text). An
/// exception fails that evaluation with its message. Called from several threads at once when
/// a rank evaluates several inputs at a time.
using TextEvaluation = std::function<std::string(const std::string& input, int threads)>;

/// Rank 0's side (or a process alone, transport null).
class DistributedRounds {
  public:
    /// Each rank evaluates `at_once` inputs at a time (on as many threads), each with
    /// `threads` threads.
    DistributedRounds(Transport* transport, int threads, TextEvaluation evaluate, int at_once = 1);
    /// Tells the other ranks that there are no more rounds, if finish() was not called.
    ~DistributedRounds();
    DistributedRounds(const DistributedRounds&) = delete;
    DistributedRounds& operator=(const DistributedRounds&) = delete;

    /// One round: every input evaluated on whichever rank is free, the results in input
    /// order. Throws std::runtime_error with an evaluation's message when one failed.
    /// `on_result`, if given, gets each successful result as it arrives (input index, text),
    /// so that a caller can keep finished work of a round that later fails or is killed.
    std::vector<std::string> run(
        const std::vector<std::string>& inputs,
        const std::function<void(std::size_t input, const std::string& result)>& on_result = {});
    /// Tells the other ranks that there are no more rounds.
    void finish();
    /// Evaluations each rank ran so far (index: rank).
    [[nodiscard]] const std::vector<int>& evaluations_per_rank() const { return per_rank_; }

  private:
    Transport* transport_;
    int threads_;
    TextEvaluation evaluate_;
    int at_once_;
    bool finished_ = false;
    std::vector<int> per_rank_;
};

/// Ranks other than 0: evaluates what rank 0 hands out, round after round, until rank 0
/// finishes. Returns the number of evaluations this rank ran.
int serve_rounds(Transport& transport, int threads, const TextEvaluation& evaluate,
                 int at_once = 1);

}  // namespace sb::distributed

// A dynamic queue of independent tasks over the ranks of a run: rank 0 hands out task numbers
// to whichever thread of whichever rank is free, owns what the tasks share (it answers their
// calls) and gathers their results as text. Campaign sweeps are its first tasks; any other
// set of independent evaluations can be distributed the same way.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "distributed/transport.hpp"

namespace sb::distributed {

/// What a running task may ask of rank 0, which owns what every task shares (a checkpoint
/// store, progress lines). Thread-safe: each thread of a rank runs its own task.
class Link {
  public:
    virtual ~Link() = default;
    /// Sends `request` to rank 0's TaskQueue::serve and waits for its answer. Throws
    /// std::runtime_error with serve's message when serve threw.
    virtual std::string call(const std::string& request) = 0;
    /// Sends `notice` to rank 0's TaskQueue::serve without waiting; its answer is dropped. A
    /// task's notices, calls and result arrive in the order it sent them.
    virtual void post(const std::string& notice) = 0;
};

/// How a task ended, on rank 0.
struct TaskOutcome {
    bool ok = false;
    std::string text;  ///< the result, or the failure's message
    int rank = 0;      ///< the rank that ran it
};

/// The tasks 0 ... task_count - 1 and what to do with them. Every rank builds the same queue
/// (the same task numbers mean the same tasks on every rank).
struct TaskQueue {
    int task_count = 0;
    int threads = 1;  ///< tasks each rank runs at once (rank 0 included)
    /// Runs task `task` on one of a rank's threads and returns its result; an exception fails
    /// the task with its message (the other tasks go on).
    std::function<std::string(int task, Link& link)> run;
    /// Rank 0 only: answers a call or takes a notice of a running task (of any rank). Called
    /// from several threads at once.
    std::function<std::string(const std::string& request)> serve;
    /// Rank 0 only, may be empty: told of each task's outcome as it arrives, on the thread
    /// that gathers them (a store keeps finished work before the other tasks end). An
    /// exception it throws is rethrown by distribute_tasks once every task has ended.
    std::function<void(int task, const TaskOutcome& outcome)> finished;
};

/// Rank 0 (or a process alone, transport null): runs the queue over every rank, its own
/// threads included, and returns every task's outcome in task order once all are done; then
/// the other ranks' serve_tasks return. Tasks are handed out one at a time, in order, to the
/// first thread that is free, so long and short tasks balance.
std::vector<TaskOutcome> distribute_tasks(Transport* transport, const TaskQueue& queue);

/// Ranks other than 0: runs the tasks rank 0 hands out until it says stop. Returns the number
/// of tasks this rank ran.
int serve_tasks(Transport& transport, const TaskQueue& queue);

/// Rank 0 when it gives up before distribute_tasks (an error): the other ranks' serve_tasks
/// return without running anything.
void release_ranks(Transport& transport);

}  // namespace sb::distributed

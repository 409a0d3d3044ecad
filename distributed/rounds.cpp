// Rounds as task queues: before each, rank 0 tells the other ranks a round begins (they then
// serve its queue) or that none will; a task fetches its input from rank 0 with a call.
#include "distributed/rounds.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "distributed/task_queue.hpp"

namespace sb::distributed {
namespace {

/// Rank 0's messages between rounds (the task queue's own messages start with a kind byte
/// and a binary number, never with these words).
const std::string kRound = "round";
const std::string kOver = "rounds over";

/// How long a waiting rank sleeps between looks for rank 0's next message.
constexpr std::chrono::milliseconds kWait{2};

TaskQueue queue_of(int threads, const TextEvaluation& evaluate, int at_once) {
    TaskQueue queue;
    queue.threads = std::max(1, at_once);
    queue.run = [threads, &evaluate](int task, Link& link) {
        return evaluate(link.call(std::to_string(task)), threads);
    };
    return queue;
}

}  // namespace

DistributedRounds::DistributedRounds(Transport* transport, int threads, TextEvaluation evaluate,
                                     int at_once)
    : transport_(transport),
      threads_(threads),
      evaluate_(std::move(evaluate)),
      at_once_(at_once),
      per_rank_(transport != nullptr ? transport->size() : 1, 0) {}

DistributedRounds::~DistributedRounds() {
    try {
        finish();
    } catch (...) {
        // the other ranks end with mpirun when this one does
    }
}

void DistributedRounds::finish() {
    if (finished_) return;
    finished_ = true;
    if (transport_ == nullptr) return;
    for (int r = 1; r < transport_->size(); ++r) transport_->send(r, kOver);
    while (!transport_->flush()) std::this_thread::sleep_for(kWait);
}

std::vector<std::string> DistributedRounds::run(
    const std::vector<std::string>& inputs,
    const std::function<void(std::size_t input, const std::string& result)>& on_result) {
    if (finished_) throw std::logic_error("DistributedRounds::run after finish");
    if (inputs.empty()) return {};
    if (transport_ != nullptr) {
        for (int r = 1; r < transport_->size(); ++r) transport_->send(r, kRound);
    }
    TaskQueue queue = queue_of(threads_, evaluate_, at_once_);
    queue.task_count = static_cast<int>(inputs.size());
    queue.serve = [&inputs](const std::string& request) {
        const int task = std::stoi(request);
        if (task < 0 || task >= static_cast<int>(inputs.size())) {
            throw std::runtime_error("rounds: no input " + request);
        }
        return inputs[static_cast<std::size_t>(task)];
    };
    if (on_result) {
        queue.finished = [&on_result](int task, const TaskOutcome& outcome) {
            if (outcome.ok) on_result(static_cast<std::size_t>(task), outcome.text);
        };
    }
    const auto outcomes = distribute_tasks(transport_, queue);
    std::vector<std::string> results;
    results.reserve(outcomes.size());
    for (const auto& o : outcomes) {
        if (!o.ok) {
            throw std::runtime_error("an evaluation on rank " + std::to_string(o.rank) +
                                     " failed: " + o.text);
        }
        ++per_rank_[static_cast<std::size_t>(o.rank)];
        results.push_back(o.text);
    }
    return results;
}

int serve_rounds(Transport& transport, int threads, const TextEvaluation& evaluate, int at_once) {
    if (transport.rank() == 0) throw std::logic_error("serve_rounds: rank 0 runs the rounds");
    const TaskQueue queue = queue_of(threads, evaluate, at_once);
    int ran = 0;
    for (;;) {
        auto message = transport.receive();
        if (!message) {
            std::this_thread::sleep_for(kWait);
            continue;
        }
        if (message->bytes == kOver) return ran;
        if (message->bytes != kRound) {
            throw std::runtime_error("rounds: an unexpected message from rank " +
                                     std::to_string(message->source));
        }
        ran += serve_tasks(transport, queue);
    }
}

}  // namespace sb::distributed

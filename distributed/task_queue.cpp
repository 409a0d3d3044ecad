// The task queue: a pool of task threads on every rank, rank 0's loop that hands out tasks
// and answers calls, the other ranks' loop that asks for tasks and forwards calls.
#include "distributed/task_queue.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

namespace sb::distributed {
namespace {

/// How long a rank's communicating thread sleeps when nothing happened: short beside a task
/// (a sweep point takes seconds), and it leaves the cores to the task threads.
constexpr std::chrono::milliseconds kIdleWait{1};

/// Message kinds. To rank 0: a thread is free (ask), a task's call, notice, result (done), and
/// the last message of a rank (bye). From rank 0: a task, no more tasks (none), the answer to
/// a call (reply), and stop.
enum class Kind : char {
    ask = 'A',
    call = 'C',
    post = 'P',
    done = 'D',
    bye = 'B',
    task = 'T',
    none = 'N',
    reply = 'R',
    stop = 'S',
};

/// kind, a number (task or thread), a flag (success), the payload.
std::string encode(Kind kind, int number = 0, bool ok = true, const std::string& payload = {}) {
    std::string bytes(6, '\0');
    bytes[0] = static_cast<char>(kind);
    const auto n = static_cast<std::int32_t>(number);
    std::memcpy(bytes.data() + 1, &n, sizeof n);
    bytes[5] = ok ? '1' : '0';
    return bytes + payload;
}

struct Decoded {
    Kind kind = Kind::none;
    int number = 0;
    bool ok = true;
    std::string payload;
};

Decoded decode(const Message& m) {
    if (m.bytes.size() < 6) {
        throw std::runtime_error("task queue: a damaged message from rank " +
                                 std::to_string(m.source));
    }
    Decoded d;
    d.kind = static_cast<Kind>(m.bytes[0]);
    std::int32_t n = 0;
    std::memcpy(&n, m.bytes.data() + 1, sizeof n);
    d.number = n;
    d.ok = m.bytes[5] == '1';
    d.payload = m.bytes.substr(6);
    return d;
}

/// A message one of a rank's task threads wants sent to rank 0.
struct Outgoing {
    int slot = 0;
    Kind kind = Kind::call;
    std::string payload;
};

/// A rank's task threads. On rank 0 a task's calls go straight to serve; elsewhere they are
/// queued for the communicating thread, which sends them and hands back the answers.
class Pool {
  public:
    Pool(const TaskQueue& queue, bool on_root) : queue_(queue), on_root_(on_root) {
        const int threads = std::max(1, queue.threads);
        slots_.resize(static_cast<std::size_t>(threads));
        for (int i = 0; i < threads; ++i) {
            links_.push_back(std::make_unique<SlotLink>(*this, i));
        }
        for (int i = 0; i < threads; ++i) {
            threads_.emplace_back([this, i] { work(i); });
        }
    }
    ~Pool() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        work_cv_.notify_all();
        reply_cv_.notify_all();
        for (auto& t : threads_) t.join();
    }
    Pool(const Pool&) = delete;
    Pool& operator=(const Pool&) = delete;

    /// Threads without a task.
    int idle() {
        std::lock_guard<std::mutex> lock(mutex_);
        int n = 0;
        for (const auto& s : slots_) n += s.busy ? 0 : 1;
        return n;
    }
    /// Gives `task` to a thread without one (there must be one).
    void assign(int task) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            for (auto& s : slots_) {
                if (s.busy) continue;
                s.busy = true;
                s.task = task;
                work_cv_.notify_all();
                return;
            }
        }
        throw std::logic_error("task queue: a task for a rank without a free thread");
    }
    std::deque<Outgoing> take_outgoing() {
        std::lock_guard<std::mutex> lock(mutex_);
        return std::exchange(outgoing_, {});
    }
    std::vector<std::pair<int, TaskOutcome>> take_finished() {
        std::lock_guard<std::mutex> lock(mutex_);
        return std::exchange(finished_, {});
    }
    /// The answer to thread `slot`'s call.
    void deliver(int slot, bool ok, std::string text) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (slot < 0 || slot >= static_cast<int>(slots_.size())) {
                throw std::runtime_error("task queue: an answer for no thread");
            }
            auto& s = slots_[static_cast<std::size_t>(slot)];
            s.reply_ready = true;
            s.reply_ok = ok;
            s.reply = std::move(text);
        }
        reply_cv_.notify_all();
    }
    /// Returns when a thread has something to send or finished, or after `timeout`.
    void wait(std::chrono::milliseconds timeout) {
        std::unique_lock<std::mutex> lock(mutex_);
        event_cv_.wait_for(lock, timeout, [this] { return event_; });
        event_ = false;
    }

  private:
    class SlotLink : public Link {
      public:
        SlotLink(Pool& pool, int slot) : pool_(pool), slot_(slot) {}
        std::string call(const std::string& request) override {
            if (pool_.on_root_) return pool_.queue_.serve(request);
            return pool_.remote_call(slot_, request);
        }
        void post(const std::string& notice) override {
            if (pool_.on_root_) {
                pool_.queue_.serve(notice);
                return;
            }
            pool_.push({slot_, Kind::post, notice});
        }

      private:
        Pool& pool_;
        int slot_;
    };

    struct Slot {
        bool busy = false;  ///< a task is assigned or running
        int task = -1;      ///< assigned, not yet started
        bool reply_ready = false;
        bool reply_ok = true;
        std::string reply;
    };

    void push(Outgoing message) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            outgoing_.push_back(std::move(message));
            event_ = true;
        }
        event_cv_.notify_all();
    }

    std::string remote_call(int slot, const std::string& request) {
        std::unique_lock<std::mutex> lock(mutex_);
        auto& s = slots_[static_cast<std::size_t>(slot)];
        s.reply_ready = false;
        outgoing_.push_back({slot, Kind::call, request});
        event_ = true;
        event_cv_.notify_all();
        reply_cv_.wait(lock, [&] { return s.reply_ready || stopping_; });
        if (!s.reply_ready) throw std::runtime_error("task queue: stopped during a call");
        s.reply_ready = false;
        if (!s.reply_ok) throw std::runtime_error(s.reply);
        return std::move(s.reply);
    }

    void work(int slot) {
        auto& s = slots_[static_cast<std::size_t>(slot)];
        for (;;) {
            int task = -1;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                work_cv_.wait(lock, [&] { return stopping_ || s.task >= 0; });
                if (stopping_) return;
                task = std::exchange(s.task, -1);
            }
            TaskOutcome outcome;
            try {
                outcome.text = queue_.run(task, *links_[static_cast<std::size_t>(slot)]);
                outcome.ok = true;
            } catch (const std::exception& e) {
                outcome.text = e.what();
            } catch (...) {
                outcome.text = "task " + std::to_string(task) + " failed";
            }
            {
                std::lock_guard<std::mutex> lock(mutex_);
                finished_.emplace_back(task, std::move(outcome));
                s.busy = false;
                event_ = true;
            }
            event_cv_.notify_all();
        }
    }

    const TaskQueue& queue_;
    bool on_root_;
    std::mutex mutex_;
    std::condition_variable work_cv_;
    std::condition_variable reply_cv_;
    std::condition_variable event_cv_;
    bool event_ = false;
    bool stopping_ = false;
    std::vector<Slot> slots_;
    std::vector<std::unique_ptr<SlotLink>> links_;
    std::vector<std::thread> threads_;
    std::deque<Outgoing> outgoing_;
    std::vector<std::pair<int, TaskOutcome>> finished_;
};

/// Tells every other rank to stop and waits for each one's last message.
void stop_ranks(Transport& transport) {
    for (int r = 1; r < transport.size(); ++r) transport.send(r, encode(Kind::stop));
    int byes = 0;
    while (byes < transport.size() - 1) {
        if (auto m = transport.receive()) {
            // Asks still under way are dropped; nothing else comes once every task is done.
            if (decode(*m).kind == Kind::bye) ++byes;
            continue;
        }
        std::this_thread::sleep_for(kIdleWait);
    }
    while (!transport.flush()) std::this_thread::sleep_for(kIdleWait);
}

}  // namespace

std::vector<TaskOutcome> distribute_tasks(Transport* transport, const TaskQueue& queue) {
    if (transport != nullptr && transport->rank() != 0) {
        throw std::logic_error("distribute_tasks: rank 0 hands out the tasks");
    }
    const int count = std::max(0, queue.task_count);
    std::vector<TaskOutcome> outcomes(static_cast<std::size_t>(count));
    int next = 0;
    int finished = 0;
    std::exception_ptr finished_error;  // of queue.finished: the tasks running end first
    {
        Pool pool(queue, true);
        const auto record = [&](int task, TaskOutcome outcome, int rank) {
            if (task < 0 || task >= count) {
                throw std::runtime_error("task queue: a result for no task");
            }
            outcome.rank = rank;
            outcomes[static_cast<std::size_t>(task)] = std::move(outcome);
            ++finished;
            if (queue.finished && !finished_error) {
                try {
                    queue.finished(task, outcomes[static_cast<std::size_t>(task)]);
                } catch (...) {
                    finished_error = std::current_exception();
                }
            }
        };
        while (finished < count) {
            bool busy = false;
            for (auto& [task, outcome] : pool.take_finished()) {
                record(task, std::move(outcome), 0);
                busy = true;
            }
            for (int idle = pool.idle(); idle > 0 && next < count; --idle) pool.assign(next++);
            while (transport != nullptr) {
                auto message = transport->receive();
                if (!message) break;
                busy = true;
                const Decoded d = decode(*message);
                const int from = message->source;
                switch (d.kind) {
                    case Kind::ask:
                        transport->send(
                            from, next < count ? encode(Kind::task, next++) : encode(Kind::none));
                        break;
                    case Kind::call: {
                        std::string answer;
                        bool ok = true;
                        try {
                            answer = queue.serve(d.payload);
                        } catch (const std::exception& e) {
                            ok = false;
                            answer = e.what();
                        }
                        transport->send(from, encode(Kind::reply, d.number, ok, answer));
                        break;
                    }
                    case Kind::post:
                        try {
                            queue.serve(d.payload);
                        } catch (const std::exception&) {
                            // A notice has nobody to answer to; the task goes on.
                        }
                        break;
                    case Kind::done:
                        record(d.number, {d.ok, d.payload, from}, from);
                        break;
                    default:
                        throw std::runtime_error("task queue: an unexpected message from rank " +
                                                 std::to_string(from));
                }
            }
            if (!busy) pool.wait(kIdleWait);
        }
    }
    if (transport != nullptr) stop_ranks(*transport);
    if (finished_error) std::rethrow_exception(finished_error);
    return outcomes;
}

int serve_tasks(Transport& transport, const TaskQueue& queue) {
    if (transport.rank() == 0) throw std::logic_error("serve_tasks: rank 0 hands out the tasks");
    Pool pool(queue, false);
    int asks = 0;  // asks not yet answered
    bool no_more = false;
    int ran = 0;
    for (;;) {
        bool busy = false;
        for (auto& out : pool.take_outgoing()) {
            transport.send(0, encode(out.kind, out.slot, true, out.payload));
            busy = true;
        }
        for (auto& [task, outcome] : pool.take_finished()) {
            transport.send(0, encode(Kind::done, task, outcome.ok, outcome.text));
            ++ran;
            busy = true;
        }
        if (!no_more) {
            for (int idle = pool.idle(); asks < idle; ++asks) transport.send(0, encode(Kind::ask));
        }
        bool stop = false;
        while (auto message = transport.receive()) {
            busy = true;
            const Decoded d = decode(*message);
            switch (d.kind) {
                case Kind::task:
                    --asks;
                    pool.assign(d.number);
                    break;
                case Kind::none:
                    --asks;
                    no_more = true;
                    break;
                case Kind::reply:
                    pool.deliver(d.number, d.ok, d.payload);
                    break;
                case Kind::stop:
                    stop = true;
                    break;
                default:
                    throw std::runtime_error("task queue: an unexpected message from rank " +
                                             std::to_string(message->source));
            }
        }
        if (stop) break;
        if (!busy) pool.wait(kIdleWait);
    }
    transport.send(0, encode(Kind::bye));
    while (!transport.flush()) std::this_thread::sleep_for(kIdleWait);
    return ran;
}

void release_ranks(Transport& transport) { stop_ranks(transport); }

}  // namespace sb::distributed

// A campaign's sweeps as tasks of the queue: the store and the progress of rank 0 reached
// through calls, results and failures as text.
#include "distributed/campaign.hpp"

#include <omp.h>

#include <Eigen/Core>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

#include "bench/resolved_config.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "core/exact_text.hpp"
#include "dem/solver.hpp"
#include "distributed/task_queue.hpp"

namespace sb::distributed {
namespace {

/// Fields joined by newlines; only the last may hold newlines itself.
std::string join(std::initializer_list<std::string> fields) {
    std::string out;
    for (const auto& f : fields) {
        if (!out.empty()) out += '\n';
        out += f;
    }
    return out;
}

/// The first `count` newline-separated fields, then the rest as the last.
std::vector<std::string> split(const std::string& text, std::size_t count) {
    std::vector<std::string> fields;
    std::size_t at = 0;
    while (fields.size() + 1 < count) {
        const auto end = text.find('\n', at);
        if (end == std::string::npos) break;
        fields.push_back(text.substr(at, end - at));
        at = end + 1;
    }
    fields.push_back(text.substr(std::min(at, text.size())));
    if (fields.size() != count) throw std::runtime_error("sweep request: fields missing");
    return fields;
}

double number(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

int whole(const std::string& text) { return std::atoi(text.c_str()); }

std::string optional_text(const std::optional<std::string>& text) {
    return text ? "1" + *text : std::string("0");
}

std::optional<std::string> from_optional_text(const std::string& reply) {
    if (reply.empty() || reply[0] != '1') return std::nullopt;
    return reply.substr(1);
}

/// What a progress belongs to, as a request's field, and back.
std::string work_name(bench::Unfinished work) {
    return work == bench::Unfinished::bed ? "bed" : "result";
}

bench::Unfinished work_of(const std::string& name) {
    if (name == "bed") return bench::Unfinished::bed;
    if (name == "result") return bench::Unfinished::result;
    throw std::runtime_error("sweep request: no progress of kind '" + name + "'");
}

/// Rank 0's store as seen by a sweep on another rank.
class RemoteStore : public bench::CheckpointStore {
  public:
    explicit RemoteStore(Link& link) : link_(link) {}
    void open(const std::string& /*config_hash*/, bool /*restart*/) override {
        throw std::logic_error("RemoteStore: rank 0 opens the store");
    }
    std::optional<std::string> load_checkpoint(const std::string& key) override {
        return from_optional_text(link_.call(join({"load_checkpoint", key})));
    }
    void save_checkpoint(const std::string& key, const std::string& text) override {
        link_.call(join({"save_checkpoint", key, text}));
    }
    std::optional<std::string> load_bed(const std::string& key) override {
        return from_optional_text(link_.call(join({"load_bed", key})));
    }
    void save_bed(const std::string& key, const std::string& text) override {
        link_.call(join({"save_bed", key, text}));
    }
    std::optional<std::string> load_progress(bench::Unfinished work,
                                             const std::string& key) override {
        return from_optional_text(link_.call(join({"load_progress", work_name(work), key})));
    }
    void save_progress(bench::Unfinished work, const std::string& key,
                       const std::string& text) override {
        link_.call(join({"save_progress", work_name(work), key, text}));
    }
    [[nodiscard]] std::string progress_name(bench::Unfinished work,
                                            const std::string& key) const override {
        return link_.call(join({"progress_name", work_name(work), key}));
    }
    std::optional<std::string> load_result(const std::string& key) override {
        return from_optional_text(link_.call(join({"load_result", key})));
    }
    void save_result(const std::string& key, const std::string& text) override {
        link_.call(join({"save_result", key, text}));
    }
    void save_file(const std::string& path, const std::string& text) override {
        link_.call(join({"save_file", path, text}));
    }

  private:
    Link& link_;
};

/// Rank 0's progress lines as seen by a sweep on another rank: the events, posted.
class RemoteProgress : public bench::SweepProgress {
  public:
    explicit RemoteProgress(Link& link) : link_(link) {}
    void point_started(const bench::SweepTask& task, int index, double frequency_hz) override {
        link_.post(join({"started", std::to_string(task.index), std::to_string(index),
                         exact_text(frequency_hz)}));
    }
    void points_resumed(int count) override {
        link_.post(join({"resumed", std::to_string(count)}));
    }
    void points_added(int count) override { link_.post(join({"added", std::to_string(count)})); }
    void note(const std::string& line) override { link_.post(join({"note", line})); }
    void point_finished(const bench::SweepTask& task, double frequency_hz,
                        const control::PointResult& result) override {
        link_.post(
            join({"finished", std::to_string(task.index), exact_text(frequency_hz),
                  std::to_string(static_cast<int>(result.status)),
                  std::to_string(result.periods_simulated), std::to_string(result.updates)}));
    }

  private:
    Link& link_;
};

/// Rank 0: a call or notice of a sweep on another rank, against the store and the progress.
std::string serve_sweep_request(const std::string& request, const bench::CampaignPlan& plan,
                                bench::CheckpointStore& store, bench::SweepProgress& progress) {
    const std::string op = request.substr(0, request.find('\n'));
    const auto task_of = [&plan](const std::string& index) -> const bench::SweepTask& {
        const auto i = static_cast<std::size_t>(whole(index));
        if (i >= plan.tasks.size() || plan.tasks[i].index != i) {
            throw std::runtime_error("sweep request: no task " + index);
        }
        return plan.tasks[i];
    };
    if (op == "load_checkpoint") return optional_text(store.load_checkpoint(split(request, 2)[1]));
    if (op == "load_bed") return optional_text(store.load_bed(split(request, 2)[1]));
    if (op == "load_result") return optional_text(store.load_result(split(request, 2)[1]));
    if (op == "load_progress") {
        const auto f = split(request, 3);
        return optional_text(store.load_progress(work_of(f[1]), f[2]));
    }
    if (op == "progress_name") {
        const auto f = split(request, 3);
        return store.progress_name(work_of(f[1]), f[2]);
    }
    if (op == "save_checkpoint") {
        const auto f = split(request, 3);
        store.save_checkpoint(f[1], f[2]);
    } else if (op == "save_bed") {
        const auto f = split(request, 3);
        store.save_bed(f[1], f[2]);
    } else if (op == "save_progress") {
        const auto f = split(request, 4);
        store.save_progress(work_of(f[1]), f[2], f[3]);
    } else if (op == "save_result") {
        const auto f = split(request, 3);
        store.save_result(f[1], f[2]);
    } else if (op == "save_file") {
        const auto f = split(request, 3);
        store.save_file(f[1], f[2]);
    } else if (op == "started") {
        const auto f = split(request, 4);
        progress.point_started(task_of(f[1]), whole(f[2]), number(f[3]));
    } else if (op == "resumed") {
        progress.points_resumed(whole(split(request, 2)[1]));
    } else if (op == "added") {
        progress.points_added(whole(split(request, 2)[1]));
    } else if (op == "note") {
        progress.note(split(request, 2)[1]);
    } else if (op == "finished") {
        const auto f = split(request, 6);
        control::PointResult result;
        result.status = static_cast<control::PointStatus>(whole(f[3]));
        result.periods_simulated = whole(f[4]);
        result.updates = whole(f[5]);
        progress.point_finished(task_of(f[1]), number(f[2]), result);
    } else {
        throw std::runtime_error("sweep request: unknown '" + op + "'");
    }
    return {};
}

/// A sweep's outcome as text: "R" and the result, or "E" and a DEM guard's failure (which
/// rank 0 throws again as such).
std::string run_sweep_task(const bench::CampaignConfig& config, const bench::SweepTask& task,
                           const std::string& config_hash, bench::CheckpointStore& store,
                           bench::SweepProgress& progress) {
    try {
        return "R" + bench::serialize_sweep_result(
                         bench::run_sweep(config, task, config_hash, store, progress));
    } catch (const dem::SimulationError& e) {
        return "E" + join({std::to_string(static_cast<int>(e.kind)), std::to_string(e.step),
                           exact_text(e.time_s), std::to_string(e.particle_id), e.what()});
    }
}

int thread_count(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

/// Eigen single-threaded inside the sweeps, as bench's executor has it (bench/campaign.cpp).
class SingleThreadedEigen {
  public:
    SingleThreadedEigen() : previous_(Eigen::nbThreads()) { Eigen::setNbThreads(1); }
    ~SingleThreadedEigen() { Eigen::setNbThreads(previous_); }
    SingleThreadedEigen(const SingleThreadedEigen&) = delete;
    SingleThreadedEigen& operator=(const SingleThreadedEigen&) = delete;

  private:
    int previous_;
};

}  // namespace

DistributedSweeps::DistributedSweeps(Transport* transport, int threads)
    : transport_(transport), threads_(thread_count(threads)) {}

DistributedSweeps::~DistributedSweeps() {
    if (!started_ && transport_ != nullptr) {
        try {
            release_ranks(*transport_);
        } catch (const std::exception&) {
            // Nothing more to do: the run ends with rank 0's error.
        }
    }
}

int DistributedSweeps::processes() const { return transport_ != nullptr ? transport_->size() : 1; }

std::vector<bench::SweepResult> DistributedSweeps::run(const bench::CampaignConfig& config,
                                                       const bench::CampaignPlan& plan,
                                                       const std::string& config_hash,
                                                       bench::CheckpointStore& store,
                                                       bench::SweepProgress& progress) {
    if (started_) throw std::logic_error("DistributedSweeps: one campaign per executor");
    started_ = true;
    SingleThreadedEigen eigen;
    TaskQueue queue;
    queue.task_count = static_cast<int>(plan.tasks.size());
    queue.threads = threads_;
    // Rank 0's own threads use the store and the progress directly.
    queue.run = [&](int task, Link&) {
        return run_sweep_task(config, plan.tasks[static_cast<std::size_t>(task)], config_hash,
                              store, progress);
    };
    queue.serve = [&](const std::string& request) {
        return serve_sweep_request(request, plan, store, progress);
    };
    std::vector<TaskOutcome> outcomes;
    try {
        outcomes = distribute_tasks(transport_, queue);
    } catch (...) {
        // The queue itself broke (not a sweep): the destructor releases the other ranks.
        started_ = false;
        throw;
    }

    per_rank_.assign(static_cast<std::size_t>(processes()), 0);
    std::vector<bench::SweepResult> sweeps;
    std::exception_ptr first_error;
    for (std::size_t i = 0; i < outcomes.size(); ++i) {
        const TaskOutcome& o = outcomes[i];
        ++per_rank_.at(static_cast<std::size_t>(o.rank));
        const std::string where = o.rank == 0 ? "" : "rank " + std::to_string(o.rank) + ": ";
        try {
            if (!o.ok) throw std::runtime_error(where + o.text);
            if (o.text.rfind('E', 0) == 0) {
                const auto f = split(o.text.substr(1), 5);
                throw dem::SimulationError(static_cast<dem::SimulationError::Kind>(whole(f[0])),
                                           std::atoll(f[1].c_str()), number(f[2]), whole(f[3]),
                                           f[4]);
            }
            if (o.text.rfind('R', 0) != 0) {
                throw std::runtime_error(where + "sweep " + plan.tasks[i].key +
                                         ": an unreadable result");
            }
            sweeps.push_back(bench::parse_sweep_result(o.text.substr(1),
                                                       "the result of sweep " + plan.tasks[i].key));
        } catch (...) {
            if (!first_error) first_error = std::current_exception();
            sweeps.emplace_back();
        }
    }
    if (first_error) std::rethrow_exception(first_error);
    return sweeps;
}

int serve_campaign(Transport& transport, const bench::CampaignConfig& config,
                   const bench::Selection& selection, int threads) {
    SingleThreadedEigen eigen;
    bench::CampaignPlan plan;
    std::string planning_error;
    try {
        plan = bench::plan_campaign(config, selection);
    } catch (const std::exception& e) {
        // Rank 0 planned the same config and stopped before handing anything out; should it
        // not have, every sweep fails with this message.
        planning_error = e.what();
    }
    const std::string config_hash = bench::config_hash(config);
    TaskQueue queue;
    queue.task_count = static_cast<int>(plan.tasks.size());
    queue.threads = thread_count(threads);
    queue.run = [&](int task, Link& link) {
        if (!planning_error.empty()) throw std::runtime_error(planning_error);
        if (task < 0 || task >= static_cast<int>(plan.tasks.size())) {
            throw std::runtime_error("no sweep " + std::to_string(task) + " in this rank's plan");
        }
        RemoteStore store(link);
        RemoteProgress progress(link);
        return run_sweep_task(config, plan.tasks[static_cast<std::size_t>(task)], config_hash,
                              store, progress);
    };
    return serve_tasks(transport, queue);
}

}  // namespace sb::distributed

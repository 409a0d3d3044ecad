// The task queue over ranks on threads (an in-process transport): every task once, results in
// task order, calls answered by rank 0, failures kept to their task, ranks released.
#include "distributed/task_queue.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace sb::distributed {
namespace {

/// Rank 0 runs `queue` with distribute_tasks on this thread, every other rank serve_tasks on a
/// thread of its own; returns rank 0's outcomes and each other rank's count of tasks run.
struct QueueRun {
    std::vector<TaskOutcome> outcomes;
    std::vector<int> ran;  ///< per rank other than 0
};

QueueRun run_over(int ranks, const TaskQueue& queue) {
    InProcessNetwork network(ranks);
    QueueRun run;
    run.ran.assign(static_cast<std::size_t>(ranks - 1), -1);
    std::vector<std::thread> others;
    for (int r = 1; r < ranks; ++r) {
        others.emplace_back([&network, &queue, &run, r] {
            auto transport = network.endpoint(r);
            run.ran[static_cast<std::size_t>(r - 1)] = serve_tasks(*transport, queue);
        });
    }
    auto root = network.endpoint(0);
    run.outcomes = distribute_tasks(root.get(), queue);
    for (auto& t : others) t.join();
    return run;
}

/// Task k asks rank 0 for k squared, waits a little (so every rank gets some) and answers.
TaskQueue squares(int count, int threads) {
    TaskQueue queue;
    queue.task_count = count;
    queue.threads = threads;
    queue.run = [](int task, Link& link) {
        const std::string square = link.call("square " + std::to_string(task));
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        return "task " + std::to_string(task) + ": " + square;
    };
    queue.serve = [](const std::string& request) {
        const int k = std::stoi(request.substr(7));
        return std::to_string(k * k);
    };
    return queue;
}

TEST(TaskQueue, EveryTaskRunsOnceAndItsResultComesBackInTaskOrder) {
    const QueueRun run = run_over(3, squares(24, 2));
    ASSERT_EQ(run.outcomes.size(), 24U);
    std::vector<int> per_rank(3, 0);
    for (int k = 0; k < 24; ++k) {
        const TaskOutcome& o = run.outcomes[static_cast<std::size_t>(k)];
        EXPECT_TRUE(o.ok) << o.text;
        EXPECT_EQ(o.text, "task " + std::to_string(k) + ": " + std::to_string(k * k));
        ++per_rank.at(static_cast<std::size_t>(o.rank));
    }
    // Each rank ran what rank 0 says it did, and every rank had a share.
    EXPECT_EQ(run.ran[0], per_rank[1]);
    EXPECT_EQ(run.ran[1], per_rank[2]);
    for (int r = 0; r < 3; ++r) EXPECT_GT(per_rank[static_cast<std::size_t>(r)], 0) << r;
}

TEST(TaskQueue, AProcessAloneRunsEveryTaskOnItsThreads) {
    const std::vector<TaskOutcome> outcomes = distribute_tasks(nullptr, squares(5, 3));
    ASSERT_EQ(outcomes.size(), 5U);
    for (int k = 0; k < 5; ++k) {
        EXPECT_EQ(outcomes[static_cast<std::size_t>(k)].text,
                  "task " + std::to_string(k) + ": " + std::to_string(k * k));
        EXPECT_EQ(outcomes[static_cast<std::size_t>(k)].rank, 0);
    }
}

TEST(TaskQueue, AFailingTaskFailsAloneWithItsMessageAndAFailingCallReachesItsTask) {
    TaskQueue queue = squares(8, 1);
    const auto square = queue.run;
    queue.run = [square](int task, Link& link) -> std::string {
        if (task == 3) throw std::runtime_error("task 3 cannot");
        if (task == 5) return link.call("refuse");
        return square(task, link);
    };
    const auto serve = queue.serve;
    queue.serve = [serve](const std::string& request) -> std::string {
        if (request == "refuse") throw std::runtime_error("rank 0 refuses");
        return serve(request);
    };
    const QueueRun run = run_over(2, queue);
    for (int k = 0; k < 8; ++k) {
        const TaskOutcome& o = run.outcomes[static_cast<std::size_t>(k)];
        if (k == 3) {
            EXPECT_FALSE(o.ok);
            EXPECT_EQ(o.text, "task 3 cannot");
        } else if (k == 5) {
            EXPECT_FALSE(o.ok);
            EXPECT_EQ(o.text, "rank 0 refuses");
        } else {
            EXPECT_TRUE(o.ok) << k << ": " << o.text;
        }
    }
}

TEST(TaskQueue, ATasksNoticesCallsAndResultArriveInTheOrderSent) {
    std::mutex mutex;
    std::map<int, std::vector<std::string>> seen;  // by task
    TaskQueue queue;
    queue.task_count = 6;
    queue.threads = 2;
    queue.run = [](int task, Link& link) {
        std::string t = std::to_string(task);
        for (int i = 0; i < 20; ++i) link.post(t + " notice " + std::to_string(i));
        link.call(t + " call");
        link.post(t + " last");
        return t;
    };
    queue.serve = [&](const std::string& request) {
        std::lock_guard<std::mutex> lock(mutex);
        seen[std::stoi(request)].push_back(request.substr(request.find(' ') + 1));
        return std::string();
    };
    const QueueRun run = run_over(3, queue);
    for (int task = 0; task < 6; ++task) {
        EXPECT_TRUE(run.outcomes[static_cast<std::size_t>(task)].ok);
        const auto& s = seen[task];
        ASSERT_EQ(s.size(), 22U) << task;
        for (int i = 0; i < 20; ++i)
            EXPECT_EQ(s[static_cast<std::size_t>(i)], "notice " + std::to_string(i));
        EXPECT_EQ(s[20], "call");
        EXPECT_EQ(s[21], "last");
    }
}

TEST(TaskQueue, RanksReleasedBeforeAnyTaskReturnWithoutRunningOne) {
    InProcessNetwork network(3);
    const TaskQueue queue = squares(4, 1);
    std::vector<int> ran(2, -1);
    std::vector<std::thread> others;
    for (int r = 1; r < 3; ++r) {
        others.emplace_back([&, r] {
            auto transport = network.endpoint(r);
            ran[static_cast<std::size_t>(r - 1)] = serve_tasks(*transport, queue);
        });
    }
    auto root = network.endpoint(0);
    release_ranks(*root);
    for (auto& t : others) t.join();
    EXPECT_EQ(ran, (std::vector<int>{0, 0}));
}

}  // namespace
}  // namespace sb::distributed

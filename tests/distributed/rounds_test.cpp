// Rounds of evaluations over ranks on threads (an in-process transport): each round's results
// in input order, every rank taking part, the other ranks waiting between rounds and released
// when rank 0 finishes, a failed evaluation reported with its rank.
#include "distributed/rounds.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace sb::distributed {
namespace {

/// "x" -> "x squared is x*x" after a short wait (so that every rank gets some); "fail" throws.
std::string square(const std::string& input, int threads) {
    if (input == "fail") throw std::runtime_error("asked to fail");
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const int x = std::stoi(input);
    return input + " squared is " + std::to_string(x * x) + " on " + std::to_string(threads);
}

std::vector<std::string> numbers(int from, int count) {
    std::vector<std::string> out;
    for (int k = from; k < from + count; ++k) out.push_back(std::to_string(k));
    return out;
}

TEST(DistributedRounds, RoundsDecidedAsTheyGoComeBackInInputOrderFromEveryRank) {
    InProcessNetwork network(3);
    std::vector<int> served(2, -1);
    std::vector<std::thread> others;
    for (int r = 1; r < 3; ++r) {
        others.emplace_back([&network, &served, r] {
            auto transport = network.endpoint(r);
            served[static_cast<std::size_t>(r - 1)] = serve_rounds(*transport, 2, square);
        });
    }
    auto root = network.endpoint(0);
    {
        DistributedRounds rounds(root.get(), 2, square);
        int expected_total = 0;
        // Three rounds of different sizes, the last one smaller than the ranks.
        for (const int count : {12, 7, 2}) {
            const auto inputs = numbers(100 * count, count);
            const auto results = rounds.run(inputs);
            ASSERT_EQ(results.size(), inputs.size());
            for (std::size_t k = 0; k < inputs.size(); ++k) {
                const int x = std::stoi(inputs[k]);
                EXPECT_EQ(results[k], inputs[k] + " squared is " + std::to_string(x * x) + " on 2");
            }
            expected_total += count;
        }
        EXPECT_TRUE(rounds.run({}).empty());
        int total = 0;
        for (const int n : rounds.evaluations_per_rank()) {
            EXPECT_GT(n, 0);
            total += n;
        }
        EXPECT_EQ(total, expected_total);
    }  // the destructor releases the other ranks
    for (auto& t : others) t.join();
    EXPECT_GT(served[0], 0);
    EXPECT_GT(served[1], 0);
}

TEST(DistributedRounds, AFailedEvaluationNamesItsRankAndTheOtherRanksAreStillReleased) {
    InProcessNetwork network(2);
    int served = -1;
    std::thread other([&network, &served] {
        auto transport = network.endpoint(1);
        served = serve_rounds(*transport, 1, square);
    });
    auto root = network.endpoint(0);
    {
        DistributedRounds rounds(root.get(), 1, square);
        try {
            rounds.run({"1", "fail", "3"});
            ADD_FAILURE() << "no exception";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("failed: asked to fail"), std::string::npos)
                << e.what();
        }
        // The queue goes on after a failure: another round runs.
        EXPECT_EQ(rounds.run({"4"}).front(), "4 squared is 16 on 1");
        rounds.finish();
    }
    other.join();
    EXPECT_GE(served, 0);
}

TEST(DistributedRounds, AloneEveryRoundRunsInThisProcess) {
    DistributedRounds rounds(nullptr, 3, square);
    EXPECT_EQ(rounds.run(numbers(5, 3)),
              (std::vector<std::string>{"5 squared is 25 on 3", "6 squared is 36 on 3",
                                        "7 squared is 49 on 3"}));
    EXPECT_EQ(rounds.evaluations_per_rank(), std::vector<int>{3});
}

}  // namespace
}  // namespace sb::distributed

// A campaign's sweeps over two ranks on threads (the in-process transport): the same files
// as one process, byte for byte, every sweep through rank 0's store; resumed from them.
#include "distributed/campaign.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/sweep_checkpoint.hpp"
#include "core/text_file.hpp"
#include "tests/bench/campaign_fixtures.hpp"

namespace sb::distributed {
namespace {

namespace fs = std::filesystem;
using bench::test::fresh_dir;

/// Two sweeps (two levels) of 30 real particles, three frequencies each (and those the grid
/// refinement adds), with the steady windows' series written through the store.
std::string small_campaign() {
    return bench::test::paper000_h0_with({
        {"levels_g", "levels_g = [1.5, 3.0]"},
        {"count = 7", "count = 3"},
        {"count = 120", "count = 30"},
        {"max_overlap_fraction", "max_overlap_fraction = 0.05"},
        {"max_periods", "max_periods = 14"},
        {"window_periods", "window_periods = 3"},
        {"transient_periods", "transient_periods = 1"},
        {"series = false", "series = true"},
    });
}

/// provenance.toml without the lines that say how the run was made (date, ranks, threads,
/// command): what remains (the config's hash, per sweep its mode, grid and settings) must not
/// depend on it.
std::string provenance_results(const fs::path& dir) {
    std::istringstream in(read_text_file(dir / "provenance.toml"));
    std::string kept;
    for (std::string line; std::getline(in, line);) {
        bool how = false;
        for (const char* key : {"date = ", "ranks = ", "threads = ", "command = "}) {
            how = how || line.rfind(key, 0) == 0;
        }
        if (!how) kept += line + "\n";
    }
    return kept;
}

std::vector<std::pair<std::string, std::string>> outputs(const fs::path& dir) {
    auto files = bench::test::files_under(dir);
    std::erase_if(files, [](const auto& f) {
        return f.first == "provenance.toml" || f.first == "plots/plots.gp";
    });
    return files;
}

/// The campaign with its sweeps on two ranks: rank 1 on a thread of its own.
bench::CampaignSummary run_on_two_ranks(const bench::CampaignConfig& config,
                                        const bench::CampaignRunOptions& base,
                                        std::vector<int>& per_rank, int& served) {
    InProcessNetwork network(2);
    std::thread rank1([&] {
        auto transport = network.endpoint(1);
        served = serve_campaign(*transport, config, {}, 1);
    });
    auto transport = network.endpoint(0);
    bench::CampaignSummary summary;
    {
        DistributedSweeps sweeps(transport.get(), 1);
        bench::CampaignRunOptions options = base;
        options.executor = &sweeps;
        summary = bench::run_campaign(config, options);
        per_rank = sweeps.sweeps_per_rank();
    }
    rank1.join();
    return summary;
}

TEST(DistributedCampaign, TwoRanksWriteTheFilesOfOneProcessByteForByteAndResumeFromThem) {
    const std::string text = small_campaign();
    const auto config = bench::load_campaign_config_text(text, "two-ranks.toml");
    bench::CampaignRunOptions alone;
    alone.out_dir = fresh_dir("one-process");
    alone.config_text = text;
    alone.threads = 1;
    const auto one = bench::run_campaign(config, alone);

    bench::CampaignRunOptions options = alone;
    options.out_dir = fresh_dir("two-ranks");
    std::vector<int> per_rank;
    int served = -1;
    const auto two = run_on_two_ranks(config, options, per_rank, served);
    // Each rank ran one of the two sweeps; rank 0 wrote everything.
    EXPECT_EQ(per_rank, (std::vector<int>{1, 1}));
    EXPECT_EQ(served, 1);
    EXPECT_EQ(two.points, one.points);
    EXPECT_EQ(two.resumed_points, 0);
    EXPECT_EQ(two.periods_simulated, one.periods_simulated);

    const auto a = outputs(alone.out_dir);
    const auto b = outputs(options.out_dir);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].first, b[i].first);
        EXPECT_TRUE(a[i].second == b[i].second) << a[i].first << " differs";
    }
    // The files compared hold both sweeps' points, checkpoints, beds and series.
    const auto has = [&a](const std::string& prefix) {
        return std::count_if(a.begin(), a.end(),
                             [&](const auto& f) { return f.first.rfind(prefix, 0) == 0; });
    };
    EXPECT_EQ(has("checkpoints/"), 2);
    EXPECT_EQ(has("settled/"), 2);
    EXPECT_EQ(has("series/"), one.points);
    EXPECT_EQ(provenance_results(alone.out_dir), provenance_results(options.out_dir));
    const std::string provenance = read_text_file(options.out_dir / "provenance.toml");
    EXPECT_NE(provenance.find("ranks = 2\nthreads = 1\n"), std::string::npos) << provenance;

    // Run again on two ranks: every point comes from rank 0's checkpoints.
    const auto again = run_on_two_ranks(config, options, per_rank, served);
    EXPECT_EQ(again.resumed_points, one.points);
    EXPECT_EQ(again.periods_simulated, 0);
    const auto c = outputs(options.out_dir);
    ASSERT_EQ(c.size(), b.size());
    for (std::size_t i = 0; i < c.size(); ++i) {
        EXPECT_TRUE(c[i].second == b[i].second) << c[i].first << " differs";
    }
}

TEST(DistributedCampaign, ASweepsResultTextReadsBackExactly) {
    bench::SweepResult s;
    s.key = "H-0_1.5g_s2";
    s.arrangement = "H-0";
    s.level_g = 1.5;
    s.first_mode_hz = 6.372345678901234;
    s.frequencies_hz = {6.1, 6.3 + 1e-15, 6.5};
    s.settings = {"pd: stiffness 1e4 N/m", "grid refined: 2 frequencies added"};
    identification::PointRow row;
    row.arrangement = "H-0";
    row.level_g = 1.5;
    row.frequency_hz = 6.3 + 1e-15;
    row.status = "closest";
    row.series = "series/H-0_1.5g_s2_1.csv";
    row.filling = 1;
    const auto value = [](double rms, std::complex<double> amplitude, double h2, double h3) {
        identification::ChannelValue v;
        v.rms = rms;
        v.amplitude = amplitude;
        v.h2_ratio = h2;
        v.h3_ratio = h3;
        return v;
    };
    row.values.push_back(value(0.1, {1.0 / 3.0, -2.0 / 7.0}, 1e-300, 0.25));
    row.values.push_back(value(1e9, {0.0, -0.0}, 0.5, 1.0 / 9.0));
    s.rows = {row, row};
    s.rows[1].series.clear();
    s.control_log = {"H-0,1.5,6.3,closest,14,3,0.1,0.2,0.1;0.2,1;2"};
    s.energy_log = {"H-0,1.5,6.3,pd,1,2,3,4,5"};
    s.resumed_points = 1;
    s.periods_simulated = 1234567890123LL;
    const std::string text = bench::serialize_sweep_result(s);
    const bench::SweepResult back = bench::parse_sweep_result(text, "test");
    EXPECT_EQ(bench::serialize_sweep_result(back), text);
    EXPECT_EQ(back.first_mode_hz, s.first_mode_hz);
    EXPECT_EQ(back.frequencies_hz, s.frequencies_hz);
    EXPECT_EQ(back.settings, s.settings);
    ASSERT_EQ(back.rows.size(), 2U);
    EXPECT_EQ(back.rows[0].values[0].amplitude, s.rows[0].values[0].amplitude);
    EXPECT_EQ(back.rows[0].filling, 1);
    EXPECT_EQ(back.rows[1].series, "");
    EXPECT_EQ(back.periods_simulated, s.periods_simulated);
    EXPECT_THROW(bench::parse_sweep_result(text.substr(0, text.size() / 2), "half"),
                 std::runtime_error);
}

}  // namespace
}  // namespace sb::distributed

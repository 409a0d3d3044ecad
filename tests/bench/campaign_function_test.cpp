// The campaign as a function: results in memory with any store, selections, and the same
// points as the recording directory the CLI writes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/resolved_config.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "identification/recording_io.hpp"
#include "killed_store.hpp"

namespace sb::bench {
namespace {

using test::fresh_dir;
using test::paper000_h0_with;
using testing::InterruptedStore;

/// A small real campaign: 30 particles, two levels, five frequencies around resonance.
CampaignConfig small_dem_campaign() {
    return load_campaign_config_text(paper000_h0_with({
                                         {"levels_g", "levels_g = [1.0, 2.0]"},
                                         {"low_ratio", "low_ratio = 0.95"},
                                         {"high_ratio", "high_ratio = 1.05"},
                                         {"count = 7", "count = 5"},
                                         {"count = 120", "count = 30"},
                                         {"max_overlap_fraction", "max_overlap_fraction = 0.05"},
                                         {"max_periods", "max_periods = 14"},
                                         {"window_periods", "window_periods = 3"},
                                         {"transient_periods", "transient_periods = 1"},
                                     }),
                                     "small.toml");
}

void expect_same_points(const std::vector<identification::PointRow>& a,
                        const std::vector<identification::PointRow>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].arrangement, b[i].arrangement);
        EXPECT_EQ(a[i].level_g, b[i].level_g);
        EXPECT_EQ(a[i].frequency_hz, b[i].frequency_hz);
        EXPECT_EQ(a[i].status, b[i].status);
        ASSERT_EQ(a[i].values.size(), b[i].values.size());
        for (std::size_t c = 0; c < a[i].values.size(); ++c) {
            EXPECT_EQ(a[i].values[c].rms, b[i].values[c].rms) << i << " " << c;
            EXPECT_EQ(a[i].values[c].amplitude, b[i].values[c].amplitude) << i << " " << c;
        }
    }
}

TEST(CampaignFunction, InMemoryItGivesThePointsTheRecordingDirectoryHolds) {
    const CampaignConfig config = small_dem_campaign();
    // The CLI's way: a file store and the recording directory.
    CampaignRunOptions files;
    files.out_dir = fresh_dir("function-files");
    files.threads = 2;
    run_campaign(config, files);
    const auto written = identification::read_recording(files.out_dir);

    // In memory, with no store at all, on one thread.
    CampaignContext none;
    none.threads = 1;
    const CampaignResult direct = run_campaign(config, none);
    EXPECT_FALSE(std::filesystem::exists(fresh_dir("function-nothing")));
    expect_same_points(direct.recording.points, written.points);
    EXPECT_EQ(direct.config_hash, config_hash(config));
    ASSERT_EQ(direct.levels.size(), 2u);
    // Five frequencies per level and those the grid refinement adds.
    EXPECT_GE(direct.summary.points, 10);
    EXPECT_EQ(direct.summary.points, static_cast<int>(written.points.size()));
    EXPECT_EQ(direct.summary.resumed_points, 0);

    // A memory store: the second call takes every point from it and simulates nothing.
    MemoryCheckpointStore memory;
    CampaignContext stored;
    stored.store = &memory;
    const CampaignResult first = run_campaign(config, stored);
    const CampaignResult again = run_campaign(config, stored);
    EXPECT_EQ(again.summary.resumed_points, direct.summary.points);
    EXPECT_EQ(again.summary.periods_simulated, 0);
    expect_same_points(again.recording.points, first.recording.points);
    expect_same_points(first.recording.points, written.points);
}

TEST(CampaignFunction, SeveralFillingsGiveTheirMeanAndScatterPerLevel) {
    CampaignConfig config = small_dem_campaign();
    set_value_text(config, "campaign.seeds", "3", "test");
    CampaignContext context;
    context.threads = 2;
    context.selection = Selection::of(config, {}, {2.0});
    const CampaignResult result = run_campaign(config, context);
    ASSERT_EQ(result.sweeps.size(), 3u);
    EXPECT_EQ(result.sweeps[1].key, result.sweeps[0].key + "_s1");
    // One FRF, and its estimates, per filling.
    ASSERT_EQ(result.levels.size(), 3u);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(result.levels[static_cast<std::size_t>(k)].filling, k);
    // The bed differs from filling to filling: so do the points.
    EXPECT_NE(result.sweeps[0].rows.front().values[1].amplitude,
              result.sweeps[1].rows.front().values[1].amplitude);
    bool scatter = false;
    for (const auto& row : result.recording.damping) {
        EXPECT_EQ(row.filling, -1);
        if (row.fillings < 2) continue;
        // The mean of the fillings' own estimates, and their scatter.
        double sum = 0.0;
        int n = 0;
        for (const auto& each : identification::filling_damping_rows(result.levels)) {
            if (each.method == row.method) {
                sum += each.damping_ratio;
                ++n;
            }
        }
        EXPECT_EQ(n, row.fillings);
        EXPECT_NEAR(row.damping_ratio, sum / n, 1e-15);
        scatter = scatter || row.damping_ratio_std > 0.0;
    }
    EXPECT_TRUE(scatter);
}

TEST(CampaignFunction, ASelectionRunsExactlyThePointsAskedFor) {
    const CampaignConfig config = small_dem_campaign();
    CampaignContext context;
    context.threads = 1;
    const std::vector<double> wanted{6.25, 6.35, 6.45};
    context.selection = Selection::of(config, {"H-0"}, {1.5}, wanted);
    const CampaignResult result = run_campaign(config, context);
    ASSERT_EQ(result.recording.points.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(result.recording.points[i].arrangement, "H-0");
        EXPECT_EQ(result.recording.points[i].level_g, 1.5);
        EXPECT_EQ(result.recording.points[i].frequency_hz, wanted[i]);
    }
    ASSERT_EQ(result.sweeps.size(), 1u);
    EXPECT_EQ(result.sweeps.front().frequencies_hz, wanted);
}

TEST(CampaignFunction, ASelectionOfAnUnknownArrangementIsRefusedBeforeSimulating) {
    const CampaignConfig config = small_dem_campaign();
    CampaignContext context;
    context.selection.sweeps.push_back({"V-90", 1.0, {}});
    EXPECT_THROW(run_campaign(config, context), config::ConfigException);
}

TEST(CampaignFunction, PointsCarryTheHarmonicRatiosOfEveryChannel) {
    const CampaignConfig config = small_dem_campaign();
    CampaignContext context;
    context.threads = 1;
    context.selection = Selection::of(config, {}, {2.0}, {6.37});
    const CampaignResult result = run_campaign(config, context);
    ASSERT_EQ(result.recording.points.size(), 1u);
    const auto& values = result.recording.points.front().values;
    // The shaker's force is a pure sine; the impacts of the bed distort the acceleration.
    EXPECT_LT(values.front().h2_ratio, 1e-9);
    EXPECT_LT(values.front().h3_ratio, 1e-9);
    EXPECT_GT(values[1].h3_ratio, 1e-4);
    EXPECT_LT(values[1].h3_ratio, 0.5);
}

TEST(CampaignFunction, AnInterruptedRunResumedEqualsAnUninterruptedOneWithStaticFriction) {
    // The history-spring law keeps tangential springs in every contact: a resumed sweep must
    // carry them through the checkpoint, or its numbers part from the uninterrupted run's.
    CampaignConfig config = small_dem_campaign();
    set_value_text(config, "dampers.pd.contact.tangential", "coulomb_spring", "test");
    CampaignContext context;
    context.threads = 1;
    context.selection = Selection::of(config, {}, {2.0});
    const CampaignResult whole = run_campaign(config, context);

    InterruptedStore store(4);  // the first point's start, two points, then the kill
    context.store = &store;
    EXPECT_THROW(run_campaign(config, context), std::runtime_error);
    store.stop_failing();
    const CampaignResult resumed = run_campaign(config, context);
    EXPECT_EQ(resumed.summary.resumed_points, 2);
    expect_same_points(resumed.recording.points, whole.recording.points);
}

TEST(CampaignFunction, ACheckpointWrittenUnderAnotherAutomaticStepIsRefusedNotContinued) {
    // The same config, a build whose automatic step rule differs (as when the rule changed
    // from t_c/20 to t_c/10): the sweep must not go on at the new step from a state reached
    // at the old one.
    CampaignConfig config = small_dem_campaign();
    CampaignContext context;
    context.threads = 1;
    context.selection = Selection::of(config, {}, {2.0});
    InterruptedStore store(3);  // the first point's start, one point, then the kill
    context.store = &store;
    EXPECT_THROW(run_campaign(config, context), std::runtime_error);
    store.stop_failing();

    const std::string key = store.last_key();
    SweepCheckpoint written = parse_checkpoint(*store.load_checkpoint(key), key);
    const std::string step_key = "pd.time_step_s=";
    const auto at = written.numerics.find(step_key);
    ASSERT_NE(at, std::string::npos) << written.numerics;
    const auto value_end = written.numerics.find(' ', at);
    const std::string value =
        written.numerics.substr(at + step_key.size(), value_end - at - step_key.size());
    const double step_s = std::stod(value);
    EXPECT_GT(step_s, 0.0);
    EXPECT_NE(written.numerics.find("step_limit_s="), std::string::npos);
    SweepCheckpoint other = written;
    other.numerics.replace(at + step_key.size(), value.size(), std::to_string(step_s / 2.0));
    store.save_checkpoint(key, serialize_checkpoint(other));
    try {
        run_campaign(config, context);
        ADD_FAILURE() << "a checkpoint written at another step was resumed";
    } catch (const CheckpointError& e) {
        EXPECT_NE(e.message().find("numerics"), std::string::npos) << e.what();
        EXPECT_NE(e.message().find("--restart"), std::string::npos) << e.what();
        EXPECT_NE(e.message().find(written.numerics), std::string::npos) << e.what();
    }
    // Its own numbers resume it.
    store.save_checkpoint(key, serialize_checkpoint(written));
    EXPECT_EQ(run_campaign(config, context).summary.resumed_points, 1);
}

TEST(CampaignFunction, ADamperAtTheShakerPointAddsItsLoadToTheShakersForce) {
    // A mass on a spring driven by the shaker at the mass, the damper's bed locked to its
    // enclosure on the same mass: the bed moves as a rigid mass, so the FRF is that of the
    // mass plus the bed. Had the shaker's force replaced the bed's load at that point, the
    // resonance would be that of the mass alone, 3 % higher. The controller waits out the
    // start's transient (40 periods, 0.5 % tolerance over 12 periods): the 2 %-damped mode
    // sheds it over 1/(2 pi zeta) = 8 periods per e-fold.
    const std::string text = R"(
[campaign]
name = "sdof"
levels_g = [0.5]
control_point = "table"
point_start = "linear-steady-state"
[campaign.frequencies]
low_ratio = 0.97
high_ratio = 1.03
count = 9
grid_damping_ratio = 0.02
[dampers.pd]
point = "table"
locked = true
[dampers.pd.particles]
count = 30
[dampers.pd.contact]
normal_stiffness = 2e5
[controller]
tolerance = 0.005
window_periods = 12
transient_periods = 40
max_periods = 300
drift_horizon_periods = 200
)" + test::table_on_a_spring(0.02);
    const CampaignConfig config = load_campaign_config_text(text, "sdof.toml");
    const CampaignResult result = test::run_on_one_thread(config);
    ASSERT_EQ(result.levels.size(), 1u);
    const auto& level = result.levels.front();
    ASSERT_TRUE(level.circle_fit.ok()) << level.circle_fit.message;
    const double bed_kg = particle_mass_kg(config.campaign.dampers.front(), config.campaign.seed);
    const double k = 2e4;
    const double m = 0.05;
    const double c = 2.0 * 0.02 * std::sqrt(k * m);  // the table's own modal damping
    const double fn = std::sqrt(k / (m + bed_kg)) / (2.0 * std::numbers::pi);
    const double zeta = c / (2.0 * std::sqrt(k * (m + bed_kg)));
    // The bed alone moves the mode by 3 % and its damping ratio by 3 %. The staggered
    // coupling hands the bed's inertia to the structure a step or two late, a damping of about
    // m_bed w^2 dt (+0.4 % of the ratio here); the frequency stays within 1e-4.
    EXPECT_NEAR(level.circle_fit.natural_frequency_hz / fn, 1.0, 1e-3);
    EXPECT_NEAR(level.circle_fit.damping_ratio / zeta, 1.0, 0.01);
}

TEST(CampaignFunction, EnergyPerPointBalancesAndItsLayersAddUp) {
    CampaignConfig config = small_dem_campaign();
    set_value_text(config, "output.energy", "true", "test");
    set_value_text(config, "output.energy_layers", "4", "test");
    set_value_text(config, "output.vtk", "resonance", "test");
    MemoryCheckpointStore store;
    CampaignContext context;
    context.threads = 1;
    context.store = &store;
    context.selection = Selection::of(config, {}, {2.0});
    const CampaignResult result = run_campaign(config, context);
    ASSERT_EQ(result.sweeps.size(), 1u);
    const auto& lines = result.sweeps.front().energy_log;
    ASSERT_GE(lines.size(), 5u);  // one damper: five points and any the refinement adds
    EXPECT_EQ(lines.size(), result.sweeps.front().rows.size());
    for (const auto& line : lines) {
        std::vector<double> cells;
        std::stringstream in(line);
        std::string cell;
        for (int i = 0; std::getline(in, cell, ','); ++i) {
            if (i == 4) {
                EXPECT_EQ(cell, "0") << line;  // the filling
            }
            if (i >= 5) cells.push_back(std::stod(cell));
        }
        ASSERT_EQ(cells.size(), 5u + 4u + 4u) << line;
        const double work = cells[0];
        const double dissipated = cells[1] + cells[2] + cells[3];
        // Over whole steady periods the bed's energy returns: what the walls put in is
        // dissipated (the window's last periods still settle a little: 10 %).
        EXPECT_GT(work, 0.0) << line;
        EXPECT_NEAR(dissipated / work, 1.0, 0.1) << line;
        const double layers = cells[5] + cells[6] + cells[7] + cells[8];
        // The rows hold 9 significant digits.
        EXPECT_NEAR(layers, dissipated, 1e-8 * dissipated) << line;
        // The layers' agitation: the bed at 2 g moves relative to its enclosure.
        double agitation = 0.0;
        for (int l = 9; l < 13; ++l) {
            EXPECT_GE(cells[static_cast<std::size_t>(l)], 0.0) << line;
            agitation += cells[static_cast<std::size_t>(l)];
        }
        EXPECT_GT(agitation, 0.0) << line;
    }
    // The bed at the point of largest response, as a ParaView file.
    const auto files = store.files();
    ASSERT_EQ(files.count("vtk/" + result.sweeps.front().key + "_resonance_pd.vtk"), 1u);
    EXPECT_NE(files.begin()->second.find("POINTS 30 double"), std::string::npos);
}

}  // namespace
}  // namespace sb::bench

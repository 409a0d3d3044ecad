// A characterisation run saves its progress between periods and, killed, continues from it to
// the numbers of an uninterrupted run, bitwise; a damaged or foreign progress is refused.
#include "bench/characterization_progress.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "bench/characterization.hpp"
#include "bench/checkpoint_store.hpp"
#include "bench/resolved_config.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"
#include "core/units.hpp"
#include "killed_store.hpp"
#include "tests/support/enclosure_setups.hpp"

namespace sb::bench {
namespace {

using testing::Killed;
using testing::KilledAfterSaves;

/// 30 loose spheres at 2 g with tangential springs (the law with a history to carry over),
/// where the energy goes measured over three layers (the samples a progress carries too).
EnclosureSetup loose_bed_with_springs() {
    EnclosureSetup setup = sb::test::locked_bed(Eigen::Vector3d(0.0, 0.0, -kStandardGravity));
    setup.options.lock.fraction = 0.0;
    setup.options.contact.tangential = dem::TangentialLaw::coulomb_spring;
    setup.options.energy_layers = 3;
    setup.bed_energy = true;
    return setup;
}

SteadyStateOptions short_criterion() {
    SteadyStateOptions steady;
    steady.transient_periods = 1;
    steady.window_periods = 3;
    steady.max_periods = 9;
    return steady;
}

/// Every number of the result, bitwise.
void expect_same(const ApparentMassPoint& a, const ApparentMassPoint& b) {
    EXPECT_EQ(a.apparent_mass_kg, b.apparent_mass_kg);
    EXPECT_EQ(a.power_w, b.power_w);
    EXPECT_EQ(a.h2_ratio, b.h2_ratio);
    EXPECT_EQ(a.h3_ratio, b.h3_ratio);
    EXPECT_EQ(a.kinetic_j, b.kinetic_j);
    EXPECT_EQ(a.periods, b.periods);
    EXPECT_EQ(a.settled, b.settled);
    ASSERT_EQ(a.energy.has_value(), b.energy.has_value());
    if (!a.energy) return;
    EXPECT_EQ(a.energy->normal_damping_w, b.energy->normal_damping_w);
    EXPECT_EQ(a.energy->friction_w, b.energy->friction_w);
    EXPECT_EQ(a.energy->rolling_w, b.energy->rolling_w);
    EXPECT_EQ(a.energy->mechanical_change_w, b.energy->mechanical_change_w);
    EXPECT_EQ(a.energy->layer_power_w, b.energy->layer_power_w);
    EXPECT_EQ(a.energy->layer_kinetic_j, b.energy->layer_kinetic_j);
    EXPECT_EQ(a.energy->kinetic_lab_j, b.energy->kinetic_lab_j);
    EXPECT_EQ(a.energy->kinetic_amplitude_j, b.energy->kinetic_amplitude_j);
    EXPECT_EQ(a.energy->dissipation_amplitude_w, b.energy->dissipation_amplitude_w);
}

TEST(CharacterizationProgress, ARunKilledBetweenPeriodsContinuesToTheUninterruptedNumbers) {
    const EnclosureSetup setup = loose_bed_with_springs();
    const HarmonicDrive drive = sb::test::drive_along_axis(std::sqrt(2.0) * g_to_m_s2(2.0), 6.3);
    const SteadyStateOptions steady = short_criterion();
    const ApparentMassPoint whole = measure_apparent_mass(setup, drive, steady);
    ASSERT_GE(whole.periods, 7);  // one transient period and two windows of three at least

    // Saved after every period that does not end the run: saving changes nothing.
    std::vector<std::string> saved;
    RunCheckpoints every_period;
    every_period.due = [] { return true; };
    every_period.save = [&](const RunProgress& p) { saved.push_back(serialize_run_progress(p)); };
    expect_same(measure_apparent_mass(setup, drive, steady, {}, every_period), whole);
    ASSERT_EQ(saved.size(), static_cast<std::size_t>(whole.periods - 1));

    for (const std::size_t kill_after : {std::size_t{0}, saved.size() / 2, saved.size() - 1}) {
        SCOPED_TRACE("continued after " + std::to_string(kill_after + 1) + " periods");
        // Through the text, as a file would carry it.
        const RunProgress progress = parse_run_progress(saved[kill_after], "progress.txt");
        EXPECT_EQ(progress.periods.size(), kill_after + 1);
        EXPECT_FALSE(progress.energy.kinetic_j.empty());
        EXPECT_EQ(serialize_run_progress(progress), saved[kill_after]);
        RunCheckpoints resume;
        resume.resume = &progress;
        int first_period = 0;
        const ApparentMassPoint continued = measure_apparent_mass(
            setup, drive, steady,
            [&](int periods) {
                if (first_period == 0) first_period = periods;
            },
            resume);
        EXPECT_EQ(first_period, static_cast<int>(kill_after) + 2);  // no period run twice
        expect_same(continued, whole);
    }
}

TEST(CharacterizationProgress, AProgressThatDoesNotFitTheRunIsRefused) {
    EnclosureSetup setup = loose_bed_with_springs();
    const HarmonicDrive drive = sb::test::drive_along_axis(std::sqrt(2.0) * g_to_m_s2(2.0), 6.3);
    const SteadyStateOptions steady = short_criterion();
    std::optional<RunProgress> first;
    RunCheckpoints save_first;
    save_first.due = [&] { return !first; };
    save_first.save = [&](const RunProgress& p) { first = p; };
    (void)measure_apparent_mass(setup, drive, steady, {}, save_first);
    ASSERT_TRUE(first);
    RunCheckpoints resume;
    resume.resume = &*first;

    HarmonicDrive faster = drive;  // another step count per period
    faster.frequency_hz = 12.6;
    EXPECT_THROW((void)measure_apparent_mass(setup, faster, steady, {}, resume),
                 std::invalid_argument);
    EnclosureSetup without_energy = setup;  // samples the run does not take
    without_energy.bed_energy = false;
    EXPECT_THROW((void)measure_apparent_mass(without_energy, drive, steady, {}, resume),
                 std::invalid_argument);
    RunProgress spent = *first;
    spent.periods.resize(static_cast<std::size_t>(steady.max_periods));
    resume.resume = &spent;
    EXPECT_THROW((void)measure_apparent_mass(setup, drive, steady, {}, resume),
                 std::invalid_argument);  // a budget already spent
}

TEST(CharacterizationProgress, ADamagedProgressTextIsRefusedNamingTheFileAndTheLine) {
    RunProgress p;
    p.steps_per_period = 4;
    p.damper.dem = dem::SolverState{};
    p.periods.resize(2);
    const std::string text = serialize_run_progress(p);
    const auto refused = [](const std::string& damaged, const char* why) {
        try {
            (void)parse_run_progress(damaged, "results/run.progress.txt");
            ADD_FAILURE() << why << ": read";
        } catch (const CheckpointError& e) {
            EXPECT_EQ(e.file(), "results/run.progress.txt") << why;
        }
    };
    refused(text.substr(0, text.size() / 2), "cut short");
    std::string changed = text;
    changed[changed.size() / 2] ^= 0x01;
    refused(changed, "a changed byte");
    refused(seal_checkpoint(std::string(checkpoint_content(text)) + "more\n"), "a line too many");
    std::string other = text;
    other.replace(other.find(" 1\n"), 3, " 9\n");
    refused(other, "another format");
}

/// The 30-sphere H-0 bed at 2 g (test::thirty_sphere_h0), one filling, two frequencies: two
/// short runs, each saving its progress after every period.
CharacterizeOptions saving_after_every_period() {
    CharacterizeOptions options = sb::test::short_characterization(2, 3, 8);
    options.seeds = 1;
    options.checkpoint_interval_s = 0.0;
    return options;
}

TEST(CharacterizationProgress, AKilledCharacterisationContinuesItsRunInProgress) {
    const auto config = test::thirty_sphere_h0("levels_g = [2.0]", "progress.toml");
    CharacterizeOptions options = saving_after_every_period();
    const auto whole = characterize(config, options);  // no store: nothing saved
    ASSERT_EQ(whole.runs, 2);
    const int first_periods = whole.runs_by_filling.front().result.periods;
    ASSERT_GE(first_periods, 7);

    // Killed after the first run's third period: its progress is in the store.
    KilledAfterSaves store(3, Unfinished::result);
    options.store = &store;
    EXPECT_THROW((void)characterize(config, options), Killed);
    std::vector<std::string> lines;
    options.progress = [&](const std::string& line) { lines.push_back(line); };
    const auto resumed = characterize(config, options);
    // The other run went on to its end after the failure (as a process's other threads do)
    // and was stored.
    EXPECT_EQ(resumed.resumed_runs, 1);
    EXPECT_EQ(characterization_csv_text(resumed.table), characterization_csv_text(whole.table));
    bool continued = false;
    for (const auto& line : lines) {
        continued = continued ||
                    line.find("continues from its progress after 3 periods") != std::string::npos;
    }
    EXPECT_TRUE(continued) << ::testing::PrintToString(lines);
    // Every run saved after each of its periods but the last, none twice; every run ended: no
    // progress is left, and the next call takes both runs as they are.
    EXPECT_EQ(store.saves, (first_periods - 1) + (whole.runs_by_filling.back().result.periods - 1));
    const auto again = characterize(config, options);
    EXPECT_EQ(again.resumed_runs, 2);
}

/// A store that remembers the keys of the progresses saved in it and each one's first text;
/// "killed" as the second run saves its first.
class KeyedStore : public MemoryCheckpointStore {
  public:
    void save_progress(Unfinished work, const std::string& key, const std::string& text) override {
        MemoryCheckpointStore::save_progress(work, key, text);
        if (std::find(keys.begin(), keys.end(), key) != keys.end()) return;
        keys.push_back(key);
        first_texts.push_back(text);
        if (keys.size() == 2) throw Killed{};
    }
    std::vector<std::string> keys;
    std::vector<std::string> first_texts;
};

TEST(CharacterizationProgress, ADamagedOrForeignProgressInTheStoreIsRefusedNamingIt) {
    const auto config = test::thirty_sphere_h0("levels_g = [2.0]", "progress.toml");
    CharacterizeOptions options = saving_after_every_period();
    KeyedStore store;
    options.store = &store;
    EXPECT_THROW((void)characterize(config, options), Killed);
    ASSERT_EQ(store.keys.size(), 2u);
    const std::string& first = store.first_texts[0];
    const std::string& second = store.first_texts[1];

    // A changed byte: refused before anything runs, the file named.
    std::string changed = second;
    changed[changed.size() / 2] ^= 0x01;
    MemoryCheckpointStore damaged;
    damaged.open(config_hash(config), false);
    damaged.save_progress(Unfinished::result, store.keys[1], changed);
    options.store = &damaged;
    try {
        (void)characterize(config, options);
        ADD_FAILURE() << "a damaged progress was continued";
    } catch (const config::ConfigException& e) {
        ASSERT_EQ(e.errors().size(), 1u) << e.what();
        EXPECT_EQ(e.errors().front().file,
                  damaged.progress_name(Unfinished::result, store.keys[1]));
        EXPECT_NE(e.errors().front().constraint.find("checksum"), std::string::npos) << e.what();
    }

    // The other frequency's progress under this run's key: sound text, another run.
    MemoryCheckpointStore foreign;
    foreign.open(config_hash(config), false);
    foreign.save_progress(Unfinished::result, store.keys[1], first);
    options.store = &foreign;
    try {
        (void)characterize(config, options);
        ADD_FAILURE() << "another run's progress was continued";
    } catch (const CheckpointError& e) {
        EXPECT_EQ(e.file(), foreign.progress_name(Unfinished::result, store.keys[1]));
        EXPECT_NE(std::string(e.what()).find("steps per period"), std::string::npos) << e.what();
    }
    // With restart the store forgets it, and the run starts over.
    options.restart = true;
    EXPECT_EQ(characterize(config, options).runs, 2);
}

}  // namespace
}  // namespace sb::bench

// The damper characterisation against dampers whose describing function is known in closed
// form: a locked bed (a rigid mass), a single particle in a gap with elastic (e = 1) and
// plastic (e -> 0) impacts.
#include "bench/characterization.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <string>

#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/checkpoint_store.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "core/units.hpp"
#include "dem/setup.hpp"
#include "tests/support/enclosure_setups.hpp"
#include "tests/support/impact_damper.hpp"
#include "tests/support/small_beam_config.hpp"

namespace sb::bench {
namespace {

using Complex = std::complex<double>;
using sb::test::drive_along_axis;
using sb::test::impact_phase;
using sb::test::locked_bed;
using sb::test::plastic_particle_apparent_mass;
using sb::test::single_particle;
using sb::test::sphere_mass_kg;
using test::thirty_sphere_h0;

TEST(Characterization, APlasticParticleInAGapHasTheApparentMassOfItsImpactPattern) {
    constexpr double kGap = 5e-3;
    constexpr double kFrequency = 10.0;
    const double w = hz_to_rad_s(kFrequency);
    const double m = sphere_mass_kg(3e-3, 7800.0);
    // e = 0.01, the DEM's nearest to a plastic impact: the rebound carries 1e-4 of the
    // impact's energy. Two amplitudes: the flight takes 0.62 and 0.32 of a half period.
    for (const double gap_over_amplitude : {1.0, 0.25}) {
        const double x_peak = kGap / gap_over_amplitude;
        const HarmonicDrive drive = drive_along_axis(x_peak * w * w, kFrequency);
        SteadyStateOptions steady;
        steady.tolerance = 1e-3;  // the pattern repeats every period once established
        const ApparentMassPoint point =
            measure_apparent_mass(single_particle(kGap, 0.01), drive, steady);
        ASSERT_TRUE(point.settled) << gap_over_amplitude;
        const Complex exact = plastic_particle_apparent_mass(m, gap_over_amplitude);
        // 2 % of the particle's mass: the stiffness lets the particle sink 0.3 % of the gap
        // into the walls, and the dashpot of e = 0.01 is not quite plastic.
        EXPECT_NEAR(point.apparent_mass_kg.real(), exact.real(), 0.02 * m) << gap_over_amplitude;
        EXPECT_NEAR(point.apparent_mass_kg.imag(), exact.imag(), 0.02 * m) << gap_over_amplitude;
        EXPECT_LT(exact.imag(), -0.1 * m) << "the case dissipates";
        // The ledger's dissipation: two impacts per period, each losing 1/2 m (A/w)^2
        // (1 - cos psi)^2.
        const double psi = impact_phase(gap_over_amplitude);
        const double impact_speed = x_peak * w * (1.0 - std::cos(psi));
        const double power = m * impact_speed * impact_speed * kFrequency;
        EXPECT_NEAR(point.power_w, power, 0.02 * power) << gap_over_amplitude;
    }
}

TEST(Characterization, AnElasticParticleInAGapDissipatesNothing) {
    constexpr double kGap = 5e-3;
    constexpr double kFrequency = 10.0;
    const double w = hz_to_rad_s(kFrequency);
    const double m = sphere_mass_kg(3e-3, 7800.0);
    const double x_peak = kGap;  // the plastic case above dissipates at this amplitude
    const HarmonicDrive drive = drive_along_axis(x_peak * w * w, kFrequency);
    // An elastic ball in a shaken gap moves irregularly (the Fermi-Ulam map), so its force
    // does not repeat from period to period; the window is long enough that the energy it
    // holds at either end (below 1/2 m (2 A/w)^2) is small against the plastic case's loss.
    SteadyStateOptions steady;
    steady.transient_periods = 0;
    steady.window_periods = 100;
    steady.tolerance = 1.0;
    steady.max_periods = 200;
    const ApparentMassPoint point =
        measure_apparent_mass(single_particle(kGap, 1.0), drive, steady);
    const Complex plastic = plastic_particle_apparent_mass(m, 1.0);
    const double plastic_power =
        -plastic.imag() * drive.acceleration_m_s2 * drive.acceleration_m_s2 / (2.0 * w);
    // No dissipation: within 2 % of the particle's mass, and of the plastic particle's power.
    EXPECT_NEAR(point.apparent_mass_kg.imag(), 0.0, 0.02 * m);
    EXPECT_NEAR(point.power_w, 0.0, 0.02 * plastic_power);
}

TEST(Characterization, ALockedBedIsARigidMass) {
    const double m = 30 * sphere_mass_kg(3e-3, 7800.0);
    // Gravity across the motion (H arrangements) and along it (V): a rigid mass either way.
    for (const Eigen::Vector3d& gravity : {Eigen::Vector3d(0.0, -kStandardGravity, 0.0),
                                           Eigen::Vector3d(0.0, 0.0, -kStandardGravity)}) {
        const ApparentMassPoint point = measure_apparent_mass(
            locked_bed(gravity), drive_along_axis(g_to_m_s2(2.0), 6.3), SteadyStateOptions{});
        EXPECT_TRUE(point.settled);
        EXPECT_NEAR(point.bed_mass_kg, m, 1e-12 * m);
        // design.md's 2 %: the snap of the locked particles acts half a step late
        // (w dt / 2 = 2e-4 rad), the rest is rounding.
        EXPECT_NEAR(point.apparent_mass_kg.real(), m, 0.02 * m) << gravity.transpose();
        EXPECT_NEAR(point.apparent_mass_kg.imag(), 0.0, 0.02 * m) << gravity.transpose();
        // It does not move in its enclosure: against the kinetic energy it rides with, 1/2 m
        // (A/w)^2, nothing but the snap's rounding.
        const double riding = 0.5 * m * std::pow(g_to_m_s2(2.0) / hz_to_rad_s(6.3), 2);
        EXPECT_LT(point.kinetic_j, 1e-6 * riding);
    }
}

TEST(Characterization, TheWallsPowerIsTheLossOfTheApparentMass) {
    // A loose bed of 30 spheres at 2 g: whatever its motion, the walls' work on it per period
    // is -<Q v>, and v is a pure sine, so P = -(A^2 / 2w) Im M (docs/characterisation.md).
    EnclosureSetup setup = locked_bed(Eigen::Vector3d(0.0, 0.0, -kStandardGravity));
    setup.options.lock.fraction = 0.0;
    const HarmonicDrive drive = drive_along_axis(std::sqrt(2.0) * g_to_m_s2(2.0), 6.3);
    const ApparentMassPoint point = measure_apparent_mass(setup, drive, SteadyStateOptions{});
    const double w = hz_to_rad_s(drive.frequency_hz);
    const double from_mass = -point.apparent_mass_kg.imag() * drive.acceleration_m_s2 *
                             drive.acceleration_m_s2 / (2.0 * w);
    EXPECT_GT(point.power_w, 0.0);
    // 2 %: the work takes each step's wall velocity, the fundamental the step's start.
    EXPECT_NEAR(point.power_w, from_mass, 0.02 * point.power_w);
}

/// A uniform aluminium cantilever with no added mass: its first mode's tip turns
/// by w'(L)/w(L) per unit deflection, w = cosh bx - cos bx - s (sinh bx - sin bx),
/// s = (cosh bL + cos bL) / (sinh bL + sin bL), bL = 1.8751041 (Euler-Bernoulli).
TEST(Characterization, TheEnergyCriterionHoldsABedThatIsStillStoringOrLosingEnergy) {
    // The plastic particle repeats its pattern every period once established: its stored
    // energy is the same at both ends of the windows, so the energy criterion changes nothing.
    constexpr double kGap = 5e-3;
    const double w = hz_to_rad_s(10.0);
    const HarmonicDrive drive = drive_along_axis(kGap * w * w, 10.0);
    SteadyStateOptions steady;
    steady.tolerance = 1e-3;
    const ApparentMassPoint force_only =
        measure_apparent_mass(single_particle(kGap, 0.01), drive, steady);
    steady.energy_tolerance = 1e-3;
    const ApparentMassPoint both =
        measure_apparent_mass(single_particle(kGap, 0.01), drive, steady);
    ASSERT_TRUE(force_only.settled);
    EXPECT_TRUE(both.settled);
    EXPECT_EQ(both.periods, force_only.periods);
    // A held bed: the walls hardly work on it, its stored energy is measured against the
    // kinetic energy it rides with, and repeats.
    const ApparentMassPoint held_bed =
        measure_apparent_mass(locked_bed(Eigen::Vector3d(0.0, 0.0, -kStandardGravity)),
                              drive_along_axis(g_to_m_s2(2.0), 6.3), steady);
    EXPECT_TRUE(held_bed.settled);
    // A loose bed at 2 g never holds its energy to a millionth of the walls' work: the force
    // criterion alone accepts it, with the energy's it runs to the budget unsettled.
    EnclosureSetup loose = locked_bed(Eigen::Vector3d(0.0, 0.0, -kStandardGravity));
    loose.options.lock.fraction = 0.0;
    const HarmonicDrive shake = drive_along_axis(std::sqrt(2.0) * g_to_m_s2(2.0), 6.3);
    SteadyStateOptions loose_steady;
    loose_steady.max_periods = 24;
    const ApparentMassPoint accepted = measure_apparent_mass(loose, shake, loose_steady);
    EXPECT_TRUE(accepted.settled);
    loose_steady.energy_tolerance = 1e-6;
    const ApparentMassPoint held = measure_apparent_mass(loose, shake, loose_steady);
    EXPECT_FALSE(held.settled);
    EXPECT_EQ(held.periods, loose_steady.max_periods);
    EXPECT_NE(loose_steady.describe().find("stored energy"), std::string::npos);
    loose_steady.energy_tolerance = -0.1;
    EXPECT_THROW(measure_apparent_mass(loose, shake, loose_steady), std::invalid_argument);
}

TEST(Characterization, ACantileverTipTurnsAsItsFirstModeSays) {
    std::string text = sb::test::kSmallBeamConfig;
    const auto at = text.find("[[structure.beam.masses]]");
    text.erase(at, text.find("[structure.excitation]") - at);
    text += "\n[campaign.frequencies]\ncount = 3\n[arrangements.H-0]\n";
    text.replace(text.find("name = \"t\""), 10,
                 "name = \"t\"\nlevels_g = [1.0]\ncontrol_point = \"tip\"");
    const auto config = load_campaign_config_text(text, "cantilever.toml");
    const CampaignPlan plan = plan_campaign(config, Selection::of(config, {}, {}));
    const Eigen::Vector3d psi =
        rotation_per_translation(plan.arrangements.front(), "tip", Eigen::Vector3d::UnitZ());
    const double bl = 1.8751040687;
    const double s = (std::cosh(bl) + std::cos(bl)) / (std::sinh(bl) + std::sin(bl));
    const double w = std::cosh(bl) - std::cos(bl) - s * (std::sinh(bl) - std::sin(bl));
    const double slope = bl * (std::sinh(bl) + std::sin(bl) - s * (std::cosh(bl) - std::cos(bl)));
    const double length = 0.5;
    // A deflection along +z with a rising slope is a rotation about -y.
    const double exact = -slope / w / length;
    // 1 %: 0.5 m x 3 mm is slender (shear and rotary inertia below 1e-4), the elements exact
    // enough at the first mode.
    EXPECT_NEAR(psi.y(), exact, 0.01 * std::abs(exact));
    EXPECT_NEAR(psi.x(), 0.0, 1e-6 * std::abs(exact));
    EXPECT_NEAR(psi.z(), 0.0, 1e-6 * std::abs(exact));
}

TEST(Characterization, TheTableIsTheSameOnOneAndTwoThreads) {
    const auto config = thirty_sphere_h0("levels_g = [2.0]", "threads.toml");
    CharacterizeOptions options = sb::test::short_characterization(2, 3, 8);
    const auto one = characterize(config, options);
    options.threads = 2;
    const auto two = characterize(config, options);
    EXPECT_EQ(one.table.rows.size(), 2u);
    EXPECT_EQ(characterization_csv_text(one.table), characterization_csv_text(two.table));
    EXPECT_EQ(one.table.rows.front().seeds, 2);
}

TEST(Characterization, ARunStillGoingSaysHowManyPeriodsItHasRunAndTheirPace) {
    // A bed of ten thousand spheres takes tens of minutes per run: the lines come every
    // progress_interval_s (here after every period), then the run's own line when it ends.
    const auto config = thirty_sphere_h0("levels_g = [2.0]", "progress.toml");
    CharacterizeOptions options = sb::test::short_characterization(1, 3, 8);
    options.seeds = 1;
    options.progress_interval_s = 0.0;
    std::vector<std::string> lines;
    options.progress = [&](const std::string& line) { lines.push_back(line); };
    const auto result = characterize(config, options);
    ASSERT_EQ(result.runs_by_filling.size(), 1u);
    const int periods = result.runs_by_filling.front().result.periods;
    ASSERT_GE(periods, 7);  // one transient period and two windows of three at least
    std::vector<std::string> going;
    for (const auto& line : lines) {
        if (line.find("periods of at most 8") != std::string::npos) going.push_back(line);
    }
    ASSERT_EQ(going.size(), static_cast<std::size_t>(periods)) << ::testing::PrintToString(lines);
    EXPECT_EQ(going.front().rfind("  H-0 pd 2 g ", 0), 0u) << going.front();
    EXPECT_NE(going.front().find(": 1 periods of at most 8, "), std::string::npos) << going.front();
    EXPECT_NE(going.back().find(": " + std::to_string(periods) + " periods of at most 8, "),
              std::string::npos)
        << going.back();
    EXPECT_NE(going.back().find(" s per period"), std::string::npos) << going.back();
    // the run's own line comes last
    EXPECT_EQ(lines.back().rfind("[1/1] H-0 pd 2 g ", 0), 0u) << lines.back();
    // with the default interval a run of a few seconds says nothing until it ends
    options.progress_interval_s = 60.0;
    lines.clear();
    (void)characterize(config, options);
    for (const auto& line : lines) EXPECT_EQ(line.find("periods of at most"), std::string::npos);
}

/// The 30-sphere H-0 bed at 1 and 2 g: a characterisation cheap enough to run four times.
CampaignConfig small_h0_bed(const std::string& name) {
    return thirty_sphere_h0("levels_g = [1.0, 2.0]", name);
}

TEST(Characterization, AnExtendedCharacterisationRunsOnlyWhatTheStoreDoesNotHold) {
    // The 2 g runs first, then 1 and 2 g with the same store: the second call takes the 2 g
    // runs and the beds from the store and runs the 1 g ones, and its table is the one a
    // single call over both levels gives. A third call simulates nothing.
    const auto config = small_h0_bed("extended.toml");
    CharacterizeOptions options = sb::test::short_characterization(2, 3, 8);
    const auto whole = characterize(config, options);
    ASSERT_EQ(whole.runs, 8);
    EXPECT_EQ(whole.resumed_runs, 0);
    // One stiffness for the campaign (sized for 2 g): both levels shake the same two beds.
    EXPECT_EQ(whole.beds_settled, 2);

    MemoryCheckpointStore store;
    options.store = &store;
    CharacterizeOptions first = options;
    first.levels_g = {2.0};
    const auto part = characterize(config, first);
    EXPECT_EQ(part.runs, 4);
    EXPECT_EQ(part.resumed_runs, 0);
    EXPECT_EQ(part.beds_settled, 2);

    const auto extended = characterize(config, options);
    EXPECT_EQ(extended.runs, 8);
    EXPECT_EQ(extended.resumed_runs, 4);
    EXPECT_EQ(extended.beds_settled, 0);
    EXPECT_EQ(characterization_csv_text(extended.table), characterization_csv_text(whole.table));

    const auto again = characterize(config, options);
    EXPECT_EQ(again.resumed_runs, 8);
    EXPECT_EQ(again.beds_settled, 0);
    EXPECT_EQ(characterization_csv_text(again.table), characterization_csv_text(whole.table));

    // Another criterion is another run: nothing of the store is taken for it.
    CharacterizeOptions longer = options;
    longer.levels_g = {2.0};
    longer.steady.max_periods = 9;
    const auto other = characterize(config, longer);
    EXPECT_EQ(other.resumed_runs, 0);
    EXPECT_EQ(other.beds_settled, 0);  // the beds do not depend on the criterion
    // With a stiffness per level (the campaign's other choice) each level has its own beds.
    CampaignConfig per_level = config;
    apply_overrides(per_level, {"dampers.pd.contact.stiffness_for=level"});
    MemoryCheckpointStore per_level_store;
    CharacterizeOptions both = options;
    both.store = &per_level_store;
    EXPECT_EQ(characterize(per_level, both).beds_settled, 4);  // two fillings at two stiffnesses
    // With restart the store forgets this config's runs and beds.
    options.restart = true;
    const auto restarted = characterize(config, options);
    EXPECT_EQ(restarted.resumed_runs, 0);
    EXPECT_EQ(restarted.beds_settled, 2);
    EXPECT_EQ(characterization_csv_text(restarted.table), characterization_csv_text(whole.table));
}

TEST(Characterization, ADamagedStoredRunIsRefusedNamingItsFile) {
    namespace fs = std::filesystem;
    const fs::path dir =
        fs::temp_directory_path() / ("shakerbench-char-store-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const auto config = small_h0_bed("damaged.toml");
    CharacterizeOptions options = sb::test::short_characterization(1, 3, 7);
    options.levels_g = {2.0};
    options.seeds = 1;
    FileCheckpointStore store(dir);
    options.store = &store;
    const auto first = characterize(config, options);
    ASSERT_EQ(first.runs, 1);
    std::vector<fs::path> results;
    for (const auto& entry : fs::directory_iterator(dir / "results")) {
        results.push_back(entry.path());
    }
    ASSERT_EQ(results.size(), 1u);
    const auto resumed = characterize(config, options);
    EXPECT_EQ(resumed.resumed_runs, 1);
    EXPECT_EQ(characterization_csv_text(resumed.table), characterization_csv_text(first.table));

    std::string text = read_text_file(results.front());
    text[text.size() / 3] = text[text.size() / 3] == '1' ? '2' : '1';  // one byte changed
    std::ofstream(results.front(), std::ios::binary) << text;
    try {
        (void)characterize(config, options);
        ADD_FAILURE() << "a damaged stored run was resumed";
    } catch (const config::ConfigException& e) {
        ASSERT_EQ(e.errors().size(), 1u) << e.what();
        EXPECT_EQ(e.errors().front().file, results.front().string());
        EXPECT_NE(e.errors().front().constraint.find("checksum"), std::string::npos) << e.what();
    }
    options.restart = true;
    const auto redone = characterize(config, options);
    EXPECT_EQ(redone.resumed_runs, 0);
    EXPECT_EQ(characterization_csv_text(redone.table), characterization_csv_text(first.table));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace sb::bench

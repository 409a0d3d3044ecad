// Runs from rest (campaign.transient): the linear response builds up from rest as the closed
// form says, a lock releases its share of the bed at its set time, in a resumed run too, and
// the config's errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/campaign_output.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/checkpoint_store.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "core/units.hpp"
#include "killed_store.hpp"

namespace sb::bench {
namespace {

/// The cells of a CSV row.
std::vector<double> cells(const std::string& line) {
    std::vector<double> out;
    std::stringstream in(line);
    std::string cell;
    while (std::getline(in, cell, ',')) out.push_back(std::stod(cell));
    return out;
}

// A mass on a spring, 2 % damped, driven from rest by a fixed force at 0.8 of its natural
// frequency.
constexpr double kOscillatorMassKg = 0.05, kStiffness = 2e4, kZeta = 0.02, kForceN = 0.5;

const std::string kSdof = R"(
[campaign]
name = "from-rest"
control_point = "table"
[[campaign.channels]]
quantity = "displacement"
point = "table"
[campaign.drive]
kind = "fixed"
amplitudes = [0.5]
[campaign.transient]
duration_s = 0.8
frequency_hz = 80.0
checkpoint_periods = 16
[output]
series_samples_per_period = 64
)" + test::table_on_a_spring(0.02);

/// x(t) of the mass from rest under F sin(w t): the steady state plus the free vibration
/// that meets x(0) = 0, x'(0) = 0; `mass_kg`: the table's, or with what moves with it; the
/// dashpot is the table's own, c = 2 zeta sqrt(k m_table) (its modal damping).
double closed_form_displacement(double t, double mass_kg = kOscillatorMassKg) {
    const double c = 2.0 * kZeta * std::sqrt(kStiffness * kOscillatorMassKg);
    const double wn = std::sqrt(kStiffness / mass_kg);
    const double zeta = c / (2.0 * mass_kg * wn);
    const double w = kTwoPi * 80.0;
    const double wd = wn * std::sqrt(1.0 - zeta * zeta);
    // Steady state X = F / (k - m w^2 + i c w), x = Im{X e^{i w t}}.
    const std::complex<double> x =
        kForceN / std::complex<double>(kStiffness - mass_kg * w * w, c * w);
    const double xs0 = x.imag();      // x_s(0)
    const double vs0 = w * x.real();  // x_s'(0)
    const double a = -xs0;            // free part: e^{-z wn t}(a cos wd t + b sin wd t)
    const double b = (-vs0 + zeta * wn * a) / wd;
    return (x * std::polar(1.0, w * t)).imag() +
           std::exp(-zeta * wn * t) * (a * std::cos(wd * t) + b * std::sin(wd * t));
}

TEST(TransientRun, ALinearSpecimenFromRestFollowsTheClosedForm) {
    const CampaignConfig config = load_campaign_config_text(kSdof, "from-rest.toml");
    const CampaignResult result = test::run_on_one_thread(config);
    ASSERT_EQ(result.sweeps.size(), 1u);
    const SweepResult& sweep = result.sweeps.front();
    EXPECT_TRUE(result.recording.points.empty());
    ASSERT_EQ(sweep.transient_channels.size(), 3u);
    EXPECT_EQ(sweep.transient_channels[2], "disp_table");
    ASSERT_EQ(sweep.transient_envelope.size(), 64u);  // 0.8 s at 80 Hz
    ASSERT_EQ(sweep.transient_series.size(), 64u * 64u);
    double largest = 0.0, worst = 0.0;
    for (const auto& line : sweep.transient_series) {
        const auto row = cells(line);
        const double expected = closed_form_displacement(row[0]);
        largest = std::max(largest, std::abs(expected));
        worst = std::max(worst, std::abs(row[3] - expected));  // time, force, acc, disp
        EXPECT_NEAR(row[1], kForceN * std::sin(kTwoPi * 80.0 * row[0]), 1e-6) << row[0];
    }
    // The beat of the start's free vibration against the drive, within 0.02 % of its peak
    // (5e-5 measured: the step's sampling of the sine).
    EXPECT_LT(worst, 2e-4 * largest) << "largest " << largest;
    // The envelope holds each period's extremes of the same samples and steps.
    for (const auto& line : sweep.transient_envelope) {
        const auto row = cells(line);
        ASSERT_EQ(row.size(), 2u + 2u * 3u);
        EXPECT_LE(row[2 + 2], row[2 + 3 + 2]);  // min <= max of disp_table
        EXPECT_GT(row[2 + 3 + 2] - row[2 + 2], 0.0);
    }
}

TEST(TransientRun, ItsDirectoryHoldsTheTimeHistoriesAndNoTransferFunction) {
    // No points and no levels: points.csv is its header (the directory stays a recording
    // that `identify` reads), and there is no frf.uff of no records.
    const CampaignConfig config = load_campaign_config_text(kSdof, "from-rest.toml");
    const CampaignResult result = test::run_on_one_thread(config);
    const auto dir = test::fresh_dir("transient-output");
    write_campaign_output(config, result, {dir, kSdof, "test"});
    const std::string sweep = result.sweeps.front().key;
    const std::string series = read_text_file(dir / "transient" / (sweep + ".csv"));
    EXPECT_EQ(std::count(series.begin(), series.end(), '\n'), 1 + 64 * 64);
    EXPECT_TRUE(std::filesystem::exists(dir / "transient" / (sweep + "_envelope.csv")));
    const std::string points = read_text_file(dir / "points.csv");
    EXPECT_EQ(std::count(points.begin(), points.end(), '\n'), 1) << points;
    EXPECT_FALSE(std::filesystem::exists(dir / "frf.uff"));
    EXPECT_TRUE(std::filesystem::exists(dir / "recording.toml"));
    std::filesystem::remove_all(dir);
}

/// kSdof run for `duration_s` with damper pd at the table, `tables` its [dampers.pd.*]
/// tables, and its force recorded.
std::string sdof_with_damper(const std::string& tables, const std::string& duration_s) {
    std::string text = kSdof + "\n[dampers.pd]\npoint = \"table\"\n" + tables +
                       "[[campaign.channels]]\nquantity = \"damper-force\"\ndamper = \"pd\"\n";
    text.replace(text.find("duration_s = 0.8"), 16, "duration_s = " + duration_s);
    return text;
}

TEST(TransientRun, ALockReleasesItsShareAtItsTimeInAResumedRunToo) {
    // Every sphere held, 30 % of them freed at 0.25 s (10 of 30, between the second and the
    // third checkpoint). Held, the bed is rigid mass of the structure whose force is -m a;
    // freed, the spheres rattle and the force is no longer that.
    std::string text = sdof_with_damper(R"(
[dampers.pd.particles]
count = 30
[dampers.pd.contact]
normal_stiffness = 2e5
[dampers.pd.lock]
fraction = 1.0
release_time_s = 0.25
release_fraction = 0.3
)",
                                        "0.5");
    text.replace(text.find("checkpoint_periods = 16"), 23, "checkpoint_periods = 8");
    const CampaignConfig config = load_campaign_config_text(text, "release.toml");
    CampaignContext context;
    context.threads = 1;
    testing::InterruptedStore whole_store;
    context.store = &whole_store;
    const CampaignResult whole = run_campaign(config, context);
    ASSERT_EQ(whole.sweeps.size(), 1u);
    EXPECT_NE(whole.sweeps.front().settings.back().find("9 of 30 particles freed at t = 0.25 s"),
              std::string::npos)
        << whole.sweeps.front().settings.back();

    // Every checkpoint: all 30 held before 0.25 s of the damper's clock, 21 after.
    ASSERT_EQ(whole_store.saved.size(), 5u);  // 40 periods, 8 per checkpoint
    for (const auto& saved : whole_store.saved) {
        const SweepCheckpoint c = parse_checkpoint(saved, "checkpoint");
        ASSERT_TRUE(c.state.attachments.front().dem);
        const auto& dem = *c.state.attachments.front().dem;
        EXPECT_NEAR(dem.time_s, c.transient_periods / 80.0, 1e-9);
        EXPECT_EQ(dem.locked.size(), dem.time_s < 0.25 ? 30u : 21u) << dem.time_s;
    }

    // Killed at the third checkpoint (after the release's period ran), resumed: the same
    // rows, number for number.
    testing::InterruptedStore store(3);
    context.store = &store;
    EXPECT_THROW(run_campaign(config, context), std::runtime_error);
    store.stop_failing();
    const CampaignResult resumed = run_campaign(config, context);
    EXPECT_EQ(resumed.sweeps.front().transient_series, whole.sweeps.front().transient_series);
    EXPECT_EQ(resumed.sweeps.front().transient_envelope, whole.sweeps.front().transient_envelope);

    // Held, the force is the bed's inertia, -m a; freed, the rattling departs from it.
    const double bed_kg = particle_mass_kg(config.campaign.dampers.front(), config.campaign.seed);
    double held = 0.0, freed = 0.0, scale = 0.0;
    for (const auto& line : whole.sweeps.front().transient_series) {
        const auto row = cells(line);
        // time, force, acc_table, disp_table, force_pd; the weight pulls along -z.
        const double inertia = -bed_kg * row[2];
        scale = std::max(scale, std::abs(inertia));
        const double departure = std::abs(row[4] - (inertia - bed_kg * kStandardGravity));
        if (row[0] < 0.24) held = std::max(held, departure);
        if (row[0] > 0.26) freed = std::max(freed, departure);
    }
    // Held, the structure's mass carries the bed: the force is its weight and inertia exactly.
    EXPECT_LT(held, 1e-9 * scale);
    EXPECT_GT(freed, 0.1 * scale);
}

TEST(TransientRun, AHeldBedFourTimesTheTablesMassMovesWithItAsRigidMass) {
    // 50 tungsten-carbide spheres of 8 mm, 0.22 kg, all held on a 0.05 kg table: the
    // structure carries them in its mass matrix, so the table with its bed follows the closed
    // form of a 0.27 kg mass on the table's spring and dashpot (the bed adds mass, not
    // damping: 2 % of the table alone, 0.86 % of the loaded mode). Applied as the
    // staggered loop's load, a step late, their inertia would be an added mass 4.4 times the
    // table's, and the run would diverge within a few steps.
    const std::string text = sdof_with_damper(R"(
[dampers.pd.enclosure]
inner_diameter_m = 0.045
height_m = 0.04
[dampers.pd.particles]
count = 50
diameter_m = 0.008
density_kg_m3 = 15600.0
[dampers.pd.contact]
normal_stiffness = 2e5
[dampers.pd.lock]
fraction = 1.0
)",
                                              "0.4");
    const CampaignConfig config = load_campaign_config_text(text, "held.toml");
    const double bed_kg = particle_mass_kg(config.campaign.dampers.front(), config.campaign.seed);
    ASSERT_GT(bed_kg, 4.0 * kOscillatorMassKg);
    const CampaignResult result = test::run_on_one_thread(config);
    ASSERT_EQ(result.sweeps.size(), 1u);
    const double total_kg = kOscillatorMassKg + bed_kg;
    const double sag_m = -bed_kg * kStandardGravity / kStiffness;  // the bed's weight, static
    double largest = 0.0, worst = 0.0, force_scale = 0.0, force_worst = 0.0;
    for (const auto& line : result.sweeps.front().transient_series) {
        const auto row = cells(line);  // time, force, acc_table, disp_table, force_pd
        const double expected = closed_form_displacement(row[0], total_kg);
        largest = std::max(largest, std::abs(expected));
        worst = std::max(worst, std::abs(row[3] - sag_m - expected));
        // The damper's force on the table: its weight and the inertia of the held bed.
        const double inertia = -bed_kg * row[2];
        force_scale = std::max(force_scale, std::abs(inertia));
        force_worst =
            std::max(force_worst, std::abs(row[4] - (inertia - bed_kg * kStandardGravity)));
    }
    // Within the step's sampling of the drive, as the table alone (1.6e-5 measured): the hold
    // balances the bed's contacts in the step they act, so a settled bed whose contacts do
    // not carry its weight exactly when the run begins gives the table no impulse (balanced a
    // step later, it did: 8.7e-4 of the peak, and 1.7e-3 with the pair contacts rounded
    // otherwise, a free vibration that followed the filling's rounding).
    EXPECT_LT(worst, 2e-4 * largest) << "largest " << largest;
    EXPECT_LT(force_worst, 1e-9 * force_scale) << "scale " << force_scale;
}

TEST(TransientRun, WithoutAFixedDriveOrAFrequencyItIsAConfigError) {
    std::string text = kSdof;
    text.replace(text.find("frequency_hz = 80.0\n"), 20, "");
    std::string message = test::config_error(text, "transient.toml");
    EXPECT_NE(message.find("campaign.transient.frequency_hz"), std::string::npos) << message;
    EXPECT_NE(message.find("is required"), std::string::npos) << message;

    text = kSdof;
    text.replace(text.find("kind = \"fixed\"\namplitudes = [0.5]\n"), 34, "");
    text.replace(text.find("name = \"from-rest\"\n"), 19,
                 "name = \"from-rest\"\nlevels_g = [1.0]\n");
    message = test::config_error(text, "transient.toml");
    EXPECT_NE(message.find("campaign.transient.duration_s"), std::string::npos) << message;
    EXPECT_NE(message.find("needs campaign.drive.kind = \"fixed\""), std::string::npos) << message;
}

}  // namespace
}  // namespace sb::bench

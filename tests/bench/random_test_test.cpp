// Random tests (campaign.random): the noise is the band it says, H1 of a linear oscillator is
// its accelerance and its modal fit the oscillator's frequency and damping, the level holds,
// an interrupted test resumes to the same numbers, and the config's errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/campaign_output.hpp"
#include "bench/checkpoint_store.hpp"
#include "bench/random_noise.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "core/units.hpp"
#include "identification/recording_io.hpp"
#include "identification/spectrum.hpp"
#include "killed_store.hpp"

namespace sb::bench {
namespace {

TEST(BandLimitedNoise, HasUnitRmsNoLineOutsideItsBandAndRepeatsWithItsSeed) {
    const BandLimitedNoise noise(20.0, 80.0, 10.0, 3);
    const auto& x = noise.samples();
    double mean_square = 0.0;
    for (double v : x) mean_square += v * v;
    EXPECT_NEAR(mean_square / static_cast<double>(x.size()), 1.0, 1e-12);
    const auto spectrum = identification::real_spectrum(x);
    const double df = noise.sample_rate_hz() / static_cast<double>(x.size());
    double inside = 0.0, outside = 0.0;
    for (std::size_t j = 0; j < spectrum.size(); ++j) {
        const double f = static_cast<double>(j) * df;
        (f >= 20.0 - 1e-9 && f <= 80.0 + 1e-9 ? inside : outside) += std::norm(spectrum[j]);
    }
    EXPECT_LT(outside, 1e-20 * inside);
    // Between samples: the straight line through them; at a sample, the sample.
    const double dt = 1.0 / noise.sample_rate_hz();
    EXPECT_DOUBLE_EQ(noise(5 * dt), x[5]);
    EXPECT_NEAR(noise(5.25 * dt), 0.75 * x[5] + 0.25 * x[6], 1e-12);
    EXPECT_EQ(BandLimitedNoise(20.0, 80.0, 10.0, 3).samples(), x);
    EXPECT_NE(BandLimitedNoise(20.0, 80.0, 10.0, 4).samples(), x);
}

// The oscillator of test::table_on_a_spring: 0.05 kg on 2e4 N/m, 2 % damped (100.66 Hz,
// half-power bandwidth 4 Hz), driven by noise in 50-150 Hz at 0.25 Hz lines.
constexpr double kRandomMassKg = 0.05, kRandomStiffness = 2e4, kRandomZeta = 0.02;

std::string random_sdof(double level_g, const std::string& random_extra = "") {
    return R"(
[campaign]
name = "random-sdof"
control_point = "table"
levels_g = [)" +
           config::number_text(level_g) +
           R"(]
[campaign.random]
low_hz = 50.0
high_hz = 150.0
resolution_hz = 0.25
averages = 16
)" + random_extra +
           test::table_on_a_spring(kRandomZeta);
}

std::complex<double> oscillator_accelerance(double f_hz) {
    const double w = kTwoPi * f_hz;
    const double c = 2.0 * kRandomZeta * std::sqrt(kRandomStiffness * kRandomMassKg);
    return -w * w / std::complex<double>(kRandomStiffness - kRandomMassKg * w * w, c * w);
}

TEST(RandomTest, H1OfALinearOscillatorIsItsAccelerationAndItsFitTheOscillator) {
    const CampaignConfig config = load_campaign_config_text(random_sdof(2.0), "random.toml");
    const CampaignResult result = test::run_on_one_thread(config);
    ASSERT_EQ(result.sweeps.size(), 1u);
    const auto& rows = result.recording.points;
    ASSERT_EQ(rows.size(), 401u);  // 50 to 150 Hz at 0.25 Hz
    const double fn = std::sqrt(kRandomStiffness / kRandomMassKg) / kTwoPi;
    double peak_error = 0.0;
    for (const auto& row : rows) {
        EXPECT_EQ(row.status, "random");
        const auto h1 = row.values[1].amplitude / row.values[0].amplitude;
        const double error = std::abs(h1 / oscillator_accelerance(row.frequency_hz) - 1.0);
        // The coherence from the line's RMS values: |H1|² G_xx / G_yy.
        const double coherence = std::norm(h1) * std::pow(row.values[0].rms / row.values[1].rms, 2);
        EXPECT_LE(coherence, 1.0 + 1e-9);
        // H1's random error over n_d = 16 averages, sqrt(1 - g²) / (|g| sqrt(2 n_d))
        // (Bendat & Piersol 2010, Table 9.6), four times, with the Hann window's bias at the
        // peak, (1/3)(1.5 df / 2 zeta fn)² = 0.3 % (§8.5.1), besides: the coherence is below
        // 1 near the peak (0.993 at worst) because each 4 s segment holds the response to
        // drive from before it (a 2 % mode rings for 1 / (zeta w) = 0.08 s).
        const double allowed = 0.003 + 4.0 * std::sqrt(1.0 - std::min(coherence, 1.0)) /
                                           (std::sqrt(coherence) * std::sqrt(32.0));
        EXPECT_LT(error, allowed) << row.frequency_hz << " Hz, coherence " << coherence;
        if (std::abs(row.frequency_hz - 100.75) < 1.0) peak_error = std::max(peak_error, error);
    }
    EXPECT_GT(peak_error, 0.0);
    // The level: the band RMS the drive's spectrum gives through H1 held within 5 %.
    const std::string& line = result.sweeps.front().settings.back();
    const auto at = line.find("control ");
    ASSERT_NE(at, std::string::npos) << line;
    EXPECT_NEAR(std::stod(line.substr(at + 8)), 2.0, 0.1) << line;
    EXPECT_EQ(line.find("did not hold"), std::string::npos) << line;
    int fits = 0;
    for (const auto& d : result.recording.damping) {
        if (d.method != "half-power" && d.method != "circle-fit") continue;
        ++fits;
        EXPECT_NEAR(d.natural_frequency_hz, fn, 1e-3 * fn) << d.method;
        EXPECT_NEAR(d.damping_ratio, kRandomZeta, 0.03 * kRandomZeta) << d.method;
    }
    EXPECT_EQ(fits, 2);
}

TEST(RandomTest, ItsDirectoryHoldsTheSpectraAndTheLinesAsARecordingThatReadsBack) {
    const CampaignConfig config = load_campaign_config_text(random_sdof(1.0), "random.toml");
    const CampaignResult result = test::run_on_one_thread(config);
    // Another process's sweep comes back whole (mpirun: distributed/).
    const SweepResult& sweep = result.sweeps.front();
    const SweepResult back = parse_sweep_result(serialize_sweep_result(sweep), "rank 1");
    EXPECT_EQ(back.random_spectra, sweep.random_spectra);
    const auto dir = test::fresh_dir("random-output");
    write_campaign_output(config, result, {dir, random_sdof(1.0), "test"});
    const std::string spectra = read_text_file(dir / "random" / (sweep.key + ".csv"));
    EXPECT_EQ(spectra.substr(0, spectra.find('\n')),
              "frequency_hz,force_psd,acc_table_psd,acc_table_h1_re,acc_table_h1_im,"
              "acc_table_coherence");
    EXPECT_EQ(std::count(spectra.begin(), spectra.end(), '\n'), 1 + 401);
    const identification::Recording recording = identification::read_recording(dir);
    ASSERT_EQ(recording.points.size(), 401u);
    for (std::size_t i = 0; i < recording.points.size(); ++i) {
        EXPECT_EQ(recording.points[i].status, "random");
        const auto read = recording.points[i].values[1].amplitude;
        const auto run = result.recording.points[i].values[1].amplitude;
        EXPECT_LE(std::abs(read - run), 1e-12 * std::abs(run)) << i;
    }
    std::filesystem::remove_all(dir);
}

TEST(RandomTest, AnInterruptedTestResumesToTheSameNumbers) {
    const CampaignConfig config =
        load_campaign_config_text(random_sdof(1.0, "checkpoint_segments = 3\n"), "random.toml");
    testing::InterruptedStore whole_store;
    const CampaignResult whole = test::run_on_one_thread(config, &whole_store);
    const int saves = static_cast<int>(whole_store.saved.size());
    // Level segments, then every third of the 17 halves and the last.
    ASSERT_GE(saves, 7);
    for (int fail_at : {2, saves - 2}) {
        testing::InterruptedStore store(fail_at);
        EXPECT_THROW(test::run_on_one_thread(config, &store), std::runtime_error);
        store.stop_failing();
        const CampaignResult resumed = test::run_on_one_thread(config, &store);
        ASSERT_EQ(resumed.recording.points.size(), whole.recording.points.size());
        for (std::size_t i = 0; i < whole.recording.points.size(); ++i) {
            const auto& a = resumed.recording.points[i].values;
            const auto& b = whole.recording.points[i].values;
            for (std::size_t c = 0; c < a.size(); ++c) {
                EXPECT_EQ(a[c].amplitude, b[c].amplitude) << fail_at << " " << i;
                EXPECT_EQ(a[c].rms, b[c].rms) << fail_at << " " << i;
            }
        }
    }
}

TEST(RandomTest, TheCheckpointTextGivesItsProgressBackExactly) {
    SweepCheckpoint c;
    c.config_hash = "abc";
    c.state.q = Eigen::VectorXd::Constant(1, 0.25);
    c.state.q_dot = Eigen::VectorXd::Constant(1, -1.0 / 3.0);
    RandomProgress p;
    p.level_segments = 3;
    p.level_done = true;
    p.drive_rms = 0.1 + 1e-17;
    p.level_rms = 9.80665;
    p.halves = 5;
    p.tail = {{1.0 / 3.0, 2.0}, {-0.5, 1e-300}};
    p.sums.segments = 4;
    p.sums.reference = {1.0, 2.0 / 3.0};
    p.sums.response = {{3.0, 4.0}};
    p.sums.cross = {{{0.1, -0.2}, {1.0 / 7.0, 5.0}}};
    c.random = p;
    const SweepCheckpoint back = parse_checkpoint(serialize_checkpoint(c), "c.txt");
    ASSERT_TRUE(back.random);
    EXPECT_EQ(back.random->level_segments, 3);
    EXPECT_TRUE(back.random->level_done);
    EXPECT_EQ(back.random->drive_rms, p.drive_rms);
    EXPECT_EQ(back.random->halves, 5);
    EXPECT_EQ(back.random->tail, p.tail);
    EXPECT_EQ(back.random->sums.reference, p.sums.reference);
    EXPECT_EQ(back.random->sums.response, p.sums.response);
    EXPECT_EQ(back.random->sums.cross, p.sums.cross);
    // A sum of another length than the line count is damage.
    std::string text = serialize_checkpoint(c);
    const auto at = text.find("gyy 2 ");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 6, "gyy 1 ");
    EXPECT_THROW(parse_checkpoint(seal_checkpoint(checkpoint_content(text)), "c.txt"),
                 CheckpointError);
}

TEST(RandomTest, ABandUpsideDownABaseExcitationOrARunFromRestIsAConfigError) {
    std::string text = random_sdof(1.0);
    text.replace(text.find("low_hz = 50.0"), 13, "low_hz = 150.0");
    std::string message = test::config_error(text, "random.toml");
    EXPECT_NE(message.find("campaign.random.low_hz"), std::string::npos) << message;
    EXPECT_NE(message.find("below campaign.random.high_hz"), std::string::npos) << message;

    text = random_sdof(1.0);
    text.replace(text.find("resolution_hz = 0.25"), 20, "resolution_hz = 20");
    message = test::config_error(text, "random.toml");
    EXPECT_NE(message.find("campaign.random.resolution_hz"), std::string::npos) << message;

    text = R"(
[campaign]
name = "random-base"
control_point = "table"
levels_g = [1.0]
[campaign.random]
low_hz = 50.0
high_hz = 150.0
)" + test::table_on_a_spring(kRandomZeta, true);
    message = test::config_error(text, "random.toml");
    EXPECT_NE(message.find("needs a force excitation"), std::string::npos) << message;

    text = random_sdof(1.5) +
           "[campaign.drive]\nkind = \"fixed\"\namplitudes = [1.0]\n"
           "[campaign.transient]\nduration_s = 1.0\nfrequency_hz = 100.0\n";
    text.replace(text.find("levels_g = [1.5]\n"), 17, "");
    message = test::config_error(text, "random.toml");
    EXPECT_NE(message.find("cannot go with campaign.transient"), std::string::npos) << message;
}

TEST(RandomTest, Paper003sSphereDampsOnceItLiftsOffAndItsMassLeavesTheMode) {
    // Paper 003's beam under random drive, 10 mm gap, at 0.16 and 0.61 g RMS at the casing,
    // beside the sphere held as rigid mass. Below lift-off the sphere rides the floor: the
    // beam's damping and frequency are the rigid sphere's. Above it (peaks of 3 sigma pass
    // 1 g from about 0.33 g RMS on) it bounces: it damps (1.93 % against the rig's 1.38 %
    // over three fillings, docs/validation.md) and its mass no longer moves with the mode,
    // whose frequency rises towards the beam's without it (46.97 Hz against 46.61).
    const auto run = [](bool rigid) {
        CampaignConfig config =
            load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper003-beam.toml");
        set_value_text(config, "campaign.levels_g", "[0.16, 0.613333]", "test");
        set_value_text(config, "campaign.random.low_hz", "10", "test");
        set_value_text(config, "campaign.random.high_hz", "100", "test");
        set_value_text(config, "campaign.random.resolution_hz", "0.0625", "test");
        if (rigid) set_value_text(config, "dampers.pd.model", "\"rigid\"", "test");
        return test::run_on_one_thread(config);
    };
    const CampaignResult held = run(true);
    const CampaignResult free = run(false);
    const auto circle = [](const CampaignResult& r, double level_g) {
        for (const auto& d : r.recording.damping) {
            if (d.method == "circle-fit" && std::abs(d.level_g - level_g) < 1e-3) return d;
        }
        ADD_FAILURE() << "no circle fit at " << level_g << " g";
        return identification::DampingRow{};
    };
    for (double level : {0.16, 0.613333}) {
        // The rigid sphere: the rig's 1.382 % within the identification's 1 %.
        EXPECT_NEAR(circle(held, level).damping_ratio, 0.01382, 0.01 * 0.01382) << level;
    }
    // Riding, the sphere sits on its contact spring (40.76 kN/m: 300 Hz with its 11.5 g), which
    // below that moves a little more than the rigid mass, 1 / (1 - (46.6/300)²) - 1 = 2.5 %
    // of 11.5 g: the mode 0.009 Hz lower, its damping 0.2 % of itself lower (measured 0.0085 Hz
    // and 2.4e-5).
    EXPECT_NEAR(circle(free, 0.16).damping_ratio, circle(held, 0.16).damping_ratio, 5e-5);
    EXPECT_NEAR(circle(free, 0.16).natural_frequency_hz, circle(held, 0.16).natural_frequency_hz,
                0.02);
    EXPECT_GT(circle(free, 0.613333).damping_ratio, circle(held, 0.613333).damping_ratio + 0.003);
    EXPECT_GT(circle(free, 0.613333).natural_frequency_hz,
              circle(held, 0.613333).natural_frequency_hz + 0.2);
}

}  // namespace
}  // namespace sb::bench

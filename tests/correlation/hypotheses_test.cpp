// Hidden effects diagnosed from the baseline config (docs/diagnosis.md): recordings made by a
// truth model with one catalogue physics on (nothing in their files names it), 2 % noise on
// every channel, at 1, 2 and 3 g; the diagnosis of the baseline ranks the hidden physics
// first, fits its value within 20 % on 1 and 2 g and predicts the held-out 3 g at least three
// times better than the baseline. A recording of the baseline itself shows no mismatch.
#include "correlation/hypotheses.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/describing_function.hpp"
#include "calibration_fixtures.hpp"
#include "core/text_file.hpp"
#include "core/units.hpp"
#include "correlation/diagnosis.hpp"
#include "tests/support/described_damper.hpp"
#include "tests/support/impact_damper.hpp"

namespace sb::correlation {
namespace {

using namespace testing;

/// The rigid bench at 1, 2 and 3 g, `count` frequencies over ±5 % of the mode; air drag,
/// when a truth or a candidate turns it on, on 8 strips (the prediction's cost grows with the
/// square of the points it balances; 8 strips give the linearised drag of 24 within 2 %, and
/// truth and candidates share them).
bench::CampaignConfig baseline(int count = 15, const std::string& levels = "[1.0, 2.0, 3.0]") {
    auto config = rigid_h0();
    config.physics.air_drag.stations = 8;
    bench::apply_overrides(
        config,
        {"campaign.levels_g=" + levels, "campaign.frequencies.count=" + std::to_string(count),
         "campaign.frequencies.low_ratio=0.95", "campaign.frequencies.high_ratio=1.05"});
    return config;
}

/// The recording of `truth`, predicted, with 2 % noise on every channel.
std::filesystem::path recording_of(const bench::CampaignConfig& truth, const std::string& name) {
    const auto dir = fresh_dir(name);
    write_noisy_recording(predict(truth, {}, 1), 0.02, 11, dir);
    return dir;
}

/// The diagnosis of `model` (the baseline by default) against the recording of `truth`.
DiagnosisResult diagnose_hidden(const bench::CampaignConfig& truth, const std::string& name,
                                int count = 15, std::optional<bench::CampaignConfig> model = {},
                                bool confirm = false) {
    DiagnosisOptions options;
    options.confirm = confirm;
    options.stated = kStated;
    options.calibration.simulate = predict;
    options.calibration.search.budget = 16;
    return diagnose(model ? *model : baseline(count), recording_of(truth, name), options);
}

/// `config` with its damper pd an impact damper whose damping falls with the level: 27 of its
/// spheres (2.98 g), as one plastic mass in an 8 mm gap (tests/support/impact_damper.hpp), a
/// describing-function table over 0.5-4 g and 5.5-7.5 Hz. Its loss -Im M is 1.6, 0.77 and
/// 0.47 g at 1, 2 and 3 g (the gap over the travel 0.92, 0.46, 0.31 at the mode): for the
/// beam, a damping ratio of about 1 %, 0.5 % and 0.3 % added to the rig's 0.5 %.
bench::CampaignConfig with_impact_damper(bench::CampaignConfig config, const std::string& name) {
    bench::apply_overrides(config, {"dampers.pd.particles.count=27"});
    // The shipped config's spheres: 3 mm of steel (7800 kg/m^3).
    const double kMass = 27.0 * 7800.0 * kPi / 6.0 * std::pow(0.003, 3);
    constexpr double kGap = 0.008;
    const auto file = sb::test::write_described_damper(
        fresh_dir(name + "-damper"), {0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 4.0}, {5.5, 6.0, 6.5, 7.0, 7.5},
        kMass, [&](double a, double f) {
            const double w = hz_to_rad_s(f);
            return sb::test::plastic_particle_apparent_mass(kMass, kGap * w * w / a);
        });
    bench::apply_overrides(config, {"dampers.pd.model=describing-function",
                                    "dampers.pd.characterization_file=\"" + file.string() + "\""});
    return config;
}

/// The hidden physics `name` ranked first by its signature (after, at most, rows of the same
/// signature: a sensor's mass and a clamp's compliance both lower the frequency alike at
/// every level) and first after the fits, the winner: `key` fitted within 20 % of `value`,
/// the misfit of the fitted and of the held-out levels down at least 3x.
void expect_found(const DiagnosisResult& d, const std::string& name,
                  const std::vector<std::pair<std::string, double>>& truth) {
    ASSERT_TRUE(d.mismatch) << d.verdict;
    ASSERT_TRUE(d.hypotheses.has_value()) << d.verdict;
    const auto& h = *d.hypotheses;
    std::cout << name << ": " << h.sentence << '\n';
    ASSERT_FALSE(h.ranking.empty());
    const auto hidden = std::find_if(h.ranking.begin(), h.ranking.end(),
                                     [&](const auto& r) { return r.entry->name == name; });
    ASSERT_NE(hidden, h.ranking.end());
    EXPECT_EQ(hidden->score, h.ranking.front().score) << h.ranking.front().reason;
    const auto same_signature = [](const CatalogueEntry& a, const CatalogueEntry& b) {
        return std::equal(a.signature.begin(), a.signature.end(), b.signature.begin(),
                          b.signature.end(), [](const auto& x, const auto& y) {
                              return x.feature == y.feature && x.shape == y.shape &&
                                     x.sign == y.sign;
                          });
    };
    for (auto r = h.ranking.begin(); r != hidden; ++r) {
        EXPECT_TRUE(same_signature(*r->entry, *hidden->entry)) << r->entry->name;
    }
    ASSERT_EQ(h.winner, 0) << h.sentence;
    const auto& w = h.fits.front();
    EXPECT_EQ(w.name(), name) << h.sentence;
    ASSERT_EQ(w.free.size(), truth.size());
    for (std::size_t k = 0; k < truth.size(); ++k) {
        EXPECT_EQ(w.free[k].path, truth[k].first);
        EXPECT_NEAR(w.values[k], truth[k].second, 0.2 * truth[k].second) << h.sentence;
    }
    ASSERT_EQ(h.held_out.size(), 1U);
    EXPECT_DOUBLE_EQ(h.held_out.front().second, d.measured.back().level_g);
    EXPECT_GE(w.baseline_fit, 3.0 * w.fit) << h.sentence;
    EXPECT_GE(w.baseline_held_out, 3.0 * w.held_out) << h.sentence;
    EXPECT_NE(d.verdict.find("the model left out"), std::string::npos) << d.verdict;
}

/// The columns of a plot data file's rows, block by block (blocks split by blank lines).
std::vector<std::vector<std::vector<double>>> read_blocks(const std::filesystem::path& file) {
    std::vector<std::vector<std::vector<double>>> blocks(1);
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty()) {
            if (!blocks.back().empty()) blocks.emplace_back();
            continue;
        }
        if (line.front() == '#') continue;
        std::istringstream fields(line);
        std::vector<double> row;
        std::string field;
        while (fields >> field) row.push_back(field == "nan" ? std::nan("") : std::stod(field));
        blocks.back().push_back(row);
    }
    if (blocks.back().empty()) blocks.pop_back();
    return blocks;
}

TEST(HiddenEffect, AirDragIsNamedFittedAndPredictsTheHeldOutLevel) {
    auto truth = baseline();
    truth.physics.air_drag.drag_coefficient = 20.0;
    const auto d = diagnose_hidden(truth, "hidden-drag");
    expect_found(d, "air-drag", {{"physics.air_drag.drag_coefficient", 20.0}});

    // The report's plots: per level the measured |H| with its uncertainty, the baseline and
    // the improved model; the improved one within the noise of the measured points, the
    // baseline not.
    const auto out = fresh_dir("hidden-drag-report");
    write_diagnosis(out, d, "test");
    const auto blocks = read_blocks(out / "plots" / "H-0-frf.dat");
    ASSERT_EQ(blocks.size(), 3U);
    for (const auto& block : blocks) {
        ASSERT_EQ(block.size(), 15U);
        double chi2_baseline = 0.0;
        double chi2_improved = 0.0;
        for (const auto& row : block) {
            ASSERT_EQ(row.size(), 5U);
            const double sigma = row[2] / row[1];  // relative: of ln|H|
            chi2_baseline += std::pow(std::log(row[3] / row[1]) / sigma, 2);
            chi2_improved += std::pow(std::log(row[4] / row[1]) / sigma, 2);
        }
        EXPECT_LT(chi2_improved, 3.0 * 15.0);
        EXPECT_GT(chi2_baseline, 3.0 * chi2_improved);
    }
    const auto levels = read_blocks(out / "plots" / "H-0-levels.dat");
    ASSERT_EQ(levels.size(), 1U);
    ASSERT_EQ(levels.front().size(), 3U);
    for (const auto& row : levels.front()) {
        ASSERT_EQ(row.size(), 9U);
        // Damping [%]: the improved model's within 3 sigma of the measured, the baseline's
        // below by more (the drag adds 0.2 to 0.7 %).
        EXPECT_NEAR(row[4], row[1], 3.0 * row[2]) << row[0] << " g";
        EXPECT_LT(row[3], row[1] - 3.0 * row[2]) << row[0] << " g";
    }
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
        EXPECT_TRUE(std::filesystem::exists(out / "diagnosis-H-0-frf.svg"));
        EXPECT_TRUE(std::filesystem::exists(out / "diagnosis-H-0-levels.svg"));
    }
    std::ifstream report(out / "report.md");
    const std::string text((std::istreambuf_iterator<char>(report)),
                           std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("diagnosis-H-0-frf.svg"), std::string::npos);
}

TEST(HiddenEffect, BackgroundDampingIsNamedFittedAndPredictsTheHeldOutLevel) {
    auto truth = baseline();
    truth.structure.damping.default_ratio = 0.008;
    expect_found(diagnose_hidden(truth, "hidden-background"), "background-damping",
                 {{"structure.damping.default_ratio", 0.008}});
}

TEST(HiddenEffect, ASensorMassIsNamedFittedAndPredictsTheHeldOutLevel) {
    auto truth = baseline();
    structure::LumpedMass sensor;
    sensor.name = "tip accelerometer";
    sensor.point = "damper";
    sensor.mass_kg = 0.003;  // the mode 1.6 % lower: clear, within the grid
    truth.structure.beam.masses.push_back(sensor);
    const auto d = diagnose_hidden(truth, "hidden-sensor");
    const std::string key = "structure.beam.masses[" +
                            std::to_string(baseline().structure.beam.masses.size()) + "].mass_kg";
    expect_found(d, "sensor-mass", {{key, 0.003}});
}

TEST(HiddenEffect, AClampsComplianceIsNamedFittedAndPredictsTheHeldOutLevel) {
    // The root turns against a spring of 100 EI/L (a bare cantilever's first mode 1.9 % lower)
    // instead of being clamped; about the stiff axis the clamp stays as good as rigid.
    auto truth = baseline();
    auto& beam = truth.structure.beam;
    const double ei_per_l = beam.youngs_modulus_pa * beam.width_m * std::pow(beam.thickness_m, 3) /
                            12.0 / beam.length_m;
    ASSERT_EQ(beam.supports.front().kind, structure::SupportKind::clamped);
    beam.supports.front().kind = structure::SupportKind::pinned;
    structure::Support spring;
    spring.name = beam.supports.front().name + "_rotational_spring";
    spring.kind = structure::SupportKind::elastic;
    spring.x_m = beam.supports.front().x_m;
    spring.rotational_stiffness_nm_per_rad = {0.0, 100.0 * ei_per_l, 1e9};
    beam.supports.push_back(spring);
    expect_found(diagnose_hidden(truth, "hidden-clamp"), "clamp-compliance",
                 {{"structure.beam.supports." + spring.name + ".rotational_stiffness_nm_per_rad[1]",
                   100.0 * ei_per_l}});
}

TEST(HiddenEffect, GeometricStiffeningIsNamedFittedAndPredictsTheHeldOutLevel) {
    // The mode 0.2, 0.8 and 1.7 % higher at 1, 2 and 3 g; 31 frequencies, so that the 0.5 %
    // peak that moves across the grid keeps enough points for the estimators at every level.
    auto truth = baseline(31);
    truth.physics.cubic_spring.point = "damper";
    truth.physics.cubic_spring.stiffness_n_per_m3 = 12000.0;
    expect_found(diagnose_hidden(truth, "hidden-stiffening", 31), "geometric-stiffening",
                 {{"physics.cubic_spring.stiffness_n_per_m3", 12000.0}});
}

TEST(HiddenEffect, MicroslipIsNamedFittedAndPredictsTheHeldOutLevel) {
    // A power-law dashpot at the tip, chi = 0.5: damping that grows like the square root of
    // the level. Over 1-3 g the rig's damping plus the drag mimic it within the noise; the
    // levels 0.5, 1 and 2 g fitted and 4 g held out tell them apart.
    const std::string levels = "[0.5, 1.0, 2.0, 4.0]";
    auto truth = baseline(15, levels);
    truth.physics.microslip.point = "damper";
    truth.physics.microslip.damping_n_s_per_m = 0.05;
    truth.physics.microslip.exponent = 0.5;
    expect_found(
        diagnose_hidden(truth, "hidden-microslip", 15, baseline(15, levels)), "joint-microslip",
        {{"physics.microslip.damping_n_s_per_m", 0.05}, {"physics.microslip.exponent", 0.5}});
}

TEST(HiddenEffect, AnIwanJointIsNamedFittedAndPredictsTheHeldOutLevel) {
    // A joint at the tip, stuck stiffness 10 N/m, sliding as a whole beyond 10 mm, chi = -0.5
    // (the row's held exponent): at 0.5 and 1 g (3 and 6 mm of tip motion) it slips over more
    // of its contact at each level, damping more and softening the mode; at 2 g and at 4 g,
    // held out, it slides whole.
    const std::string levels = "[0.5, 1.0, 2.0, 4.0]";
    auto truth = baseline(15, levels);
    truth.physics.iwan_joint.point = "damper";
    truth.physics.iwan_joint.stiffness_n_per_m = 10.0;
    truth.physics.iwan_joint.macroslip_displacement_m = 0.01;
    const DiagnosisResult d =
        diagnose_hidden(truth, "hidden-iwan", 15, baseline(15, levels), /*confirm=*/true);
    expect_found(d, "iwan-joint",
                 {{"physics.iwan_joint.stiffness_n_per_m", 10.0},
                  {"physics.iwan_joint.macroslip_displacement_m", 0.01}});
    // Fitted on the prediction, the winner is simulated again by the coupled campaign, its
    // sliders stepped: the misfits fall there as they did on the prediction.
    ASSERT_TRUE(d.hypotheses && d.hypotheses->confirmation);
    const Confirmation& c = *d.hypotheses->confirmation;
    std::cout << c.sentence << '\n';
    EXPECT_TRUE(c.error.empty()) << c.error;
    EXPECT_TRUE(c.confirmed) << c.sentence;
    const CandidateFit& w = d.hypotheses->fits.front();
    EXPECT_LT(c.fit, c.baseline_fit / 3.0) << c.sentence;
    EXPECT_LT(c.held_out, c.baseline_held_out / 3.0) << c.sentence;
    EXPECT_LT(c.fit, 2.0 * w.fit) << c.sentence << "; predicted " << w.fit;
}

TEST(HiddenEffect, AVoltageDrivenShakerIsNamedFittedAndPredictsTheHeldOutLevel) {
    // The rig records the amplifier's voltage as its reference, not a force: a shaker of
    // force factor 12 N/A and coil resistance 4 ohm (1 mH) turns it into force and its
    // back-EMF damps the FRF (about 36 N s/m at the drive point). The model drives a force:
    // only the shaker's row can turn newtons into volts, and its fit finds both values.
    auto truth = baseline();
    truth.physics.shaker.force_factor_n_per_a = 12.0;
    truth.physics.shaker.coil_resistance_ohm = 4.0;
    truth.physics.shaker.coil_inductance_h = 1e-3;
    const DiagnosisResult d = diagnose_hidden(truth, "hidden-shaker");
    expect_found(d, "electrodynamic-shaker",
                 {{"physics.shaker.force_factor_n_per_a", 12.0},
                  {"physics.shaker.coil_resistance_ohm", 4.0}});
}

TEST(HiddenEffect, AirDragConcealedByALowerBackgroundIsFoundAsThePair) {
    // The rig damps less than the config says (0.35 % against 0.5 %) and the air drags
    // (C_D = 20): at 1 g the two nearly cancel, the residual grows like neither alone. A
    // power of the level (the microslip row, two values) fits it within the noise too; the
    // pair, as complex, fits it better.
    auto truth = baseline();
    truth.structure.damping.default_ratio = 0.0035;
    truth.physics.air_drag.drag_coefficient = 20.0;
    const auto d = diagnose_hidden(truth, "hidden-pair");
    ASSERT_TRUE(d.hypotheses.has_value()) << d.verdict;
    const auto& h = *d.hypotheses;
    std::cout << "pair: " << h.sentence << '\n';
    for (const auto& f : h.fits) {
        std::cout << "  " << f.name() << ": BIC " << f.bic << ", held out " << f.held_out << '\n';
    }
    EXPECT_TRUE(h.pairs_tried);
    ASSERT_EQ(h.winner, 0) << h.sentence;
    const auto& w = h.fits.front();
    ASSERT_EQ(w.entries.size(), 2U) << h.sentence;
    EXPECT_NE(w.name().find("air-drag"), std::string::npos) << h.sentence;
    EXPECT_NE(w.name().find("background-damping"), std::string::npos) << h.sentence;
    for (std::size_t k = 0; k < w.free.size(); ++k) {
        const double truth_value =
            w.free[k].path == "physics.air_drag.drag_coefficient" ? 20.0 : 0.0035;
        EXPECT_NEAR(w.values[k], truth_value, 0.2 * truth_value) << w.free[k].path;
    }
    EXPECT_GE(w.baseline_held_out, 3.0 * w.held_out) << h.sentence;
}

TEST(HiddenEffect, AirDragConcealedByAParticleDamperIsFoundUnderIt) {
    // The particle damper's damping falls with the level, the drag's (C_D = 20) grows: the
    // measured damping hardly moves from 2 to 3 g where the damper alone would fall. The
    // model holds the damper, so the residual is the drag's.
    const auto model = with_impact_damper(baseline(), "hidden-drag-under-pd");
    auto truth = model;
    truth.physics.air_drag.drag_coefficient = 20.0;
    const auto d = diagnose_hidden(truth, "hidden-drag-under-pd", 15, model);
    ASSERT_EQ(d.measured.size(), 3U);
    ASSERT_EQ(d.simulated.size(), 3U);
    const auto zeta = [](const LevelFeatureValues& v) {
        return v.value[static_cast<std::size_t>(LevelFeature::damping_ratio)];
    };
    for (std::size_t k = 0; k < 3; ++k) {
        std::cout << d.measured[k].level_g << " g: damping " << zeta(d.measured[k]) << " measured, "
                  << zeta(d.simulated[k]) << " the model\n";
    }
    // The model's damping falls by more than a third from 1 to 3 g; the measured by less
    // than half as much.
    const double model_fall = 1.0 - zeta(d.simulated[2]) / zeta(d.simulated[0]);
    const double measured_fall = 1.0 - zeta(d.measured[2]) / zeta(d.measured[0]);
    EXPECT_GT(model_fall, 0.35);
    EXPECT_LT(measured_fall, 0.5 * model_fall);
    expect_found(d, "air-drag", {{"physics.air_drag.drag_coefficient", 20.0}});
}

TEST(Confirmation, TheFullModelSimulatesADescribedDamperAsItsDemBed) {
    const auto described = with_impact_damper(baseline(), "full-model");
    std::vector<std::string> switched;
    const auto full = full_model(described, &switched);
    EXPECT_EQ(switched, std::vector<std::string>{"pd"});
    const auto& damper = full.campaign.dampers.front();
    EXPECT_EQ(damper.model, bench::DamperSpec::Model::dem);
    EXPECT_EQ(damper.particles.count, 27);  // the bed its table stands for
    // A rigid damper is simulated as it is.
    std::vector<std::string> none;
    EXPECT_EQ(full_model(baseline(), &none).campaign.dampers.front().model,
              bench::DamperSpec::Model::rigid);
    EXPECT_TRUE(none.empty());
}

TEST(HiddenEffect, TheBaselinesOwnRecordingShowsNoMismatchAndFitsNothing) {
    const auto d = diagnose_hidden(baseline(), "hidden-none");
    EXPECT_FALSE(d.mismatch) << d.verdict;
    EXPECT_EQ(d.verdict, "no significant mismatch");
    EXPECT_FALSE(d.hypotheses.has_value());
}

}  // namespace
}  // namespace sb::correlation

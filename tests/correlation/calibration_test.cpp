// Calibration on the fast prediction of a linear bench (the particles a rigid mass): values
// known, noise known, so the recovered values and what the report calls identifiable can be
// checked exactly.
#include "correlation/calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "calibration_fixtures.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "correlation/two_fidelity.hpp"

namespace sb::correlation {
namespace {

namespace fs = std::filesystem;
using namespace testing;

void expect_recovered(const CalibrationResult& r, const Truth& truth) {
    ASSERT_EQ(r.findings.size(), 3U) << r.findings_note;
    const auto& zeta = finding(r, "structure.damping.default_ratio");
    const auto& modulus = finding(r, "structure.beam.youngs_modulus_pa");
    const auto& rolling = finding(r, "dampers.pd.contact.rolling_friction");
    // 2 % noise on 18 points: the damping to a few per cent, the modulus (through the
    // frequency, f ∝ sqrt(E)) far better.
    EXPECT_TRUE(zeta.identifiable) << zeta.reason;
    EXPECT_NEAR(zeta.value, truth.damping_ratio, 0.05 * truth.damping_ratio);
    EXPECT_LE(zeta.lo95, truth.damping_ratio) << zeta.reason << ", value " << zeta.value;
    EXPECT_GE(zeta.hi95, truth.damping_ratio) << zeta.reason << ", value " << zeta.value;
    EXPECT_TRUE(modulus.identifiable) << modulus.reason;
    EXPECT_NEAR(modulus.value, truth.modulus_pa, 0.005 * truth.modulus_pa);
    // A rigid bed has no rolling friction: nothing in the data depends on it.
    EXPECT_FALSE(rolling.identifiable) << rolling.reason << "; modulus " << modulus.reason;
    EXPECT_GT(rolling.hi95 - rolling.lo95, 0.5 * 0.05);
    for (double share : rolling.information_share) EXPECT_LT(share, 1e-6);
    EXPECT_LT(r.best.misfit, 0.25 * r.start.misfit);
}

TEST(Calibration,
     DirectSearchRecoversTheDampingAndModulusOfALinearBenchAndFlagsAKeyWithoutInfluence) {
    const Truth truth;
    const auto measured = read_measurement(measured_linear_bench("direct", truth), kStated);
    EXPECT_EQ(measured.depth, "points.csv");
    const auto config = rigid_h0();
    CalibrationOptions options;
    options.simulate = predict;
    options.search.mode = SearchMode::direct;
    options.search.budget = 60;
    const auto result = calibrate(config, measured, linear_free(config), options);
    expect_recovered(result, truth);
    // The search within its budget, then a stencil around the emulator's minimum (both sides
    // of each value, one side at the end of an interval) and the simulation that confirms it.
    EXPECT_LE(result.outcome.evaluations, 60);
    const int after_search = static_cast<int>(result.history.size()) - result.outcome.evaluations;
    EXPECT_GE(after_search, 3 + 1);
    EXPECT_LE(after_search, 2 * 3 + 1);
}

TEST(Calibration, TheSurrogateFindsTheSameInFewerSimulations) {
    const Truth truth;
    const auto measured = read_measurement(measured_linear_bench("surrogate", truth), kStated);
    const auto config = rigid_h0();
    CalibrationOptions options;
    options.simulate = predict;
    options.search.mode = SearchMode::surrogate;
    options.search.budget = 30;
    const auto surrogate = calibrate(config, measured, linear_free(config), options);
    expect_recovered(surrogate, truth);
    options.search.mode = SearchMode::direct;
    options.search.budget = 60;
    const auto direct = calibrate(config, measured, linear_free(config), options);
    EXPECT_LT(surrogate.simulations, direct.simulations);
}

TEST(Calibration, WhenTheAnswerSimulatedFitsWorseThanTheStartNoValueIsCalledIdentifiable) {
    // A simulation exact at the config's damping (the truth) and scattered by 20 % anywhere
    // else, as a DEM campaign with too few fillings scatters: the emulator's optimum cannot
    // hold when simulated, and its narrow interval must not be reported as what the data say.
    Truth truth;
    truth.modulus_pa = 72e9;  // the config's
    const auto measured = read_measurement(measured_linear_bench("unconfirmed", truth), kStated);
    auto config = rigid_h0();
    bench::apply_overrides(config, {"structure.damping.default_ratio=0.008"});
    CalibrationOptions options;
    options.simulate = [](const bench::CampaignConfig& c, const bench::Selection& selection,
                          int threads) {
        auto result = predict(c, selection, threads);
        const double damping = c.structure.damping.default_ratio;
        if (damping == 0.008) return result;
        std::mt19937_64 generator(std::hash<double>{}(damping));
        std::normal_distribution<double> normal(0.0, 0.2);
        for (auto& point : result.recording.points) {
            for (std::size_t k = 1; k < point.values.size(); ++k) {
                point.values[k].amplitude *= 1.0 + normal(generator);
            }
        }
        return result;
    };
    options.search.mode = SearchMode::surrogate;
    options.search.budget = 8;
    const auto r = calibrate(
        config, measured,
        parse_free_parameters(config, {"structure.damping.default_ratio=0.002:0.02"}), options);
    ASSERT_GT(r.best.misfit, r.start.misfit);
    ASSERT_EQ(r.findings.size(), 1U) << r.findings_note;
    EXPECT_FALSE(r.findings.front().identifiable) << r.findings.front().reason;
    EXPECT_NE(r.findings.front().reason.find("fit worse than the start"), std::string::npos)
        << r.findings.front().reason;
    EXPECT_EQ(r.warnings.size(), 1U);
}

TEST(Calibration, TwoFidelityCorrectsABiasedCheapModelWithAFewFullSimulations) {
    const Truth truth;
    const auto measured = read_measurement(measured_linear_bench("two-fidelity", truth), kStated);
    const auto config = rigid_h0();
    const auto free = parse_free_parameters(config, {"structure.damping.default_ratio=0.002:0.02",
                                                     "structure.beam.youngs_modulus_pa=60e9:80e9"});
    // The cheap model is wrong the way a describing function can be: more damping (0.15 % of
    // critical) and a stiffer structure (2 %) than the full simulation at the same values.
    const Simulation biased = [](const bench::CampaignConfig& c, const bench::Selection& s,
                                 int threads) {
        auto changed = c;
        changed.structure.damping.default_ratio += 0.0015;
        changed.structure.beam.youngs_modulus_pa *= 1.02;
        return predict(changed, s, threads);
    };
    CalibrationOptions options;
    options.simulate = predict;
    options.low_fidelity_simulate = biased;
    options.fidelity = Fidelity::two_fidelity;
    options.search.mode = SearchMode::surrogate;
    options.search.budget = 30;
    const auto two = calibrate(config, measured, free, options);
    ASSERT_EQ(two.findings.size(), 2U) << two.findings_note;
    const auto& zeta = finding(two, "structure.damping.default_ratio");
    const auto& modulus = finding(two, "structure.beam.youngs_modulus_pa");
    EXPECT_NEAR(zeta.value, truth.damping_ratio, 0.05 * truth.damping_ratio)
        << two.corrections_stopped;
    EXPECT_NEAR(modulus.value, truth.modulus_pa, 0.005 * truth.modulus_pa)
        << two.corrections_stopped;
    EXPECT_TRUE(zeta.identifiable) << zeta.reason;
    EXPECT_TRUE(modulus.identifiable) << modulus.reason;
    // The full simulation: the start, one stencil of five, a few corrections and the
    // confirmation; the coupled surrogate search takes some 30.
    EXPECT_LE(two.simulations, 1 + 5 + (kTwoFidelityCorrections - 1) + 1);
    EXPECT_GE(two.low_fidelity_simulations, 10);
    EXPECT_LT(two.best.misfit, 0.25 * two.start.misfit);

    // The cheap model alone, uncorrected, misses by about its bias.
    options.fidelity = Fidelity::coupled;
    options.simulate = biased;
    const auto cheap = calibrate(config, measured, free, options);
    EXPECT_GT(
        std::abs(finding(cheap, "structure.damping.default_ratio").value - truth.damping_ratio),
        0.1 * truth.damping_ratio);
    EXPECT_GT(std::abs(finding(cheap, "structure.beam.youngs_modulus_pa").value - truth.modulus_pa),
              0.01 * truth.modulus_pa);
}

TEST(Calibration, AnInterruptedOrRepeatedCalibrationTakesEveryEvaluationFromItsCache) {
    const Truth truth;
    const auto measured = read_measurement(measured_linear_bench("cache", truth));
    const auto config = rigid_h0();
    const auto cache = fresh_dir("cache-store");
    CalibrationOptions options;
    options.simulate = predict;
    options.cache_dir = cache;
    options.search.budget = 12;
    const auto first = calibrate(config, measured, linear_free(config), options);
    EXPECT_GT(first.simulations, 0);
    EXPECT_LE(first.simulations, 12 + 2 * 3 + 1);
    const auto again = calibrate(config, measured, linear_free(config), options);
    EXPECT_EQ(again.simulations, 0);
    EXPECT_EQ(again.best.values, first.best.values);
    EXPECT_EQ(again.best.misfit, first.best.misfit);
    // A cache file cut short is simulated again, not half believed.
    for (const auto& entry : fs::directory_iterator(cache)) {
        fs::resize_file(entry.path(), fs::file_size(entry.path()) / 2);
        break;
    }
    const auto cut = calibrate(config, measured, linear_free(config), options);
    EXPECT_EQ(cut.simulations, 1);
    EXPECT_EQ(cut.best.values, first.best.values);
}

TEST(Calibration, TheReportAndTheCalibratedConfigAreWritten) {
    const Truth truth;
    const auto measured = read_measurement(measured_linear_bench("report", truth), kStated);
    const auto config = rigid_h0();
    CalibrationOptions options;
    options.simulate = predict;
    options.search.budget = 40;
    const auto result = calibrate(config, measured, linear_free(config), options);
    const auto out = fresh_dir("report-out");
    write_calibration(out, result, measured, "shakerbench calibrate test");
    for (const char* name : {"calibration.toml", "report.md", "calibrated.toml", "evaluations.csv",
                             "plots/calibration-damping.dat", "plots/calibration.gp"}) {
        EXPECT_TRUE(fs::exists(out / name)) << name;
    }
    // The calibrated config loads and holds the calibrated values.
    const auto calibrated = bench::load_campaign_config(out / "calibrated.toml");
    EXPECT_EQ(std::get<double>(bench::get_value(calibrated, "structure.damping.default_ratio")),
              result.best.values[0]);
    const std::string toml = read_text_file(out / "calibration.toml");
    EXPECT_NE(toml.find("identifiable = false"), std::string::npos);
}

TEST(Calibration, ADemDamperWithOneFillingPerLevelIsRefusedBeforeAnySimulation) {
    auto config = bench::load_campaign_config(std::string(SB_SOURCE_DIR) +
                                              "/tests/bench/golden/small-h0.toml");
    Measurement m;
    m.features.push_back(Feature{"H-0", 1.0, FeatureKind::damping_ratio, 0.0, 0.02, 0.001});
    m.selection.sweeps.push_back({"H-0", 1.0, {}});
    CalibrationOptions options;
    options.simulate = [](const bench::CampaignConfig&, const bench::Selection&,
                          int) -> bench::CampaignResult {
        ADD_FAILURE() << "simulated";
        return {};
    };
    try {
        calibrate(config, m, default_free_parameters(config), options);
        ADD_FAILURE() << "no error";
    } catch (const config::ConfigException& e) {
        EXPECT_NE(std::string(e.what()).find("campaign.seeds = 1: must be at least 2"),
                  std::string::npos)
            << e.what();
    }
}

TEST(Measurement, ADampingCsvAloneGivesFrequencyAndDampingPerLevelOnTheConfigsGrid) {
    const auto dir = fresh_dir("damping-only");
    fs::create_directories(dir);
    identification::DampingRow row;
    row.arrangement = "H-0";
    row.level_g = 1.0;
    row.natural_frequency_hz = 6.5;
    row.damping_ratio = 0.02;
    row.method = "half-power";
    identification::write_damping_csv(dir / "damping.csv", {row});
    const auto m = read_measurement(dir, {0.1, 0.01, 0.05});
    EXPECT_EQ(m.depth, "damping.csv");
    ASSERT_EQ(m.features.size(), 2U);
    EXPECT_EQ(m.features[0].kind, FeatureKind::natural_frequency);
    EXPECT_DOUBLE_EQ(m.features[0].sigma, 0.01 * 6.5);
    EXPECT_DOUBLE_EQ(m.features[1].sigma, 0.1 * 0.02);
    ASSERT_EQ(m.selection.sweeps.size(), 1U);
    EXPECT_TRUE(m.selection.sweeps[0].frequencies_hz.empty());
    EXPECT_THROW(read_measurement(fresh_dir("nothing-there")), std::invalid_argument);
}

TEST(Measurement, RepeatsScatteringMoreThanTheStatedUncertaintyGiveTheirs) {
    const auto dir = fresh_dir("repeats");
    fs::create_directories(dir);
    identification::DampingRow row;
    row.arrangement = "H-0";
    row.level_g = 1.0;
    row.natural_frequency_hz = 6.5;
    row.damping_ratio = 0.02;
    row.method = "circle-fit";
    row.fillings = 4;
    row.damping_ratio_std = 0.004;        // over sqrt(4): 0.002, above 5 % of 0.02
    row.natural_frequency_std_hz = 0.01;  // over sqrt(4): 0.005, below 0.2 % of 6.5 Hz
    identification::write_damping_csv(dir / "damping.csv", {row});
    const auto m = read_measurement(dir);
    ASSERT_EQ(m.features.size(), 2U);
    EXPECT_TRUE(m.features[1].sigma_from_repeats);
    EXPECT_DOUBLE_EQ(m.features[1].sigma, 0.004 / 2.0);
    EXPECT_DOUBLE_EQ(m.features[0].sigma, 0.002 * 6.5);
}

}  // namespace
}  // namespace sb::correlation

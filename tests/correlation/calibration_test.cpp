// Calibration on the fast prediction of a linear bench (the particles a rigid mass): values
// known, noise known, so the recovered values and what the report calls identifiable can be
// checked exactly.
#include "correlation/calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "calibration_fixtures.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"

namespace sb::correlation {
namespace {

namespace fs = std::filesystem;
using testing::fresh_dir;
using testing::predict;

bench::CampaignConfig rigid_h0() {
    auto config =
        bench::load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    bench::apply_overrides(config, {"dampers.pd.model=rigid", "campaign.levels_g=[1.0, 2.0]"});
    return config;
}

struct Truth {
    double damping_ratio = 0.008;
    double modulus_pa = 69.0e9;
};

/// The rigid bench with the true values, predicted, 2 % noise on every channel.
fs::path measured_linear_bench(const std::string& name, const Truth& truth) {
    auto config = rigid_h0();
    bench::apply_overrides(config,
                           {"structure.damping.default_ratio=" + exact_text(truth.damping_ratio),
                            "structure.beam.youngs_modulus_pa=" + exact_text(truth.modulus_pa)});
    const auto dir = fresh_dir(name);
    testing::write_noisy_recording(predict(config, {}, 1), 0.02, 7, dir);
    return dir;
}

std::vector<FreeParameter> linear_free(const bench::CampaignConfig& config) {
    return parse_free_parameters(config, {"structure.damping.default_ratio=0.002:0.02",
                                          "structure.beam.youngs_modulus_pa=60e9:80e9",
                                          "dampers.pd.contact.rolling_friction"});
}

const ParameterFinding& finding(const CalibrationResult& r, const std::string& path) {
    for (const auto& f : r.findings) {
        if (f.parameter.path == path) return f;
    }
    throw std::runtime_error("no finding for " + path);
}

void expect_recovered(const CalibrationResult& r, const Truth& truth) {
    ASSERT_EQ(r.findings.size(), 3U) << r.findings_note;
    const auto& zeta = finding(r, "structure.damping.default_ratio");
    const auto& modulus = finding(r, "structure.beam.youngs_modulus_pa");
    const auto& rolling = finding(r, "dampers.pd.contact.rolling_friction");
    // 2 % noise on 18 points: the damping to a few per cent, the modulus (through the
    // frequency, f ∝ sqrt(E)) far better.
    EXPECT_TRUE(zeta.identifiable) << zeta.reason;
    EXPECT_NEAR(zeta.value, truth.damping_ratio, 0.05 * truth.damping_ratio);
    EXPECT_LE(zeta.lo95, truth.damping_ratio);
    EXPECT_GE(zeta.hi95, truth.damping_ratio);
    EXPECT_TRUE(modulus.identifiable) << modulus.reason;
    EXPECT_NEAR(modulus.value, truth.modulus_pa, 0.005 * truth.modulus_pa);
    // A rigid bed has no rolling friction: nothing in the data depends on it.
    EXPECT_FALSE(rolling.identifiable) << rolling.reason;
    EXPECT_GT(rolling.hi95 - rolling.lo95, 0.5 * 0.05);
    for (double share : rolling.information_share) EXPECT_LT(share, 1e-6);
    EXPECT_LT(r.best.misfit, 0.25 * r.start.misfit);
}

TEST(Calibration,
     DirectSearchRecoversTheDampingAndModulusOfALinearBenchAndFlagsAKeyWithoutInfluence) {
    const Truth truth;
    const auto measured =
        read_measurement(measured_linear_bench("direct", truth), {0.02, 0.002, 0.02});
    EXPECT_EQ(measured.depth, "points.csv");
    const auto config = rigid_h0();
    CalibrationOptions options;
    options.simulate = predict;
    options.search.mode = SearchMode::direct;
    options.search.budget = 60;
    const auto result = calibrate(config, measured, linear_free(config), options);
    expect_recovered(result, truth);
    EXPECT_EQ(result.outcome.evaluations, static_cast<int>(result.history.size()));
    EXPECT_LE(result.outcome.evaluations, 60);
}

TEST(Calibration, TheSurrogateFindsTheSameInFewerSimulations) {
    const Truth truth;
    const auto measured =
        read_measurement(measured_linear_bench("surrogate", truth), {0.02, 0.002, 0.02});
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
    EXPECT_EQ(first.simulations, 12);
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
    const auto measured =
        read_measurement(measured_linear_bench("report", truth), {0.02, 0.002, 0.02});
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

TEST(Measurement, RepeatsGiveTheUncertaintyInsteadOfTheStatedOne) {
    const auto dir = fresh_dir("repeats");
    fs::create_directories(dir);
    identification::DampingRow row;
    row.arrangement = "H-0";
    row.level_g = 1.0;
    row.natural_frequency_hz = 6.5;
    row.damping_ratio = 0.02;
    row.method = "circle-fit";
    row.fillings = 4;
    row.damping_ratio_std = 0.002;
    row.natural_frequency_std_hz = 0.02;
    identification::write_damping_csv(dir / "damping.csv", {row});
    const auto m = read_measurement(dir);
    ASSERT_EQ(m.features.size(), 2U);
    EXPECT_TRUE(m.features[1].sigma_from_repeats);
    EXPECT_DOUBLE_EQ(m.features[1].sigma, 0.002 / 2.0);
    EXPECT_DOUBLE_EQ(m.features[0].sigma, 0.02 / 2.0);
}

}  // namespace
}  // namespace sb::correlation

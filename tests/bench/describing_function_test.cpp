// characterization.csv and the describing function's interpolation.
#include "bench/describing_function.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "bench/attachment.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "core/units.hpp"
#include "identification/file_error.hpp"

namespace sb::bench {
namespace {

namespace fs = std::filesystem;
using Complex = std::complex<double>;

/// A made-up apparent mass linear in log |a| and in f, so that the interpolation must give it
/// back exactly between the grid points (a monotone cubic reproduces straight lines).
Complex linear_mass(double a, double f) {
    return {0.01 + 0.002 * std::log(a) + 1e-4 * f, -0.003 - 0.001 * std::log(a) + 2e-4 * f};
}

CharacterizationTable grid_table(const std::vector<double>& levels_g,
                                 const std::vector<double>& frequencies_hz) {
    CharacterizationTable t;
    t.config = "made-up.toml";
    t.config_hash = "0123456789abcdef";
    t.damper_hashes = {{"pd", "fedcba9876543210"}};
    for (double level : levels_g) {
        for (double f : frequencies_hz) {
            CharacterizationRow r;
            r.damper = "pd";
            r.arrangement = "H-0";
            r.level_g = level;
            r.acceleration_m_s2 = std::sqrt(2.0) * g_to_m_s2(level);
            r.frequency_hz = f;
            r.bed_mass_kg = 0.0132;
            r.rotation_per_translation_rad_m = {0.0, -2.68, 0.0};
            r.seeds = 3;
            r.apparent_mass_kg = linear_mass(r.acceleration_m_s2, f);
            r.apparent_mass_re_std_kg = 1e-4;
            r.power_w = 0.01 * level;
            r.h2_ratio = 0.01;
            r.h3_ratio = 0.2 + 0.01 * level;
            r.kinetic_j = 1e-4;
            r.periods = 20;
            t.rows.push_back(r);
        }
    }
    return t;
}

fs::path temp_file(const std::string& name, const std::string& text) {
    const auto path =
        fs::temp_directory_path() / ("shakerbench-df-" + std::to_string(::getpid()) + "-" + name);
    std::ofstream(path) << text;
    return path;
}

/// The FileError reading `text` gives, as "line:column: message" (empty when it reads).
std::string read_error(const std::string& text) {
    const auto path = temp_file("bad.csv", text);
    try {
        read_characterization_csv(path);
    } catch (const identification::FileError& e) {
        return std::to_string(e.line()) + ":" + std::to_string(e.column()) + ": " + e.message();
    }
    return "";
}

TEST(DescribingFunction, TheFileReadsBackToTheSameTable) {
    const auto table = grid_table({0.5, 1.0, 3.0}, {6.0, 6.5});
    const auto path = temp_file("round.csv", characterization_csv_text(table));
    const auto back = read_characterization_csv(path);
    EXPECT_EQ(characterization_csv_text(back), characterization_csv_text(table));
    EXPECT_EQ(back.config_hash, "0123456789abcdef");
    ASSERT_EQ(back.damper_hashes.size(), 1u);
    EXPECT_EQ(back.damper_hashes.front().second, "fedcba9876543210");
    EXPECT_EQ(back.rows.size(), 6u);
}

TEST(DescribingFunction, InterpolationGivesBackAFunctionLinearInLogAmplitudeAndFrequency) {
    const auto table = grid_table({0.5, 1.0, 2.0, 5.0}, {5.8, 6.1, 6.5, 7.0});
    const DescribingFunction df = describing_function_for(table, "t.csv", "pd", "H-0");
    for (double level : {0.5, 0.7, 1.3, 2.0, 4.1, 5.0}) {
        for (double f : {5.8, 5.95, 6.3, 6.9, 7.0}) {
            const double a = std::sqrt(2.0) * g_to_m_s2(level);
            const auto v = df.evaluate(a, f);
            EXPECT_NEAR(v.apparent_mass_kg.real(), linear_mass(a, f).real(), 1e-12);
            EXPECT_NEAR(v.apparent_mass_kg.imag(), linear_mass(a, f).imag(), 1e-12);
            EXPECT_TRUE(v.inside);
            EXPECT_TRUE(v.settled);
        }
    }
    EXPECT_NEAR(df.bed_mass_kg(), 0.0132, 1e-15);
    EXPECT_EQ(df.rotation_per_translation_rad_m(), Eigen::Vector3d(0.0, -2.68, 0.0));
}

TEST(DescribingFunction, OutsideTheGridTheEdgeValueIsHeldAndFlagged) {
    const auto table = grid_table({1.0, 2.0}, {6.0, 6.5});
    const DescribingFunction df = describing_function_for(table, "t.csv", "pd", "H-0");
    const double top = std::sqrt(2.0) * g_to_m_s2(2.0);
    const auto above = df.evaluate(2.0 * top, 6.5);
    EXPECT_FALSE(above.inside);
    EXPECT_NEAR(above.apparent_mass_kg.real(), linear_mass(top, 6.5).real(), 1e-15);
    EXPECT_FALSE(df.evaluate(top, 7.0).inside);
    EXPECT_TRUE(df.evaluate(top, 6.5).inside);
}

TEST(DescribingFunction, AnUnsettledGridPointMarksTheCellsAroundIt) {
    auto table = grid_table({1.0, 2.0, 3.0}, {6.0, 6.5});
    table.rows[5].settled = false;  // 3 g, 6.5 Hz
    const DescribingFunction df = describing_function_for(table, "t.csv", "pd", "H-0");
    const auto a = [](double g) { return std::sqrt(2.0) * g_to_m_s2(g); };
    EXPECT_FALSE(df.evaluate(a(2.5), 6.2).settled);
    EXPECT_TRUE(df.evaluate(a(1.5), 6.2).settled);
}

TEST(DescribingFunction, MonotoneCubicNeitherOvershootsNorMissesTheData) {
    const std::vector<double> x{0.0, 1.0, 2.0, 3.0};
    const std::vector<double> y{0.0, 0.0, 1.0, 1.0};  // a step: a plain cubic spline overshoots
    for (double at = 0.0; at <= 3.0; at += 0.01) {
        const double v = monotone_cubic(x, y, at);
        EXPECT_GE(v, 0.0) << at;
        EXPECT_LE(v, 1.0) << at;
    }
    for (std::size_t k = 0; k < x.size(); ++k) EXPECT_EQ(monotone_cubic(x, y, x[k]), y[k]);
}

TEST(DescribingFunction, ABadFileIsReportedAtItsLineAndColumn) {
    const std::string good = characterization_csv_text(grid_table({1.0, 2.0}, {6.0, 6.5}));
    // Lines are counted from 1; the first data row follows the comment lines and the header.
    const auto row_start = [&](int line) {
        std::size_t at = 0;
        for (int k = 1; k < line; ++k) at = good.find('\n', at) + 1;
        return at;
    };
    int first_row = 1;
    while (good.compare(row_start(first_row), 3, "pd,") != 0) ++first_row;
    const std::string line = std::to_string(first_row);
    const auto r0 = row_start(first_row);
    std::string bad_number = good;
    const auto c = bad_number.find(",1,", r0);  // level_g of the first row
    bad_number.replace(c + 1, 1, "x");
    EXPECT_EQ(read_error(bad_number),
              line + ":" + std::to_string(c + 2 - r0) + ": column 'level_g': 'x' is not a number");

    std::string missing = good;
    missing.erase(row_start(first_row + 1), row_start(first_row + 2) - row_start(first_row + 1));
    EXPECT_NE(read_error(missing).find("do not form a grid"), std::string::npos)
        << read_error(missing);

    std::string not_ours = good;
    not_ours.replace(0, good.find('\n'), "# some other file");
    EXPECT_EQ(read_error(not_ours).rfind("1:1: not a characterisation file", 0), 0u);

    std::string negative_std = good;
    const auto std_at = negative_std.find(",0.0001,", r0);
    negative_std.replace(std_at + 1, 6, "-1e-4");
    EXPECT_EQ(read_error(negative_std).rfind(line + ":", 0), 0u);
    EXPECT_NE(read_error(negative_std).find("must be >= 0"), std::string::npos);
}

TEST(DescribingFunction, TheAttachmentsLoadIsTheApparentMassTimesTheMotion) {
    // M constant: the attachment must return F = M' w^2 (u - u0) + w M'' v for a harmonic
    // motion, at the end of the step, after its first period has measured the amplitude.
    auto table = grid_table({1.0, 2.0}, {6.0, 6.5});
    for (auto& r : table.rows) r.apparent_mass_kg = {0.012, -0.004};
    auto df = std::make_shared<const DescribingFunction>(
        describing_function_for(table, "t.csv", "pd", "H-0"));
    const Eigen::Vector3d rest(0.5, 0.0, 0.0);
    DescribingFunctionDamper damper(df, Eigen::Vector3d::UnitZ(), rest, PointLoad{});
    const double f = 6.2;
    const double w = hz_to_rad_s(f);
    const int n = 400;
    const double dt = 1.0 / (f * n);
    const double x = 1.3 * g_to_m_s2(1.0) / (w * w);
    damper.set_frequency(f);
    for (int k = 0; k < 2 * n; ++k) {
        const double t = k * dt;
        PointMotion m;
        m.position_m = rest + Eigen::Vector3d(0.0, 0.0, 1e-3 + x * std::sin(w * t));
        m.velocity_m_s = Eigen::Vector3d(0.0, 0.0, x * w * std::cos(w * t));
        const PointLoad load = damper.step(m, dt);
        if (k < n) continue;
        // The load at the end of the step, as the coupled specimen applies it.
        const double end = t + dt;
        const double expected =
            0.012 * w * w * x * std::sin(w * end) + w * (-0.004) * x * w * std::cos(w * end);
        ASSERT_NEAR(load.force_n.z(), expected, 1e-9 * 0.012 * w * w * x) << k;
    }
    EXPECT_NEAR(damper.acceleration_m_s2(), x * w * w, 1e-9 * x * w * w);
}

TEST(DescribingFunction, ItsStateGoesThroughACheckpointExactly) {
    SweepCheckpoint c;
    c.config_hash = "0123456789abcdef";
    c.state.q = Eigen::VectorXd::Constant(2, 1e-3);
    c.state.q_dot = Eigen::VectorXd::Constant(2, -2e-2);
    AttachmentState a;
    a.describing = DescribingState{13.868697431446114, -8.1e-4 / 3.0};
    c.state.attachments.push_back(a);
    c.state.loads.push_back(Eigen::Matrix<double, 6, 1>::Constant(0.1 / 3.0));
    const SweepCheckpoint back = parse_checkpoint(serialize_checkpoint(c), "t.txt");
    ASSERT_EQ(back.state.attachments.size(), 1u);
    ASSERT_TRUE(back.state.attachments[0].describing.has_value());
    EXPECT_FALSE(back.state.attachments[0].dem.has_value());
    EXPECT_EQ(back.state.attachments[0].describing->acceleration_m_s2, 13.868697431446114);
    EXPECT_EQ(back.state.attachments[0].describing->mean_displacement_m, -8.1e-4 / 3.0);
    EXPECT_EQ(serialize_checkpoint(back), serialize_checkpoint(c));
}

}  // namespace
}  // namespace sb::bench

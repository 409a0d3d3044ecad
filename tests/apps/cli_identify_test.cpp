// shakerbench identify: recording directories and UFF files, options, and the error exits.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_helpers.hpp"
#include "core/units.hpp"
#include "identification/recording_io.hpp"
#include "identification/uff58.hpp"

namespace {

using namespace sb::test;
namespace fs = std::filesystem;
namespace id = sb::identification;

/// Exact data through CSV/UFF text with 17 digits: every method within 2 % (the bound).
constexpr double kDampingTolerance = 0.02;

/// Accelerance of an SDOF (modal mass 1/a kg) on 31 points around its resonance.
id::Frf sdof(double fn_hz, double zeta, double a = 1.0) {
    id::Frf frf{{}, {}, id::FrfForm::accelerance};
    for (int i = 0; i < 31; ++i) {
        const double f = fn_hz * (1.0 + zeta * (-4.0 + 8.0 * (i + 0.3) / 30.0));
        const double w = sb::hz_to_rad_s(f), wn = sb::hz_to_rad_s(fn_hz);
        frf.frequency_hz.push_back(f);
        frf.value.push_back(-w * w * a /
                            std::complex<double>(wn * wn - w * w, 2.0 * zeta * wn * w));
    }
    return frf;
}

/// Grid indices of sdof() either side of f_n: f_n(1 + ζ(−4 + 8(i + 0.3)/30)) = f_n at i = 14.7.
constexpr std::size_t kNearResonance[] = {14, 15};

/// A recording directory: force reference, acceleration control, two levels of an SDOF. With
/// `closest`, the two points nearest the resonance at 1 g did not hold their level: response
/// 30 % low, status closest.
fs::path write_recording(const std::string& name, bool base = false, bool closest = false) {
    const auto dir = temp_dir(name);
    id::Recording rec;
    rec.info.name = name;
    rec.info.excitation = base ? "base" : "force";
    rec.channels = {
        {"force", base ? "acceleration" : "force", "N", "shaker", id::ChannelRole::reference},
        {"acc", "acceleration", "m/s^2", "damper", id::ChannelRole::control}};
    for (const auto& [level, zeta] : {std::pair{0.5, 0.02}, std::pair{1.0, 0.04}}) {
        const auto frf = sdof(6.4, zeta);
        for (std::size_t i = 0; i < frf.value.size(); ++i) {
            const std::complex<double> force(1.5, 0.5);
            const bool bad =
                closest && level == 1.0 && (i == kNearResonance[0] || i == kNearResonance[1]);
            rec.points.push_back({"H-0",
                                  level,
                                  frf.frequency_hz[i],
                                  bad ? "closest" : "converged",
                                  "",
                                  {{1.0, force}, {1.0, frf.value[i] * force * (bad ? 0.7 : 1.0)}}});
        }
    }
    id::write_recording(dir, rec);
    return dir;
}

/// damping_ratio column of every row of a damping.csv.
std::vector<double> damping_ratios(const fs::path& csv) {
    std::vector<double> out;
    for (const auto& row : id::read_damping_csv(csv)) out.push_back(row.damping_ratio);
    return out;
}

/// The output names a file position: `<file>:<line>:<column>: ` (digits; no std::regex,
/// which trips g++ 12's maybe-uninitialized warning under the sanitizers).
bool has_location(const std::string& output, const std::string& file) {
    const auto digits = [&](std::size_t& i) {
        const std::size_t b = i;
        while (i < output.size() && output[i] >= '0' && output[i] <= '9') ++i;
        return i > b;
    };
    for (auto at = output.find(file + ":"); at != std::string::npos;
         at = output.find(file + ":", at + 1)) {
        std::size_t i = at + file.size() + 1;
        if (!digits(i) || i >= output.size() || output[i++] != ':' || !digits(i)) continue;
        if (output.compare(i, 2, ": ") == 0) return true;
    }
    return false;
}

TEST(CliIdentify, WritesIntoDirIdentifiedByDefaultAndPrintsTheLossFactor) {
    const auto dir = write_recording("identify-default");
    const auto r = run("identify " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("eta [-]"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("0.040000"), std::string::npos) << r.output;  // η = 2ζ at 0.5 g
    const auto ratios = damping_ratios(dir / "identified" / "damping.csv");
    ASSERT_EQ(ratios.size(), 4u);  // 2 levels × half-power, circle-fit
    EXPECT_NEAR(ratios[0] / 0.02, 1.0, kDampingTolerance);
    EXPECT_NEAR(ratios[3] / 0.04, 1.0, kDampingTolerance);
    EXPECT_TRUE(fs::exists(dir / "identified" / "plots" / "plots.gp"));
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
        EXPECT_TRUE(fs::exists(dir / "identified" / "H-0-frf.svg")) << r.output;
        EXPECT_TRUE(fs::exists(dir / "identified" / "H-0-damping.svg")) << r.output;
    }
}

TEST(CliIdentify, LeavesClosestPointsOutByDefaultSaysSoAndWritesWhichPointsWereUsed) {
    const auto dir = write_recording("identify-closest", false, true);
    const auto r = run("identify " + dir.string() + " --no-plots");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto grid = sdof(6.4, 0.04).frequency_hz;
    const double f1 = grid[kNearResonance[0]], f2 = grid[kNearResonance[1]];
    char line[160];
    std::snprintf(line, sizeof line,
                  "H-0 1 g: 2 points with status closest left out of the fits (%.6g, %.6g Hz)", f1,
                  f2);
    EXPECT_NE(r.output.find(line), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("H-0 0.5 g: "), std::string::npos) << r.output;  // nothing left out
    const auto csv = dir / "identified" / "damping.csv";
    EXPECT_EQ(file_text(csv).substr(0, file_text(csv).find('\n')),
              "arrangement,level_g,natural_frequency_hz,damping_ratio,method,points_used,"
              "frequencies_used_hz,points_skipped,fillings,natural_frequency_std_hz,"
              "damping_ratio_std");
    const auto rows = id::read_damping_csv(csv);
    ASSERT_EQ(rows.size(), 4u);  // 2 levels × half-power, circle-fit
    for (const auto& row : rows) {
        EXPECT_EQ(row.points_skipped, row.level_g == 1.0 ? 2 : 0);
        EXPECT_EQ(row.frequencies_used_hz.size(), static_cast<std::size_t>(row.points_used));
        EXPECT_GE(row.points_used, 3);
        for (double f : row.frequencies_used_hz) {
            if (row.level_g == 1.0) {
                EXPECT_NE(f, f1);
                EXPECT_NE(f, f2);
            }
        }
        // The rest is exact SDOF data: every method within the bound.
        EXPECT_NEAR(row.damping_ratio / (row.level_g == 1.0 ? 0.04 : 0.02), 1.0, kDampingTolerance);
    }
}

TEST(CliIdentify, ClosestUseKeepsThePointsFlagsThemAndChangesTheResult) {
    const auto dir = write_recording("identify-closest-use", false, true);
    const auto skip =
        run("identify " + dir.string() + " --no-plots --out " + (dir / "skip").string());
    const auto use = run("identify " + dir.string() + " --no-plots --closest use --out " +
                         (dir / "use").string());
    ASSERT_EQ(skip.exit_code, 0) << skip.output;
    ASSERT_EQ(use.exit_code, 0) << use.output;
    EXPECT_NE(use.output.find("H-0 1 g: 2 points with status closest kept in the fits"),
              std::string::npos)
        << use.output;
    EXPECT_EQ(use.output.find("left out"), std::string::npos) << use.output;
    const auto kept = id::read_damping_csv(dir / "use" / "damping.csv");
    const auto left_out = id::read_damping_csv(dir / "skip" / "damping.csv");
    // The 30 % dip at the peak moves (or removes) the 1 g estimates; 0.5 g is unchanged.
    int changed = 0;
    for (const auto& a : left_out) {
        bool found = false;
        for (const auto& b : kept) {
            if (b.level_g != a.level_g || b.method != a.method) continue;
            found = true;
            EXPECT_EQ(b.points_skipped, 0);
            if (a.level_g == 0.5) {
                EXPECT_EQ(b.damping_ratio, a.damping_ratio);
            }
            if (a.level_g == 1.0 && std::abs(b.damping_ratio / a.damping_ratio - 1.0) > 0.01)
                ++changed;
        }
        if (!found && a.level_g == 1.0) ++changed;
    }
    EXPECT_EQ(changed, 2) << use.output;
}

TEST(CliIdentify, AnUnknownClosestPolicyExitsTwo) {
    const auto dir = write_recording("identify-closest-maybe", false, true);
    const auto r = run("identify " + dir.string() + " --closest maybe");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--closest"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "identified" / "damping.csv"));
}

TEST(CliIdentify, RefusesToWriteIntoTheRecordingItself) {
    // A recording that is only a damping.csv: --out DIR would overwrite it.
    const auto dir = temp_dir("identify-only-damping");
    std::ofstream(dir / "recording.toml")
        << "[recording]\nname = \"paper\"\n[channels.force]\nquantity = \"force\"\n"
           "role = \"reference\"\n";
    const std::string damping =
        "arrangement,level_g,natural_frequency_hz,damping_ratio,method\nH-0,0.5,6.3,0.05,"
        "half-power\n";
    std::ofstream(dir / "damping.csv") << damping;
    auto r = run("identify " + dir.string() + " --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("would overwrite its input"), std::string::npos) << r.output;
    EXPECT_EQ(file_text(dir / "damping.csv"), damping);
    r = run("identify " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("only damping.csv"), std::string::npos) << r.output;
    EXPECT_EQ(file_text(dir / "damping.csv"), damping);
}

TEST(CliIdentify, AppliesBackgroundAndMassToAUffFile) {
    const auto dir = temp_dir("identify-uff");
    const auto file = dir / "frf.uff";
    auto a = id::to_uff58(sdof(20.0, 0.03, 0.5), "low level");
    a.response_name = "acc";
    auto b = id::to_uff58(sdof(20.0, 0.05, 0.5), "high level");
    b.response_name = "acc";
    id::write_uff58(file, {a, b});
    const auto r = run("identify " + file.string() + " --background 0.01 --mass 2");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto ratios = damping_ratios(dir / "frf-identified" / "damping.csv");
    ASSERT_EQ(ratios.size(), 4u);
    EXPECT_NEAR(ratios[0] / 0.02, 1.0, kDampingTolerance);  // 0.03 − 0.01
    EXPECT_NEAR(ratios[2] / 0.04, 1.0, kDampingTolerance);  // 0.05 − 0.01
    // W/T at the peak: 4πζ f_n/f − 4πζ_bg, about 4π(0.03 − 0.01) = 0.25.
    EXPECT_NE(r.output.find("W/T = 0.2"), std::string::npos) << r.output;
}

TEST(CliIdentify, SelectsUffRecordsByResponseNameAndRejectsAnUnknownOne) {
    const auto dir = temp_dir("identify-uff-channel");
    const auto file = dir / "frf.uff";
    auto a = id::to_uff58(sdof(20.0, 0.03), "point 1");
    a.response_name = "acc1";
    auto b = id::to_uff58(sdof(30.0, 0.05), "point 2");
    b.response_name = "acc2";
    id::write_uff58(file, {a, b});
    auto r = run("identify " + file.string() + " --channel acc2 --out " + (dir / "o").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto ratios = damping_ratios(dir / "o" / "damping.csv");
    ASSERT_EQ(ratios.size(), 2u);
    EXPECT_NEAR(ratios[0] / 0.05, 1.0, kDampingTolerance);
    r = run("identify " + file.string() + " --channel acc9");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--channel 'acc9'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("found: acc1, acc2"), std::string::npos) << r.output;
}

TEST(CliIdentify, RejectsMassForATransmissibilityRecord) {
    const auto dir = temp_dir("identify-uff-mass");
    auto a = id::to_uff58(sdof(20.0, 0.03), "transmissibility");
    a.function_type = 5;
    a.denominator = {12, 1, 0, 0, "Acceleration", "m/s^2"};
    id::write_uff58(dir / "t.uff", {a});
    const auto r = run("identify " + (dir / "t.uff").string() + " --mass 1");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--mass"), std::string::npos) << r.output;
}

TEST(CliIdentify, RejectsMassForBaseExcitationAndAnUnknownChannel) {
    const auto base = write_recording("identify-base", true);
    auto r = run("identify " + base.string() + " --mass 1");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--mass needs force excitation"), std::string::npos) << r.output;
    const auto dir = write_recording("identify-channel");
    r = run("identify " + dir.string() + " --channel acc9");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("no channel 'acc9' in recording.toml (channels: force, acc)"),
              std::string::npos)
        << r.output;
    r = run("identify " + dir.string() + " --channel force");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("is the reference"), std::string::npos) << r.output;
}

/// Replaces the first occurrence of `from` in a file.
void edit(const fs::path& file, const std::string& from, const std::string& to) {
    std::string text = file_text(file);
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    std::ofstream(file, std::ios::binary) << text;
}

TEST(CliIdentify, EveryBadRecordingExitsTwoWithFileLineAndColumn) {
    struct Case {
        const char* name;
        const char* file;
        const char* from;
        const char* to;
        const char* message;
    };
    const Case cases[] = {
        {"missing-column", "points.csv", "", "", "missing column 'acc_im'"},
        {"non-numeric", "points.csv", "converged,,1,", "converged,,abc,", "'abc' is not a number"},
        {"nan", "points.csv", "converged,,1,", "converged,,nan,", "is not a finite number"},
        {"unknown-column", "points.csv", "", "", "unknown column 'acc9_rms'"},
        {"two-references", "recording.toml", "role = \"control\"", "role = \"reference\"",
         "two reference channels: 'force' and 'acc'"},
        {"unknown-key", "recording.toml", "unit = \"N\"", "units = \"N\"",
         "unknown key 'channels.force.units'"},
    };
    for (const auto& c : cases) {
        const auto dir = write_recording(std::string("identify-bad-") + c.name);
        const std::string name = c.name;
        if (name == "missing-column" || name == "unknown-column") {
            // Every row loses its last cell or gains one, so that only the header is wrong.
            std::string text = file_text(dir / "points.csv");
            std::string out;
            std::size_t b = 0;
            for (int line_no = 1; b < text.size(); ++line_no) {
                const auto e = text.find('\n', b);
                const std::string line = text.substr(b, e - b);
                if (name == "missing-column") {
                    out += line.substr(0, line.rfind(',')) + "\n";
                } else {
                    out += line + (line_no == 1 ? ",acc9_rms" : ",0") + "\n";
                }
                b = e + 1;
            }
            std::ofstream(dir / "points.csv", std::ios::binary) << out;
        } else {
            edit(dir / c.file, c.from, c.to);
        }
        const auto r = run("identify " + dir.string());
        EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.output;
        EXPECT_TRUE(has_location(r.output, c.file)) << c.name << ": " << r.output;
        EXPECT_NE(r.output.find(c.message), std::string::npos) << c.name << ": " << r.output;
        EXPECT_FALSE(fs::exists(dir / "identified" / "damping.csv")) << c.name;
    }
}

}  // namespace

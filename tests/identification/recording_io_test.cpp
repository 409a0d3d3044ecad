// Recording directory: round trip and the documented errors with file, line and column.
#include "identification/recording_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/units.hpp"
#include "identification/file_error.hpp"

namespace sb::identification {
namespace {

namespace fs = std::filesystem;

const char* const kToml =
    "[recording]\n"
    "name = \"beam-h0\"\n"
    "kind = \"measured\"\n"
    "excitation = \"force\"\n"
    "description = \"free text\"\n"
    "\n"
    "[channels.force]\n"
    "quantity = \"force\"\n"
    "unit = \"N\"\n"
    "location = \"shaker\"\n"
    "role = \"reference\"\n"
    "\n"
    "[channels.acc_damper]\n"
    "quantity = \"acceleration\"\n"
    "unit = \"m/s^2\"\n"
    "location = \"damper\"\n"
    "role = \"control\"\n";

const char* const kHeader =
    "arrangement,level_g,frequency_hz,status,series,force_rms,force_re,force_im,acc_damper_rms,"
    "acc_damper_re,acc_damper_im\n";

fs::path make_dir(const std::string& name, const std::string& toml, const std::string& points) {
    const auto dir = fs::temp_directory_path() / "sb_identification_recording_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "recording.toml") << toml;
    std::ofstream(dir / "points.csv") << points;
    return dir;
}

FileError expect_error(const fs::path& dir) {
    try {
        read_recording(dir);
    } catch (const FileError& e) {
        return e;
    }
    ADD_FAILURE() << "no FileError for " << dir;
    return FileError("", 0, 0, "");
}

/// A series of `periods` periods of f at `per_period` samples per period: force cos, acc sin.
void write_series(const fs::path& file, double f, int periods, int per_period,
                  const std::string& header = "time_s,force,acc_damper") {
    fs::create_directories(file.parent_path());
    std::ofstream out(file);
    out.precision(17);
    out << header << '\n';
    const int n = periods * per_period;
    for (int k = 0; k < n; ++k) {
        const double t = (k + 1) / (f * per_period);
        out << t << ',' << 2.0 * std::cos(kTwoPi * f * t) << ',' << -3.0 * std::sin(kTwoPi * f * t)
            << '\n';
    }
}

TEST(RecordingIo, ReadsTheFormatsExampleAndRoundTripsExactly) {
    const auto dir = make_dir("good", kToml,
                              std::string(kHeader) +
                                  "H-0,0.5,6.3,converged,,1.2,1.5,0.1,4.9,0.3,6.9\n"
                                  "H-0,0.5,6.4,closest,series/p2.csv,1.1,1.4,0.2,4.8,0.2,6.7\n");
    write_series(dir / "series" / "p2.csv", 6.4, 3, 32);
    auto rec = read_recording(dir);
    ASSERT_EQ(rec.channels.size(), 2u);
    EXPECT_EQ(rec.channels[0].name, "force");
    EXPECT_EQ(rec.channels[1].role, ChannelRole::control);
    EXPECT_EQ(rec.reference_index(), 0u);
    ASSERT_EQ(rec.points.size(), 2u);
    EXPECT_EQ(rec.points[1].series, "series/p2.csv");
    EXPECT_EQ(rec.points[1].values[1].amplitude, std::complex<double>(0.2, 6.7));
    rec.points[0].values[0].amplitude = {1.0 / 3.0, -2.0 / 7.0};
    rec.damping.push_back({"H-0", 0.5, 6.35, 0.0123456789012345, "half-power"});
    const auto out = dir.parent_path() / "good-out";
    write_recording(out, rec);
    const auto back = read_recording(out);
    EXPECT_EQ(back.points[0].values[0].amplitude, rec.points[0].values[0].amplitude);
    EXPECT_EQ(back.damping[0].damping_ratio, rec.damping[0].damping_ratio);
    EXPECT_EQ(back.info.description, "free text");
    EXPECT_EQ(back.points[1].history.columns, rec.points[1].history.columns);
}

TEST(RecordingIo, LoadsSeriesAndComputesMissingAmplitudesOverWholePeriods) {
    // acc_damper's cells are empty: rms and fundamental come from the series. With t_k =
    // (k+1)/(f N), x = -3 sin(ωt) has amplitude 3i (x = Re{X e^{iωt}}).
    const auto dir = make_dir("fromseries", kToml,
                              std::string(kHeader) +
                                  "H-0,0.5,6.4,converged,series/a.csv,1.2,"
                                  "1.5,0.1,,,\n");
    write_series(dir / "series" / "a.csv", 6.4, 4, 25);
    const auto rec = read_recording(dir);
    ASSERT_EQ(rec.points.size(), 1u);
    const auto& v = rec.points[0].values[1];
    EXPECT_TRUE(v.from_series);
    EXPECT_FALSE(rec.points[0].values[0].from_series);
    EXPECT_NEAR(std::abs(v.amplitude - std::complex<double>(0.0, 3.0)), 0.0, 1e-12);
    EXPECT_NEAR(v.rms, 3.0 / std::sqrt(2.0), 1e-12);
    ASSERT_EQ(rec.points[0].history.time_s.size(), 100u);
}

TEST(RecordingIo, SeriesErrorsNameTheFileAndTheCell) {
    // Unknown channel column in the series: at its header cell.
    auto dir = make_dir("series-channel", kToml,
                        std::string(kHeader) + "H-0,0.5,6.4,converged,series/a.csv,1,1,0,1,1,1\n");
    write_series(dir / "series" / "a.csv", 6.4, 2, 25, "time_s,force,acc9");
    auto e = expect_error(dir);
    EXPECT_NE(std::string(e.what()).find("a.csv:1:14: unknown channel 'acc9'"), std::string::npos)
        << e.what();
    // Not whole periods.
    dir = make_dir("series-periods", kToml,
                   std::string(kHeader) + "H-0,0.5,6.5,converged,series/a.csv,1,1,0,1,1,1\n");
    write_series(dir / "series" / "a.csv", 6.4, 2, 25);
    e = expect_error(dir);
    EXPECT_NE(e.message().find("a series must hold whole periods"), std::string::npos) << e.what();
    // Missing file: at the points.csv cell.
    dir = make_dir("series-missing", kToml,
                   std::string(kHeader) + "H-0,0.5,6.4,converged,series/b.csv,1,1,0,1,1,1\n");
    e = expect_error(dir);
    EXPECT_NE(std::string(e.what()).find("points.csv:2:23: series file 'series/b.csv' not found"),
              std::string::npos)
        << e.what();
    // Empty cells without a series.
    dir =
        make_dir("series-none", kToml, std::string(kHeader) + "H-0,0.5,6.4,converged,,1,1,0,,,\n");
    e = expect_error(dir);
    EXPECT_NE(e.message().find("are empty and the row has no series"), std::string::npos)
        << e.what();
}

TEST(RecordingIo, ASeriesOutsideTheRecordingDirectoryIsRefusedAtItsCell) {
    // A series of the right shape one folder up: only the path is wrong.
    const auto up = fs::temp_directory_path() / "sb_identification_recording_test" / "up.csv";
    write_series(up, 6.4, 2, 25);
    for (const std::string& series :
         {std::string("../up.csv"), up.string(), std::string("series/../../up.csv")}) {
        const auto dir =
            make_dir("series-outside", kToml,
                     std::string(kHeader) + "H-0,0.5,6.4,converged," + series + ",1,1,0,1,1,1\n");
        const auto e = expect_error(dir);
        EXPECT_NE(std::string(e.what()).find("points.csv:2:23: series file '" + series +
                                             "' must be a relative path inside the recording "
                                             "directory"),
                  std::string::npos)
            << e.what();
    }
}

TEST(RecordingIo, ASeriesThatCannotHoldTheRowsFrequencyIsRefused) {
    // 32 samples at 1 per period of 6.4 Hz are whole periods, but hold nothing of 6.4 Hz: its
    // fundamental would read as zero.
    const auto dir =
        make_dir("series-nyquist", kToml,
                 std::string(kHeader) + "H-0,0.5,6.4,converged,series/a.csv,1,1,0,,,\n");
    write_series(dir / "series" / "a.csv", 6.4, 32, 1);
    const auto e = expect_error(dir);
    EXPECT_NE(e.message().find("a series needs more than two samples per period"),
              std::string::npos)
        << e.what();
    EXPECT_EQ(fs::path(e.file()).filename(), "a.csv");
}

TEST(RecordingIo, ATimeAxisThatDoesNotIncreaseIsAnErrorAtItsLastCell) {
    const auto p = fs::temp_directory_path() / "sb_identification_recording_test" / "back.csv";
    fs::create_directories(p.parent_path());
    std::ofstream(p) << "time_s,force\n0.3,1\n0.2,1\n0.1,1\n";
    try {
        (void)read_time_history_csv(p);
        FAIL() << "read";
    } catch (const FileError& e) {
        EXPECT_EQ(e.line(), 4);
        EXPECT_NE(e.message().find("time_s must increase"), std::string::npos) << e.what();
    }
    std::ofstream(p) << "time_s,force\n1,1\n1,1\n1,1\n";
    EXPECT_THROW((void)read_time_history_csv(p), FileError);
}

TEST(RecordingIo, MissingColumnNamesTheColumnAndTheChannelAtTheHeaderLine) {
    // Two comment lines and a blank line precede the header: the error is on line 4.
    const auto dir =
        make_dir("missing", kToml,
                 "# exported by hand\n# second comment\n\n"
                 "arrangement,level_g,frequency_hz,status,series,force_rms,force_re,force_im,"
                 "acc_damper_rms,acc_damper_re\nH-0,0.5,6.3,converged,,1,1,0,1,1\n");
    const auto e = expect_error(dir);
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.column(), 0);
    EXPECT_NE(e.message().find("missing column 'acc_damper_im' for channel 'acc_damper'"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("points.csv:4:0: "), std::string::npos) << e.what();
}

TEST(RecordingIo, NanAndInfinityCellsAreNotNumbers) {
    for (const char* bad : {"nan", "inf", "-Infinity", "NaN"}) {
        const auto dir = make_dir(
            "nan", kToml,
            std::string(kHeader) + "H-0,0.5,6.3,converged,,1.2," + bad + ",0.1,4.9,0.3,6.9\n");
        const auto e = expect_error(dir);
        EXPECT_EQ(e.line(), 2) << bad;
        EXPECT_EQ(e.column(), 28) << bad;
        EXPECT_NE(e.message().find("is not a finite number"), std::string::npos) << e.what();
    }
}

TEST(RecordingIo, NonNumericCellGivesLineAndColumn) {
    const auto dir = make_dir("nonnumeric", kToml,
                              std::string(kHeader) +
                                  "H-0,0.5,6.3,converged,,1.2,1.5,0.1,4.9,0.3,6.9\n"
                                  "H-0,0.5,6.4,converged,,1.2,abc,0.1,4.9,0.3,6.9\n");
    const auto e = expect_error(dir);
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.column(), 28);  // the cell "abc" starts at character 28
    EXPECT_NE(e.message().find("column 'force_re': 'abc' is not a number"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("points.csv:3:28: "), std::string::npos) << e.what();
}

TEST(RecordingIo, UnknownChannelColumnIsAnError) {
    const auto dir = make_dir(
        "unknown", kToml,
        std::string("arrangement,level_g,frequency_hz,status,series,force_rms,force_re,force_im,"
                    "acc_damper_rms,acc_damper_re,acc_damper_im,acc9_rms\n") +
            "H-0,0.5,6.3,converged,,1,1,0,1,1,1,2\n");
    const auto e = expect_error(dir);
    EXPECT_EQ(e.line(), 1);
    EXPECT_EQ(e.column(), 119);
    EXPECT_NE(e.message().find("unknown column 'acc9_rms'"), std::string::npos) << e.what();
}

TEST(RecordingIo, TwoReferenceChannelsAreAnErrorAtTheSecondOne) {
    const std::string toml = std::string(kToml) +
                             "\n[channels.force2]\nquantity = \"force\"\nunit = \"N\"\nlocation = "
                             "\"x\"\nrole = \"reference\"\n";
    const auto dir = make_dir("tworef", toml, kHeader);
    const auto e = expect_error(dir);
    EXPECT_EQ(e.line(), 19);
    EXPECT_EQ(e.column(), 11);  // the second channel's name in [channels.force2]
    EXPECT_NE(e.message().find("two reference channels: 'force' and 'force2'"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("recording.toml:19:11: "), std::string::npos) << e.what();
}

TEST(RecordingIo, NoReferenceChannelAndTwoControlChannelsAreErrors) {
    std::string none = kToml;
    none.replace(none.find("role = \"reference\""), 18, "role = \"response\"");
    EXPECT_NE(expect_error(make_dir("noref", none, kHeader)).message().find("no channel has role"),
              std::string::npos);
    const std::string two =
        std::string(kToml) + "\n[channels.acc2]\nquantity = \"acceleration\"\nrole = \"control\"\n";
    const auto e = expect_error(make_dir("twocontrol", two, kHeader));
    EXPECT_EQ(e.line(), 19);
    EXPECT_NE(e.message().find("two control channels: 'acc_damper' and 'acc2'"), std::string::npos)
        << e.what();
}

TEST(RecordingIo, UnknownKeyInRecordingTomlIsAnError) {
    std::string toml = kToml;
    toml.replace(toml.find("unit = \"N\""), 10, "units = \"N\"");
    const auto e = expect_error(make_dir("unknownkey", toml, kHeader));
    EXPECT_EQ(e.line(), 9);
    EXPECT_NE(e.message().find("unknown key 'channels.force.units'"), std::string::npos)
        << e.what();
}

/// The first line of a file.
std::string first_line(const fs::path& file) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    return line;
}

/// Two channels, two points; acc_damper knows its harmonics (one of them not at row 0).
Recording harmonic_recording() {
    Recording rec;
    rec.info.name = "harmonics";
    rec.channels = {{"force", "force", "N", "shaker", ChannelRole::reference},
                    {"acc_damper", "acceleration", "m/s^2", "damper", ChannelRole::control}};
    for (int i = 0; i < 2; ++i) {
        PointRow p{"H-0",       0.5, 6.3 + 0.1 * i,
                   "converged", "",  {{1.0, {2.0, 0.5}}, {3.0, {0.1, 4.0}}}};
        p.values[1].h2_ratio = i == 0 ? 1.0 / 3.0 : 0.1;
        p.values[1].h3_ratio = i == 0 ? std::numeric_limits<double>::quiet_NaN() : 2.0 / 7.0;
        rec.points.push_back(p);
    }
    return rec;
}

TEST(RecordingIo, HarmonicRatiosRoundTripExactlyInColumnsAfterEveryChannelsValues) {
    const auto dir = fs::temp_directory_path() / "sb_identification_recording_test" / "harmonics";
    fs::remove_all(dir);
    const Recording rec = harmonic_recording();
    write_recording(dir, rec);
    // force has no ratio at any row: no columns for it; acc_damper's pair after all values.
    EXPECT_EQ(first_line(dir / "points.csv"),
              "arrangement,level_g,frequency_hz,status,series,force_rms,force_re,force_im,"
              "acc_damper_rms,acc_damper_re,acc_damper_im,acc_damper_h2,acc_damper_h3");
    const auto back = read_recording(dir);
    ASSERT_EQ(back.points.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(back.points[i].values[1].h2_ratio, rec.points[i].values[1].h2_ratio) << i;
        EXPECT_TRUE(std::isnan(back.points[i].values[0].h2_ratio)) << i;
        EXPECT_TRUE(std::isnan(back.points[i].values[0].h3_ratio)) << i;
    }
    EXPECT_TRUE(std::isnan(back.points[0].values[1].h3_ratio));
    EXPECT_EQ(back.points[1].values[1].h3_ratio, 2.0 / 7.0);
}

TEST(RecordingIo, TheFillingOfEachPointRoundTripsAndIsOptionalOnRead) {
    const auto dir = fs::temp_directory_path() / "sb_identification_recording_test" / "fillings";
    fs::remove_all(dir);
    Recording rec = harmonic_recording();
    rec.points[1].filling = 3;
    write_recording(dir, rec);
    EXPECT_EQ(first_line(dir / "points.csv")
                  .rfind("arrangement,level_g,frequency_hz,status,series,filling,force_rms", 0),
              0u);
    const auto back = read_recording(dir);
    EXPECT_EQ(back.points[0].filling, 0);
    EXPECT_EQ(back.points[1].filling, 3);
    // A recording of one filling writes no such column, and one without it reads as filling 0.
    const auto plain = fs::temp_directory_path() / "sb_identification_recording_test" / "one";
    fs::remove_all(plain);
    write_recording(plain, harmonic_recording());
    EXPECT_EQ(first_line(plain / "points.csv").find("filling"), std::string::npos);
    EXPECT_EQ(read_recording(plain).points[1].filling, 0);
    // A filling that is not a whole number >= 0 is an error at its cell.
    std::string header = kHeader;
    header.insert(header.find(",force_rms"), ",filling");
    try {
        read_recording(make_dir("bad-filling", kToml,
                                header + "H-0,0.5,6.3,converged,,-1,1.2,1.5,0.1,4.9,0.3,6.9\n"));
        FAIL() << "a negative filling was accepted";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("filling '-1' must be a whole number >= 0"),
                  std::string::npos)
            << e.what();
    }
}

TEST(RecordingIo, HarmonicColumnsAreOptionalOnReadButComeAsAPair) {
    // Without the columns (another tool's file): not known.
    auto rec = read_recording(
        make_dir("no-harmonics", kToml,
                 std::string(kHeader) + "H-0,0.5,6.3,converged,,1.2,1.5,0.1,4.9,0.3,6.9\n"));
    EXPECT_TRUE(std::isnan(rec.points[0].values[1].h2_ratio));
    EXPECT_TRUE(std::isnan(rec.points[0].values[1].h3_ratio));
    // Present, one cell empty: that one is not known.
    std::string header = kHeader;
    header.insert(header.size() - 1, ",acc_damper_h2,acc_damper_h3");
    rec =
        read_recording(make_dir("empty-harmonic", kToml,
                                header + "H-0,0.5,6.3,converged,,1.2,1.5,0.1,4.9,0.3,6.9,,0.02\n"));
    EXPECT_TRUE(std::isnan(rec.points[0].values[1].h2_ratio));
    EXPECT_EQ(rec.points[0].values[1].h3_ratio, 0.02);
    // Only one of the pair: an error at the header line naming the missing one.
    header = kHeader;
    header.insert(header.size() - 1, ",acc_damper_h2");
    const auto e = expect_error(make_dir(
        "half-pair", kToml, header + "H-0,0.5,6.3,converged,,1.2,1.5,0.1,4.9,0.3,6.9,0.1\n"));
    EXPECT_EQ(e.line(), 1);
    EXPECT_NE(e.message().find("missing column 'acc_damper_h3'"), std::string::npos) << e.what();
}

TEST(RecordingIo, ABadHarmonicCellIsReportedAtFileLineAndColumn) {
    std::string header = kHeader;
    header.insert(header.size() - 1, ",acc_damper_h2,acc_damper_h3");
    for (const std::string bad : {"abc", "nan", "-0.1"}) {
        const std::string row = "H-0,0.5,6.3,converged,,1.2,1.5,0.1,4.9,0.3,6.9,0.1," + bad + "\n";
        const auto e = expect_error(make_dir("bad-harmonic", kToml, header + row));
        EXPECT_EQ(e.line(), 2) << bad;
        EXPECT_EQ(e.column(), static_cast<int>(row.rfind(',')) + 2) << bad;
        EXPECT_NE(e.message().find("column 'acc_damper_h3': '" + bad + "'"), std::string::npos)
            << e.what();
    }
}

TEST(RecordingIo, HarmonicRatiosComeFromTheSeriesWithTheFundamentalWhenItsCellsAreEmpty) {
    // acc_damper = 3 sin ωt + 0.3 cos(2ωt + 1) + 0.15 sin(3ωt): H2/H1 = 0.1, H3/H1 = 0.05.
    // force's cells are given, its harmonic cells too (a number in the file is kept).
    const double f = 6.4;
    const int per_period = 32, periods = 4;
    const auto dir = make_dir("harmonics-from-series", kToml, "");
    std::string header = kHeader;
    header.insert(header.size() - 1, ",force_h2,force_h3,acc_damper_h2,acc_damper_h3");
    std::ofstream(dir / "points.csv")
        << header << "H-0,0.5,6.4,converged,series/a.csv,1.2,1.5,0.1,,,,0.5,,,\n";
    fs::create_directories(dir / "series");
    std::ofstream out(dir / "series" / "a.csv");
    out.precision(17);
    out << "time_s,force,acc_damper\n";
    for (int k = 0; k < periods * per_period; ++k) {
        const double t = k / (f * per_period);
        const double w = kTwoPi * f;
        out << t << ',' << std::cos(w * t) << ','
            << 3.0 * std::sin(w * t) + 0.3 * std::cos(2.0 * w * t + 1.0) +
                   0.15 * std::sin(3.0 * w * t)
            << '\n';
    }
    out.close();
    const auto rec = read_recording(dir);
    const auto& acc = rec.points[0].values[1];
    EXPECT_TRUE(acc.from_series);
    EXPECT_NEAR(acc.h2_ratio, 0.1, 1e-12);
    EXPECT_NEAR(acc.h3_ratio, 0.05, 1e-12);
    EXPECT_NEAR(std::abs(acc.amplitude), 3.0, 1e-12);
    const auto& force = rec.points[0].values[0];
    EXPECT_FALSE(force.from_series);
    EXPECT_EQ(force.h2_ratio, 0.5);
    EXPECT_TRUE(std::isnan(force.h3_ratio));
}

TEST(RecordingIo, DampingCsvRoundTripsWhichPointsEachEstimateUsed) {
    const auto file = fs::temp_directory_path() / "sb_identification_recording_test" / "d.csv";
    fs::create_directories(file.parent_path());
    std::vector<DampingRow> rows = {
        {"H-0", 2.0, 6.35, 0.0123456789012345, "half-power", 3, {6.3, 6.35 + 1.0 / 3.0, 6.7}, 2},
        {"H-0", 2.0, 6.36, 0.0125, "circle-fit", 0, {}, 0}};
    write_damping_csv(file, rows);
    EXPECT_EQ(first_line(file),
              "arrangement,level_g,natural_frequency_hz,damping_ratio,method,points_used,"
              "frequencies_used_hz,points_skipped,fillings,natural_frequency_std_hz,"
              "damping_ratio_std");
    const auto back = read_damping_csv(file);
    ASSERT_EQ(back.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(back[i].damping_ratio, rows[i].damping_ratio) << i;
        EXPECT_EQ(back[i].method, rows[i].method) << i;
        EXPECT_EQ(back[i].points_used, rows[i].points_used) << i;
        EXPECT_EQ(back[i].frequencies_used_hz, rows[i].frequencies_used_hz) << i;
        EXPECT_EQ(back[i].points_skipped, rows[i].points_skipped) << i;
    }
}

TEST(RecordingIo, DampingCsvWithoutTheNewColumnsStillReads) {
    const auto file = fs::temp_directory_path() / "sb_identification_recording_test" / "old.csv";
    fs::create_directories(file.parent_path());
    std::ofstream(file) << "arrangement,level_g,natural_frequency_hz,damping_ratio,method\n"
                           "H-0,0.5,6.3,0.05,half-power\n";
    const auto rows = read_damping_csv(file);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0].damping_ratio, 0.05);
    EXPECT_EQ(rows[0].points_used, 0);
    EXPECT_TRUE(rows[0].frequencies_used_hz.empty());
    EXPECT_EQ(rows[0].points_skipped, 0);
}

TEST(RecordingIo, DampingCsvBadUsedPointsAreReportedAtTheirCell) {
    const auto file = fs::temp_directory_path() / "sb_identification_recording_test" / "bad.csv";
    fs::create_directories(file.parent_path());
    const std::string header =
        "arrangement,level_g,natural_frequency_hz,damping_ratio,method,points_used,"
        "frequencies_used_hz,points_skipped\n";
    const auto error = [&](const std::string& row) {
        std::ofstream(file) << header << row;
        try {
            read_damping_csv(file);
        } catch (const FileError& e) {
            return e;
        }
        ADD_FAILURE() << "no FileError for " << row;
        return FileError("", 0, 0, "");
    };
    // A frequency that is not a number: at its own position within the cell.
    std::string row = "H-0,0.5,6.3,0.05,half-power,3,6.2;x6.3;6.4,0\n";
    auto e = error(row);
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.column(), static_cast<int>(row.find("x6.3")) + 1);
    EXPECT_NE(e.message().find("'x6.3' is not a number"), std::string::npos) << e.what();
    // The count contradicts the list.
    row = "H-0,0.5,6.3,0.05,half-power,4,6.2;6.3;6.4,0\n";
    e = error(row);
    EXPECT_EQ(e.column(), static_cast<int>(row.find("6.2;")) + 1);
    EXPECT_NE(e.message().find("lists 3 frequencies but points_used is 4"), std::string::npos)
        << e.what();
    // A count that is not a count.
    row = "H-0,0.5,6.3,0.05,half-power,3,6.2;6.3;6.4,-1\n";
    e = error(row);
    EXPECT_EQ(e.column(), static_cast<int>(row.rfind(',')) + 2);
    EXPECT_NE(e.message().find("column 'points_skipped': '-1' is not a count"), std::string::npos)
        << e.what();
}

TEST(RecordingIo, TimeHistoryRoundTripsAndRejectsNonUniformSampling) {
    TimeHistory h;
    h.channels = {"force", "acc_damper"};
    h.columns.resize(2);
    for (int i = 0; i < 8; ++i) {
        h.time_s.push_back(i / 1000.0);
        h.columns[0].push_back(std::sin(i * 0.7));
        h.columns[1].push_back(std::cos(i * 0.3) / 3.0);
    }
    const auto p = fs::temp_directory_path() / "sb_identification_recording_test" / "series.csv";
    fs::create_directories(p.parent_path());
    write_time_history_csv(p, h);
    const auto back = read_time_history_csv(p);
    EXPECT_EQ(back.columns, h.columns);
    EXPECT_NEAR(back.sample_rate_hz(), 1000.0, 1e-9);
    std::ofstream(p) << "time_s,a\n0,1\n0.001,2\n0.003,3\n";
    EXPECT_THROW(read_time_history_csv(p), FileError);
}

}  // namespace
}  // namespace sb::identification

// Recording directory: round trip and the documented errors with file, line and column.
#include "identification/recording_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>

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

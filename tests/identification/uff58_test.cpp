// UFF58: exact round trip, a hand-written file with the reader traps, binary 58b.
#include "identification/uff58.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "identification/file_error.hpp"
#include "sdof_frf.hpp"

namespace sb::identification {
namespace {

namespace fs = std::filesystem;

/// Values written with E20.12 carry 13 significant digits: relative error ≤ 5e-13.
constexpr double kNominalRelative = 1e-12;
/// Abscissa in E13.5: 6 significant digits.
constexpr double kAbscissaRelative = 1e-5;
/// Single-precision ordinates in E13.5: 6 significant digits (relative error ≤ 5e-6).
constexpr double kSingleRelative = 1e-5;

fs::path temp_file(const std::string& name) {
    const auto dir = fs::temp_directory_path() / "sb_identification_uff58_test";
    fs::create_directories(dir);
    return dir / name;
}

void write_text(const fs::path& p, const std::string& s) {
    std::ofstream f(p, std::ios::binary);
    f << s;
}

void expect_same_axis(const Uff58Axis& a, const Uff58Axis& b, const std::string& what) {
    EXPECT_EQ(a.data_type, b.data_type) << what;
    EXPECT_EQ(a.length_exponent, b.length_exponent) << what;
    EXPECT_EQ(a.force_exponent, b.force_exponent) << what;
    EXPECT_EQ(a.temperature_exponent, b.temperature_exponent) << what;
    EXPECT_EQ(a.label, b.label) << what;
    EXPECT_EQ(a.units, b.units) << what;
}

/// Every field of records 1–11.
void expect_same_header(const Uff58Record& a, const Uff58Record& b) {
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.function_type, b.function_type);
    EXPECT_EQ(a.function_id, b.function_id);
    EXPECT_EQ(a.version, b.version);
    EXPECT_EQ(a.load_case, b.load_case);
    EXPECT_EQ(a.response_name, b.response_name);
    EXPECT_EQ(a.response_node, b.response_node);
    EXPECT_EQ(a.response_direction, b.response_direction);
    EXPECT_EQ(a.reference_name, b.reference_name);
    EXPECT_EQ(a.reference_node, b.reference_node);
    EXPECT_EQ(a.reference_direction, b.reference_direction);
    EXPECT_EQ(a.ordinate_type, b.ordinate_type);
    EXPECT_EQ(a.z_value, b.z_value);
    expect_same_axis(a.abscissa, b.abscissa, "abscissa");
    expect_same_axis(a.ordinate, b.ordinate, "ordinate");
    expect_same_axis(a.denominator, b.denominator, "denominator");
    expect_same_axis(a.z_axis, b.z_axis, "z axis");
}

std::vector<Uff58Record> sample_records() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto frf = testing::modal_accelerance(testing::grid_around(6.37, 0.03, 17, 4.0, 0.1),
                                          {{6.37, 0.03, 1.0}});
    Uff58Record a = to_uff58(frf, "accelerance beam H-0 0.5 g");
    a.id = {"accelerance beam H-0 0.5 g", "run 17", "25-Nov-26 10:00:00", "load case one",
            std::string(80, 'x')};
    a.function_id = 12;
    a.version = 3;
    a.load_case = 0;
    a.response_name = "acc damper";  // 10 characters, with a blank
    a.response_node = 4;
    a.response_direction = -2;
    a.reference_name = "shaker";
    a.reference_node = 1;
    a.reference_direction = 2;
    a.z_value = 1.0 / 3.0;
    a.z_axis = {1, 0, 0, 0, "Level", "g RMS"};
    a.ordinate.units = "m/s^2 per 20 chars.";
    Uff58Record t;
    t.function_type = 1;
    t.ordinate_type = 4;
    t.abscissa = {17, 0, 0, 0, "Time", "s"};
    t.denominator = {};
    for (int i = 0; i < 11; ++i) {
        t.x.push_back(i / 1024.0);
        t.y.emplace_back(u(rng) * 1e-3, 0.0);
    }
    // Single precision keeps its type; its values are floats.
    Uff58Record c = to_uff58(frf, "single");
    c.ordinate_type = 5;
    for (auto& y : c.y) {
        y = {static_cast<double>(static_cast<float>(y.real())),
             static_cast<double>(static_cast<float>(y.imag()))};
    }
    Uff58Record d = t;
    d.ordinate_type = 2;
    for (auto& y : d.y) y = {static_cast<double>(static_cast<float>(y.real())), 0.0};
    return {a, t, c, d};
}

TEST(Uff58, RoundTripsEveryNumberBitForBitWithExactDigits) {
    const auto records = sample_records();
    const auto p = temp_file("exact.uff");
    write_uff58(p, records, Uff58Digits::exact);
    const auto back = read_uff58(p);
    ASSERT_EQ(back.size(), records.size());
    for (std::size_t k = 0; k < records.size(); ++k) {
        SCOPED_TRACE("record " + std::to_string(k));
        EXPECT_EQ(back[k].x, records[k].x);
        EXPECT_EQ(back[k].y, records[k].y);
        expect_same_header(back[k], records[k]);
    }
    // Every line of the file stays within 80 columns.
    std::ifstream f(p);
    for (std::string line; std::getline(f, line);) EXPECT_LE(line.size(), 80u) << line;
}

TEST(Uff58, NominalLayoutKeepsThirteenDigitsAndRewritesIdentically) {
    const auto records = sample_records();
    const auto p = temp_file("nominal.uff");
    write_uff58(p, records, Uff58Digits::nominal);
    const auto back = read_uff58(p);
    ASSERT_EQ(back.size(), records.size());
    for (std::size_t k = 0; k < records.size(); ++k) {
        SCOPED_TRACE("record " + std::to_string(k));
        auto expected = records[k];
        expected.z_value = back[k].z_value;  // E13.5
        expect_same_header(back[k], expected);
        EXPECT_NEAR(back[k].z_value, records[k].z_value, kAbscissaRelative);
        const bool single = records[k].ordinate_type == 2 || records[k].ordinate_type == 5;
        const double rel = single ? kSingleRelative : kNominalRelative;
        for (std::size_t i = 0; i < records[k].y.size(); ++i) {
            EXPECT_NEAR(back[k].y[i].real(), records[k].y[i].real(),
                        rel * std::abs(records[k].y[i]));
            EXPECT_NEAR(back[k].y[i].imag(), records[k].y[i].imag(),
                        rel * std::abs(records[k].y[i]));
            EXPECT_NEAR(back[k].x[i], records[k].x[i], kAbscissaRelative * records[k].x.back());
        }
    }
    // Write what was read: the same numbers again (a fixed point).
    const auto p2 = temp_file("nominal2.uff");
    write_uff58(p2, back, Uff58Digits::nominal);
    const auto again = read_uff58(p2);
    for (std::size_t k = 0; k < records.size(); ++k) {
        EXPECT_EQ(again[k].y, back[k].y);
        EXPECT_EQ(again[k].x, back[k].x);
    }
}

TEST(Uff58, RefusesToWriteANameLongerThanItsFieldInsteadOfCuttingIt) {
    auto records = sample_records();
    records[0].response_name = "acc_damper1";  // 11 characters in a 10-character field
    EXPECT_THROW(write_uff58(temp_file("long.uff"), records), std::invalid_argument);
    records = sample_records();
    records[0].ordinate.label = std::string(21, 'a');
    EXPECT_THROW(write_uff58(temp_file("long.uff"), records), std::invalid_argument);
    records = sample_records();
    records[0].id[2] = std::string(81, 'a');
    EXPECT_THROW(write_uff58(temp_file("long.uff"), records), std::invalid_argument);
}

TEST(Uff58, ReadsAFileWhoseLinesArePaddedWithBlanksToEightyColumns) {
    const std::string lines[] = {
        "    -1",
        "    58",
        "padded",
        "NONE",
        "NONE",
        "NONE",
        "NONE",
        "    4         1    0         0 acc                4   2 force              1   2",
        "         6         2         0  0.00000E+00  0.00000E+00  2.50000E-01",
        "        18    0    0    0 Frequency            Hz",
        "        12    1    0    0 Acceleration         m/s^2",
        "        13    0    1    0 Force                N",
        "         0    0    0    0 NONE                 NONE",
        "  1.00000E+01  1.250000000000E+00 -2.500000000000E-01",
        "  1.05000E+01  2.000000000000E+00 -1.000000000000E+00",
        "    -1"};
    std::string text;
    for (const auto& l : lines) text += l + std::string(80 - l.size(), ' ') + "\r\n";
    const auto p = temp_file("padded.uff");
    write_text(p, text);
    const auto r = read_uff58(p);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].id[0], "padded");
    EXPECT_EQ(r[0].response_name, "acc");
    EXPECT_EQ(r[0].reference_direction, 2);
    EXPECT_EQ(r[0].z_value, 0.25);
    EXPECT_EQ(r[0].abscissa.units, "Hz");
    EXPECT_EQ(r[0].z_axis.label, "NONE");
    EXPECT_EQ(r[0].x, (std::vector<double>{10.0, 10.5}));
    EXPECT_EQ(r[0].y[1], std::complex<double>(2.0, -1.0));
}

TEST(Uff58, ReadsAHandWrittenFileWithDExponentsPaddingGluedFieldsAndOtherDatasets) {
    // Layout from research note §4.2–4.3, typed by hand: a dataset 151 to skip, a complex
    // double uneven FRF (case 8) with a Fortran D exponent and a glued line, and a real single
    // even time response (case 1) whose last row is padded with zeros past num_pts.
    const std::string text =
        "    -1\n"
        "   151\n"
        "model name\n"
        "    -1\n"
        "    -1\n"
        "    58\n"
        "FRF acc/force\n"
        "\n"
        "25-Nov-26 10:00:00\n"
        "NONE\n"
        "NONE\n"
        "    4         1    0         0 acc       \x20        4   2 force     \x20        1   2\n"
        "         6         3         0  0.00000E+00  0.00000E+00  0.00000E+00\n"
        "        18    0    0    0 Frequency            Hz\n"
        "        12    1    0    0 Acceleration         m/s^2\n"
        "        13    0    1    0 Force                N\n"
        "         0    0    0    0 NONE                 NONE\n"
        "  1.00000E+01  1.250000000000D+00 -2.500000000000E-01\n"
        "  1.05000E+01  2.000000000000E+00-1.000000000000E+00\n"
        "  1.10000E+01  1.0-1 3.0+00\r\n"
        "    -1\n"
        "    -1\n"
        "    58\n"
        "time\nNONE\nNONE\nNONE\nNONE\n"
        "    1         0    0         0 acc                4   2 NONE               0   0\n"
        "         2         8         1  0.00000E+00  1.00000E-03  0.00000E+00\n"
        "        17    0    0    0 Time                 s\n"
        "        12    1    0    0 Acceleration         m/s^2\n"
        "         0    0    0    0 NONE                 NONE\n"
        "         0    0    0    0 NONE                 NONE\n"
        "  1.00000E+00  2.00000E+00  3.00000E+00  4.00000E+00  5.00000E+00  6.00000E+00\n"
        "  7.00000D+00  8.00000E+00  0.00000E+00  0.00000E+00  0.00000E+00  0.00000E+00\n"
        "    -1\n";
    const auto p = temp_file("hand.uff");
    write_text(p, text);
    const auto r = read_uff58(p);
    ASSERT_EQ(r.size(), 2u);
    EXPECT_EQ(r[0].function_type, 4);
    EXPECT_EQ(r[0].response_name, "acc");
    EXPECT_EQ(r[0].response_node, 4);
    EXPECT_EQ(r[0].reference_name, "force");
    EXPECT_EQ(r[0].id[1], "NONE");  // blank ID line
    ASSERT_EQ(r[0].x.size(), 3u);
    EXPECT_EQ(r[0].x[1], 10.5);
    EXPECT_EQ(r[0].y[0], std::complex<double>(1.25, -0.25));
    EXPECT_EQ(r[0].y[1], std::complex<double>(2.0, -1.0));
    EXPECT_EQ(r[0].y[2], std::complex<double>(0.1, 3.0));
    const Frf frf = to_frf(r[0]);
    EXPECT_EQ(frf.form, FrfForm::accelerance);
    EXPECT_EQ(r[1].function_type, 1);
    ASSERT_EQ(r[1].y.size(), 8u);
    EXPECT_EQ(r[1].y[6].real(), 7.0);
    EXPECT_NEAR(r[1].x[7], 7e-3, 1e-15);
}

TEST(Uff58, ReadsBinary58bWithAWrongByteCountAndAStrayCrLf) {
    std::string s =
        "    -1\n"
        "    58b     1     2          11          16     0     0           0           0\n"
        "bin\nNONE\nNONE\nNONE\nNONE\n"
        "    4         1    0         0 acc                4   2 force              1   2\n"
        "         6         2         0  0.00000E+00  0.00000E+00  0.00000E+00\n"
        "        18    0    0    0 Frequency            Hz\n"
        "        12    1    0    0 Acceleration         m/s^2\n"
        "        13    0    1    0 Force                N\n"
        "         0    0    0    0 NONE                 NONE\n";
    const double v[6] = {5.0, 0.1, -0.2, 6.0, -1.0e-300, 12345.678};
    char bytes[sizeof v];
    std::memcpy(bytes, v, sizeof v);  // the test host is little-endian, like the header says
    s.append(bytes, sizeof v);
    s += "\r\n    -1\n";
    const auto p = temp_file("bin.uff");
    write_text(p, s);
    const auto r = read_uff58(p);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].x, (std::vector<double>{5.0, 6.0}));
    EXPECT_EQ(r[0].y[0], std::complex<double>(0.1, -0.2));
    EXPECT_EQ(r[0].y[1], std::complex<double>(-1.0e-300, 12345.678));
}

/// Header of a binary dataset 58b (records 1–11) with the given id line and record 7.
std::string binary_header(const std::string& id_line, const std::string& record7) {
    return "    -1\n" + id_line + "\nbin\nNONE\nNONE\nNONE\nNONE\n" +
           "    4         1    0         0 acc                4   2 force              1   2\n" +
           record7 + "\n" +
           "        18    0    0    0 Frequency            Hz\n"
           "        12    1    0    0 Acceleration         m/s^2\n"
           "        13    0    1    0 Force                N\n"
           "         0    0    0    0 NONE                 NONE\n";
}

/// The bytes of values of type T, in big- or little-endian order.
template <typename T>
std::string bytes_of(const std::vector<double>& values, bool big_endian) {
    std::string out;
    for (double v : values) {
        const T t = static_cast<T>(v);
        char b[sizeof(T)];
        std::memcpy(b, &t, sizeof(T));
        const bool host_big = std::endian::native == std::endian::big;
        if (big_endian != host_big) std::reverse(b, b + sizeof(T));
        out.append(b, sizeof(T));
    }
    return out;
}

TEST(Uff58, ReadsBigEndianBinary58b) {
    std::string s = binary_header(
        "    58b     2     2          11          48     0     0           0           0",
        "         6         2         0  0.00000E+00  0.00000E+00  0.00000E+00");
    s += bytes_of<double>({5.0, 0.1, -0.2, 6.0, -1.0e-300, 12345.678}, true);
    s += "    -1\n";
    const auto p = temp_file("bin-big.uff");
    write_text(p, s);
    const auto r = read_uff58(p);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].x, (std::vector<double>{5.0, 6.0}));
    EXPECT_EQ(r[0].y[1], std::complex<double>(-1.0e-300, 12345.678));
}

TEST(Uff58, ReadsSinglePrecisionEvenlySpacedBinary58bWithTheSpacedHeader) {
    // Complex single (type 5), even spacing from 10 Hz by 0.5 Hz: 4 bytes per value, no x.
    // The id line is written "58 b" by some tools.
    std::string s = binary_header(
        "    58 b     1     2          11          24     0     0           0           0",
        "         5         3         1  1.00000E+01  5.00000E-01  0.00000E+00");
    const std::vector<double> v = {0.5, -0.25, 1.5, 2.0, -3.0, 0.125};  // exact in float
    s += bytes_of<float>(v, false);
    s += "\n    -1\n";
    const auto p = temp_file("bin-single.uff");
    write_text(p, s);
    const auto r = read_uff58(p);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].ordinate_type, 5);
    EXPECT_EQ(r[0].x, (std::vector<double>{10.0, 10.5, 11.0}));
    EXPECT_EQ(r[0].y[0], std::complex<double>(0.5, -0.25));
    EXPECT_EQ(r[0].y[2], std::complex<double>(-3.0, 0.125));
}

/// fuzz/corpus/uff58/regression-huge-point-count.uff: record 7 announces 999999999 points
/// of three values each; the reader reserved room for all of them before reading one (24 GB).
TEST(Uff58, AHugePointCountIsReportedAsMissingValuesNotAllocated) {
    const std::string text =
        "    -1\n    58\nx\nx\nx\nx\nx\n"
        "    4         1    0         0 acc                4   2 force              1   2\n"
        "         6 999999999         0  0.00000E+00  0.00000E+00  0.00000E+00\n"
        "        18    0    0    0 Frequency            Hz\n"
        "        12    1    0    0 Acceleration         m/s^2\n"
        "        13    0    1    0 Force                N\n"
        "         0    0    0    0 NONE                 NONE\n"
        "  1.00000E+01  1.250000000000E+00 -2.500000000000E-01\n"
        "    -1\n";
    const auto p = temp_file("huge.uff");
    write_text(p, text);
    try {
        (void)read_uff58(p);
        FAIL() << "read";
    } catch (const FileError& e) {
        EXPECT_NE(e.message().find("3 values for 999999999 points"), std::string::npos) << e.what();
    }
}

/// fuzz/corpus/uff58/regression-binary-nan.uff: a NaN in a binary block came through as a
/// value of the FRF.
TEST(Uff58, ANonFiniteValueInABinaryBlockIsAnErrorAtItsPoint) {
    std::string s = binary_header(
        "    58b     1     2          11          48     0     0           0           0",
        "         6         2         0  0.00000E+00  0.00000E+00  0.00000E+00");
    s += bytes_of<double>({5.0, 0.1, -0.2, 6.0, std::numeric_limits<double>::quiet_NaN(), 1.0},
                          false);
    s += "    -1\n";
    const auto p = temp_file("bin-nan.uff");
    write_text(p, s);
    try {
        (void)read_uff58(p);
        FAIL() << "read";
    } catch (const FileError& e) {
        EXPECT_NE(e.message().find("point 2 is not a finite number"), std::string::npos)
            << e.what();
    }
    // An evenly spaced abscissa past the largest double, from finite min and increment.
    s = binary_header(
        "    58b     1     2          11          48     0     0           0           0",
        "         2         3         1  1.00000E+308  1.00000E+308  0.00000E+00");
    s += bytes_of<float>({1.0, 2.0, 3.0}, false) + "    -1\n";
    write_text(p, s);
    EXPECT_THROW((void)read_uff58(p), FileError);
}

TEST(Uff58, ADeviceIsNotReadAsAFile) {
    try {
        (void)read_uff58("/dev/zero");
        FAIL() << "read";
    } catch (const FileError& e) {
        EXPECT_EQ(e.message(), "not a regular file");
    }
}

TEST(Uff58, ReportsFileLineAndColumnOfABadNumber) {
    const std::string text =
        "    -1\n    58\nx\nx\nx\nx\nx\n"
        "    4         1    0         0 acc                4   2 force              1   2\n"
        "         6         1         0  0.00000E+00  0.00000E+00  0.00000E+00\n"
        "        18    0    0    0 Frequency            Hz\n"
        "        12    1    0    0 Acceleration         m/s^2\n"
        "        13    0    1    0 Force                N\n"
        "         0    0    0    0 NONE                 NONE\n"
        "  1.00000E+01  1.250000000000E+00   oops\n"
        "    -1\n";
    const auto p = temp_file("bad.uff");
    write_text(p, text);
    try {
        read_uff58(p);
        FAIL() << "no error";
    } catch (const FileError& e) {
        EXPECT_EQ(e.line(), 14);
        EXPECT_EQ(e.column(), 34);
        EXPECT_NE(std::string(e.what()).find("bad.uff:14:34: record 12: not a number"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace sb::identification

// End-to-end checks of the shakerbench executable: exit codes and messages users see.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>

#include "cli_helpers.hpp"

namespace {

using namespace sb::test;

TEST(Cli, HelpListsTheSubcommandsAndExitsZero) {
    const auto r = run("--help");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.output.find("modes"), std::string::npos) << r.output;
}

TEST(Cli, VersionPrintsTheVersion) {
    const auto r = run("--version");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.output.find("shakerbench 0."), std::string::npos) << r.output;
}

TEST(Cli, AnUnknownSubcommandIsBadInput) {
    const auto r = run("shake-it");
    EXPECT_EQ(r.exit_code, 2) << r.output;
}

TEST(Cli, AMissingConfigFileIsBadInputNamingTheFile) {
    const auto r = run("modes /nonexistent/campaign.toml");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("/nonexistent/campaign.toml"), std::string::npos) << r.output;
}

TEST(Cli, ABadConfigGivesFileLineKeyAndExitCodeTwo) {
    const auto dir = temp_dir("bad");
    const auto file = dir / "bad.toml";
    std::ofstream(file) << "[structure]\nkind = \"beam\"\n[structure.beam]\nlength_m = -1.0\n"
                           "width_m = 0.05\nthickness_m = 0.003\ndensity_kg_m3 = 2700.0\n"
                           "youngs_modulus_pa = 7e10\n[structure.beam.supports.root]\nx_m = 0.0\n";
    const auto r = run("modes " + file.string() + " --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(file.string() + ":4:12: structure.beam.length_m = -1: must be > 0"),
              std::string::npos)
        << r.output;
}

TEST(Cli, ModesOnTheBuiltInBeamPrintsTheFirstModeAndWritesShapes) {
    const auto dir = temp_dir("modes");
    const auto r = run("modes --out " + dir.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("frequency [Hz]"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "paper000-h0-modes.csv"));
}

/// A recording directory of an exact SDOF accelerance (m, f_n, zeta) around its resonance.
std::filesystem::path write_sdof_recording(const std::string& name, double zeta, bool broken) {
    const auto dir = temp_dir(name);
    std::ofstream(dir / "recording.toml")
        << "[recording]\nname = \"sdof\"\nkind = \"simulated\"\nexcitation = \"force\"\n\n"
           "[channels.force]\nquantity = \"force\"\nunit = \"N\"\nlocation = \"shaker\"\n"
           "role = \"reference\"\n\n[channels.acc]\nquantity = \"acceleration\"\n"
           "unit = \"m/s^2\"\nlocation = \"damper\"\nrole = \"control\"\n";
    std::ofstream points(dir / "points.csv");
    points << "arrangement,level_g,frequency_hz,status,series,force_rms,force_re,force_im,acc_rms,"
              "acc_re,acc_im\n";
    const double mass_kg = 0.1;
    const double fn_hz = 6.4;
    for (int i = 0; i <= 40; ++i) {
        const double f = fn_hz * (0.9 + 0.005 * i);
        const double r = f / fn_hz;
        const std::complex<double> receptance =
            1.0 / (mass_kg * std::pow(2.0 * std::numbers::pi * fn_hz, 2) *
                   std::complex<double>(1.0 - r * r, 2.0 * zeta * r));
        const std::complex<double> acc = -std::pow(2.0 * std::numbers::pi * f, 2) * receptance;
        points << "H-0,1," << f << ",converged,,0.70710678,1,0," << std::abs(acc) / std::sqrt(2.0)
               << ',' << acc.real() << ','
               << (broken && i == 7 ? std::string("oops") : std::to_string(acc.imag())) << '\n';
    }
    return dir;
}

TEST(Cli, IdentifyRecoversTheDampingOfAnSdofRecording) {
    const double zeta = 0.02;
    const auto dir = write_sdof_recording("identify-good", zeta, false);
    const auto r = run("identify " + dir.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("half-power"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "damping.csv"));
    std::ifstream csv(dir / "out" / "damping.csv");
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "arrangement,level_g,natural_frequency_hz,damping_ratio,method");
    int rows = 0;
    while (std::getline(csv, line)) {
        const auto last = line.rfind(',');
        const auto before = line.rfind(',', last - 1);
        const double ratio = std::stod(line.substr(before + 1, last - before - 1));
        // Exact data (6 significant digits in the CSV): every method within 2 %.
        EXPECT_NEAR(ratio, zeta, 0.02 * zeta) << line;
        ++rows;
    }
    EXPECT_GE(rows, 2);
}

TEST(Cli, IdentifyReportsANonNumericCellWithFileLineAndExitCodeTwo) {
    const auto dir = write_sdof_recording("identify-bad", 0.02, true);
    const auto r = run("identify " + dir.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("points.csv:9:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("oops"), std::string::npos) << r.output;
}

}  // namespace

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
#include <vector>

#include "cli_helpers.hpp"
#include "tests/support/small_beam_config.hpp"

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
    EXPECT_NE(r.output.find(file.string() + ":4:12: structure.beam.length_m = -1.0: must be > 0"),
              std::string::npos)
        << r.output;
}

const std::string& kBeamConfig = sb::test::kSmallBeamConfig;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

/// Runs `shakerbench ARGS` in `dir`, so that files named relative to it print as written.
Result run_in(const std::filesystem::path& dir, const std::string& arguments) {
    return run_command("cd '" + dir.string() + "' && " + std::string(SB_CLI) + " " + arguments +
                       " 2>&1");
}

/// `shakerbench modes NAME` on `text` written to NAME in a fresh directory.
Result modes_on(const std::string& test, const std::string& name, const std::string& text) {
    const auto dir = temp_dir(test);
    std::ofstream(dir / name) << text;
    return run_in(dir, "modes " + name + " --out out");
}

/// Every line of `output` that names `file`.
std::vector<std::string> lines_naming(const std::string& output, const std::string& file) {
    std::vector<std::string> lines;
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind(file + ":", 0) == 0) lines.push_back(line);
    }
    return lines;
}

/// `modes` on the small beam config with `from` replaced by `to` exits 2, and `expected` is
/// the only line of its output that names the file.
void expect_the_only_error(const std::string& name, const std::string& from, const std::string& to,
                           const std::string& expected) {
    const auto r = modes_on(name, "bad.toml", replaced(kBeamConfig, from, to));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(lines_naming(r.output, "bad.toml"), std::vector<std::string>{expected}) << r.output;
}

TEST(CliBadConfig, ANegativeLengthIsReportedAtItsValueAndNothingElseIsBlamed) {
    expect_the_only_error(
        "negative-length", "length_m = 0.5", "length_m = -0.5",
        "bad.toml:9:12: structure.beam.length_m = -0.5: must be > 0 (beam length [m])");
}

TEST(CliBadConfig, AnUnknownKeyIsReportedAsUnknown) {
    expect_the_only_error(
        "unknown-key", "width_m = 0.05", "width_m = 0.05\nwdith_m = 0.05",
        "bad.toml:11:11: structure.beam.wdith_m = 0.05: unknown key (see docs/config.md "
        "for the keys of [structure.beam])");
}

TEST(CliBadConfig, AMassOutsideTheBeamNamesTheAllowedRange) {
    expect_the_only_error("mass-outside", "point = \"tip\"", "x_m = 0.7",
                          "bad.toml:24:7: structure.beam.masses[0].x_m = 0.7: must be "
                          "in [0, 0.5] (mass position along the beam [m])");
}

TEST(CliBadConfig, AMissingBeamSectionIsReportedWithTheOtherErrorsOfTheStructure) {
    std::string text = kBeamConfig.substr(0, kBeamConfig.find("[structure.beam]\n")) +
                       kBeamConfig.substr(kBeamConfig.find("[structure.excitation]"));
    text = replaced(text, "kind = \"beam\"", "kind = \"beam\"\nmodes = 0");
    const auto r = modes_on("missing-section", "bad.toml", text);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(lines_naming(r.output, "bad.toml"),
              (std::vector<std::string>{
                  "bad.toml:5:1: structure.beam: is required (the beam of a structure of kind "
                  "\"beam\")",
                  "bad.toml:7:9: structure.modes = 0: must be >= 1 (modes kept in the reduced "
                  "modal model)"}))
        << r.output;
}

TEST(CliBadConfig, AMissingStructureIsReportedAtTheTopOfTheFile) {
    const auto r = modes_on("missing-structure", "bad.toml", "[campaign]\nname = \"t\"\n");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(
        lines_naming(r.output, "bad.toml"),
        std::vector<std::string>{"bad.toml:1:1: structure: is required (the structure under test)"})
        << r.output;
}

TEST(CliBadConfig, AWrongTypeNamesTheTypeExpected) {
    expect_the_only_error("wrong-type", "density_kg_m3 = 2700.0", "density_kg_m3 = \"steel\"",
                          "bad.toml:12:17: structure.beam.density_kg_m3 = \"steel\": "
                          "must be a number (beam density [kg/m^3])");
}

TEST(CliBadConfig, TheReadmeExamplePrintsWhatTheReadmeShows) {
    std::string text = replaced(kBeamConfig, "length_m = 0.5", "length_m = -0.5");
    text = replaced(text, "width_m = 0.05", "width_m = 0.05\nwdith_m = 0.05");
    const auto r = modes_on("readme", "my.toml", text);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    // README.md, "Copy a config and change it".
    EXPECT_EQ(r.output,
              "my.toml:9:12: structure.beam.length_m = -0.5: must be > 0 (beam length [m])\n"
              "my.toml:11:11: structure.beam.wdith_m = 0.05: unknown key (see docs/config.md for "
              "the keys of [structure.beam])\n"
              "shakerbench: 2 errors in the config; nothing was run.\n");
}

TEST(CliBadConfig, ANegativeSeedIsAnError) {
    expect_the_only_error(
        "seed", "name = \"t\"", "name = \"t\"\nseed = -3",
        "bad.toml:4:8: campaign.seed = -3: must be >= 0 (seed of the particle filling)");
}

TEST(CliBadConfig, ASectionThickerThanItIsWideIsAnError) {
    expect_the_only_error(
        "thick", "thickness_m = 0.003", "thickness_m = 0.06",
        "bad.toml:11:15: structure.beam.thickness_m = 0.06: must be <= width_m = 0.05 "
        "(section side along z, the shorter one [m]; drive the stiff direction with "
        "excitation.direction = [0, 1, 0])");
}

/// A fixed-free chain of three 1 kg masses and 100 N/m springs, as Matrix Market files in
/// `dir/sub`, and a config naming `dofs` (TOML lines) there.
void write_chain(const std::filesystem::path& dir, const std::string& dofs,
                 const std::string& extra_matrix_keys = "", const std::string& point = "c") {
    std::filesystem::create_directories(dir / "sub");
    std::ofstream(dir / "sub" / "m.mtx")
        << "%%MatrixMarket matrix coordinate real symmetric\n3 3 3\n1 1 1.0\n2 2 1.0\n3 3 1.0\n";
    std::ofstream(dir / "sub" / "k.mtx")
        << "%%MatrixMarket matrix coordinate real symmetric\n3 3 5\n1 1 200.0\n2 1 -100.0\n"
           "2 2 200.0\n3 2 -100.0\n3 3 100.0\n";
    std::ofstream(dir / "sub" / "chain.toml")
        << "[campaign]\nname = \"chain\"\n\n[structure]\nkind = \"matrix\"\nmodes = 3\n\n"
           "[structure.matrix]\nmass_file = \"m.mtx\"\nstiffness_file = \"k.mtx\"\n"
        << extra_matrix_keys << "\n[structure.matrix.dofs]\n"
        << dofs << "\n[structure.excitation]\npoint = \"" << point << "\"\n";
}

struct ModeLine {
    double frequency_hz = 0.0;
    std::string effective_z;
};

/// The mode table `shakerbench modes` prints: frequency and z effective mass per mode.
std::vector<ModeLine> mode_lines(const std::string& output) {
    std::vector<ModeLine> out;
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);) {
        std::istringstream fields(line);
        int mode = 0;
        ModeLine m;
        double damping = 0.0, modal = 0.0;
        std::string ex, slash1, ey, slash2, ez;
        if (fields >> mode >> m.frequency_hz >> damping >> modal >> ex >> slash1 >> ey >> slash2 >>
                ez &&
            slash1 == "/" && slash2 == "/") {
            m.effective_z = ez;
            out.push_back(m);
        }
    }
    return out;
}

/// Fixed-free chain of N = 3 masses m = 1 kg and springs k = 100 N/m: the eigenvalues of its
/// tridiagonal (k/m) [2 -1; -1 2 -1; -1 1] are w_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2N + 1))).
double chain_frequency_hz(int j) {
    return 2.0 * 10.0 * std::sin((2 * j - 1) * std::numbers::pi / 14.0) / (2.0 * std::numbers::pi);
}

constexpr double kPrintedHz = 5e-5;  // the table prints four decimals

TEST(CliMatrixImport, ModesOfAChainImportedThroughARelativeConfigPathAreTheAnalyticOnes) {
    const auto dir = temp_dir("matrix-chain");
    write_chain(dir, "\"a.z\" = 0\n\"b.z\" = 1\n\"c.z\" = 2\n");
    const auto r = run_in(dir, "modes sub/chain.toml --out out");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto modes = mode_lines(r.output);
    ASSERT_EQ(modes.size(), 3u) << r.output;
    double effective_sum = 0.0;
    for (int j = 1; j <= 3; ++j) {
        EXPECT_NEAR(modes[static_cast<std::size_t>(j - 1)].frequency_hz, chain_frequency_hz(j),
                    kPrintedHz)
            << r.output;
        effective_sum += std::stod(modes[static_cast<std::size_t>(j - 1)].effective_z);
    }
    EXPECT_NEAR(effective_sum, 3.0, 3 * 5e-6) << r.output;  // every mass moves along z
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "chain-modes.csv"));
}

TEST(CliMatrixImport, EffectiveMassesOfAPartlyNamedImportAreNotGuessed) {
    const auto dir = temp_dir("matrix-partly-named");
    write_chain(dir, "\"a.z\" = 0\n\"b.z\" = 1\n", "", "b");
    const auto r = run_in(dir, "modes sub/chain.toml --out out");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto modes = mode_lines(r.output);
    ASSERT_EQ(modes.size(), 3u) << r.output;
    for (const auto& m : modes) EXPECT_EQ(m.effective_z, "n/a") << r.output;
    EXPECT_NE(r.output.find("structure.matrix.rigid_body_file"), std::string::npos) << r.output;
}

TEST(CliMatrixImport, ARigidBodyFileGivesTheEffectiveMassesOfAPartlyNamedImport) {
    const auto dir = temp_dir("matrix-rigid-body");
    write_chain(dir, "\"a.z\" = 0\n\"b.z\" = 1\n", "rigid_body_file = \"r.mtx\"\n", "b");
    std::ofstream(dir / "sub" / "r.mtx")
        << "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 3 1.0\n2 3 1.0\n3 3 1.0\n";
    const auto r = run_in(dir, "modes sub/chain.toml --out out");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto modes = mode_lines(r.output);
    ASSERT_EQ(modes.size(), 3u) << r.output;
    double effective_sum = 0.0;
    for (const auto& m : modes) effective_sum += std::stod(m.effective_z);
    EXPECT_NEAR(effective_sum, 3.0, 3 * 5e-6) << r.output;
}

TEST(CliMatrixImport, ADofRowBeyondTheMatrixIsReportedAtItsLineWhenTheConfigLoads) {
    const auto dir = temp_dir("matrix-row");
    write_chain(dir, "\"a.z\" = 0\n\"b.z\" = 3\n\"c.z\" = 2\n");
    const auto r = run_in(dir, "modes sub/chain.toml --out out");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(lines_naming(r.output, "sub/chain.toml"),
              std::vector<std::string>{"sub/chain.toml:14:9: structure.matrix.dofs.\"b.z\" = 3: "
                                       "must be < 3, the rows of mass_file (zero-based row of a "
                                       "named DOF)"})
        << r.output;
}

TEST(CliMatrixImport, AMissingMatrixFileIsAConfigError) {
    const auto dir = temp_dir("matrix-missing");
    write_chain(dir, "\"a.z\" = 0\n", "", "a");
    std::filesystem::remove(dir / "sub" / "m.mtx");
    const auto r = run_in(dir, "modes sub/chain.toml --out out");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    const auto lines = lines_naming(r.output, "sub/chain.toml");
    ASSERT_EQ(lines.size(), 1u) << r.output;
    // The file as the bench resolved it, next to the config.
    EXPECT_EQ(lines[0], "sub/chain.toml:9:13: structure.matrix.mass_file = \"" +
                            (std::filesystem::canonical(dir) / "sub" / "m.mtx").string() +
                            "\": cannot be read: cannot open file (Matrix Market mass matrix)")
        << r.output;
}

TEST(CliMatrixImport, BadMatrixContentIsBadInputNamingTheFileAndLine) {
    const auto dir = temp_dir("matrix-content");
    write_chain(dir, "\"a.z\" = 0\n", "", "a");
    std::ofstream(dir / "sub" / "k.mtx")
        << "%%MatrixMarket matrix coordinate real symmetric\n3 3 3\n1 1 1.0\n2 2 x\n3 3 1.0\n";
    const auto r = run_in(dir, "modes sub/chain.toml --out out");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("k.mtx:4: expected 'row column value'"), std::string::npos) << r.output;
}

TEST(CliMatrixImport, AMassMatrixThatIsNotPositiveDefiniteIsBadInput) {
    const auto dir = temp_dir("matrix-indefinite");
    write_chain(dir, "\"a.z\" = 0\n", "", "a");
    std::ofstream(dir / "sub" / "m.mtx")
        << "%%MatrixMarket matrix coordinate real symmetric\n3 3 3\n1 1 1.0\n2 2 -1.0\n3 3 1.0\n";
    const auto r = run_in(dir, "modes sub/chain.toml --out out");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("m.mtx: the mass matrix must be positive definite"), std::string::npos)
        << r.output;
}

TEST(Cli, ModesOnTheBuiltInBeamPrintsTheFirstModeAndWritesShapes) {
    const auto dir = temp_dir("modes");
    const auto r = run("modes --out " + dir.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("frequency [Hz]"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "paper000-h0-modes.csv"));
}

/// The frequency of mode `mode` in the table `modes` prints [Hz].
double mode_frequency_hz(const std::string& output, int mode) {
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        int index = 0;
        double frequency = 0.0;
        if (words >> index >> frequency && index == mode) return frequency;
    }
    ADD_FAILURE() << "no mode " << mode << " in\n" << output;
    return 0.0;
}

TEST(CliSet, ModesWithFourTimesTheModuliHasTwiceTheFrequencies) {
    const auto dir = temp_dir("set-modes");
    const auto plain = run("modes --out " + dir.string());
    ASSERT_EQ(plain.exit_code, 0) << plain.output;
    // Young's and shear moduli together scale every stiffness of the Timoshenko beam.
    const auto stiff = run("modes --out " + dir.string() +
                           " --set structure.beam.youngs_modulus_pa=288e9"
                           " --set structure.beam.shear_modulus_pa=108e9");
    ASSERT_EQ(stiff.exit_code, 0) << stiff.output;
    for (int mode : {1, 2, 3}) {
        // The table prints 4 decimals.
        EXPECT_NEAR(mode_frequency_hz(stiff.output, mode),
                    2.0 * mode_frequency_hz(plain.output, mode), 2e-4)
            << mode;
    }
}

TEST(CliSet, AnUnknownKeyExitsTwoNamingItAndSet) {
    const auto r = run("modes --set no.such.key=1");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--set: no.such.key: unknown key"), std::string::npos) << r.output;
}

TEST(CliSet, AValueOutsideItsBoundExitsTwoNamingTheKeyAndSet) {
    const auto r = run("modes --set structure.beam.length_m=-1");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--set: structure.beam.length_m = -1: must be > 0 (beam length [m])"),
              std::string::npos)
        << r.output;
}

TEST(CliSet, AnAssignmentWithoutEqualsSignExitsTwo) {
    const auto r = run("modes --set structure.beam.length_m");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("must be KEY=VALUE"), std::string::npos) << r.output;
}

/// The hash `keys` prints last.
std::string printed_hash(const std::string& output) {
    const std::string key = "# config_hash = \"";
    const auto at = output.find(key);
    return at == std::string::npos ? "" : output.substr(at + key.size(), 16);
}

TEST(CliKeys, ListsEveryPathWithItsValueAndTheConfigsHash) {
    const auto r = run("keys");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    for (const char* line : {"dampers.pd.contact.sliding_friction = 0.6 ",
                             "structure.beam.masses[5].mass_kg = 0.0238 ",
                             "dampers.pd.contact.normal_stiffness = automatic ",
                             "structure.beam.points.damper = 0.533 "}) {
        EXPECT_NE(r.output.find(std::string("\n") + line), std::string::npos) << line;
    }
    const auto changed = run("keys --set dampers.pd.contact.sliding_friction=0.45");
    EXPECT_NE(changed.output.find("\ndampers.pd.contact.sliding_friction = 0.45 "),
              std::string::npos)
        << changed.output;
    // The wall's friction follows the particles' when the config does not give it.
    EXPECT_NE(changed.output.find("\ndampers.pd.contact.wall_sliding_friction = 0.45 "),
              std::string::npos)
        << changed.output;
    ASSERT_EQ(printed_hash(r.output).size(), 16u) << r.output;
    EXPECT_NE(printed_hash(changed.output), printed_hash(r.output));
}

TEST(CliKeys, DefaultsListTheGenericPathsOfEveryKey) {
    const auto r = run("keys --defaults");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("\ndampers.NAME.contact.wall_sliding_friction = as sliding_friction"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("\nstructure.beam.masses[i].mass_kg = required"), std::string::npos)
        << r.output;
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
    EXPECT_EQ(line.substr(0, line.find(",points_used")),
              "arrangement,level_g,natural_frequency_hz,damping_ratio,method");
    int rows = 0;
    while (std::getline(csv, line)) {
        // damping_ratio is the fourth cell.
        std::size_t begin = 0;
        for (int cell = 0; cell < 3; ++cell) begin = line.find(',', begin) + 1;
        const double ratio = std::stod(line.substr(begin, line.find(',', begin) - begin));
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

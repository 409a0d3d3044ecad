// `mpirun -np 2 shakerbench run` against one process: the same files byte for byte; a rank
// killed mid-run loses only its point in progress, and one rank finishes the run from the
// checkpoints with the same files. Built and run only with SB_WITH_MPI.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "campaign_files.hpp"
#include "cli_helpers.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sb::test;

/// mpirun as root in a container: allowed as root, more ranks than slots allowed, no binding
/// (the test shares the cores with whatever else runs), shared memory without the kernel's
/// single-copy mechanism (containers usually forbid it).
std::string mpirun(int ranks) {
    return "OMPI_MCA_btl_vader_single_copy_mechanism=none " + std::string(SB_MPIEXEC) +
           " --allow-run-as-root --oversubscribe --bind-to none -np " + std::to_string(ranks) +
           " " + SB_CLI;
}

/// Two sweeps (two levels) of 30 real particles, three frequencies each (and those the grid
/// refinement adds), with the steady windows' series.
fs::path write_campaign(const fs::path& dir) {
    return write_edited_h0(dir, "two-sweeps.toml",
                           {{"levels_g", "levels_g = [1.5, 3.0]"},
                            {"count = 7", "count = 3"},
                            {"count = 120", "count = 30"},
                            {"max_overlap_fraction", "max_overlap_fraction = 0.05"},
                            {"max_periods", "max_periods = 14"},
                            {"window_periods", "window_periods = 3"},
                            {"transient_periods", "transient_periods = 1"},
                            {"series = false", "series = true"}});
}

/// provenance.toml without the lines that say how the run was made (date, ranks, threads,
/// command).
std::string provenance_results(const fs::path& dir) {
    std::istringstream in(file_text(dir / "provenance.toml"));
    std::string kept;
    for (std::string line; std::getline(in, line);) {
        bool how = false;
        for (const char* key : {"date = ", "ranks = ", "threads = ", "command = "}) {
            how = how || line.rfind(key, 0) == 0;
        }
        if (!how) kept += line + "\n";
    }
    return kept;
}

/// Every file of `expected` equals the one of `actual` with the same name, and `actual` has
/// no other file; the provenance without how the run was made, the plot script (it names its
/// directory) left out.
void expect_same_files(const fs::path& expected, const fs::path& actual) {
    std::vector<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(expected)) {
        if (!entry.is_regular_file()) continue;
        const auto name = fs::relative(entry.path(), expected).string();
        names.push_back(name);
        if (name == "provenance.toml" || name == "plots/plots.gp") continue;
        EXPECT_TRUE(file_text(entry.path()) == file_text(actual / name)) << name << " differs";
    }
    std::vector<std::string> others;
    for (const auto& entry : fs::recursive_directory_iterator(actual)) {
        if (entry.is_regular_file()) others.push_back(fs::relative(entry.path(), actual).string());
    }
    std::sort(names.begin(), names.end());
    std::sort(others.begin(), others.end());
    EXPECT_EQ(names, others);
    EXPECT_EQ(provenance_results(expected), provenance_results(actual));
    for (const char* name : {"points.csv", "control.csv", "damping.csv", "frf.uff",
                             "checkpoints/H-0_1.5g.txt", "checkpoints/H-0_3g.txt"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    }
}

/// The number of finished points a sweep's checkpoint holds (0 while it has none).
int points_done(const fs::path& checkpoint) {
    const std::regex done("points_done ([0-9]+)\n");
    const std::string text = file_text(checkpoint);
    std::smatch match;
    return std::regex_search(text, match, done) ? std::stoi(match[1]) : 0;
}

TEST(CliMpi, TwoRanksGiveTheFilesOfOneProcessAndAKilledRankLosesOnlyItsPointInProgress) {
    const auto dir = temp_dir("mpi-" + std::to_string(getpid()));
    const auto config = write_campaign(dir);
    const auto one = dir / "one-process";
    const auto r = run("run " + config.string() + " --out " + one.string() + " -j 1 -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;

    // mpirun -np 2: each rank one sweep, rank 0 writes the files.
    const auto two = dir / "two-ranks";
    const auto m = run_command(mpirun(2) + " run " + config.string() + " --out " + two.string() +
                               " -j 1 2>&1");
    ASSERT_EQ(m.exit_code, 0) << m.output;
    EXPECT_NE(m.output.find("rank 1 of 2: pid"), std::string::npos) << m.output;
    EXPECT_NE(m.output.find("sweeps run per rank: 1 1 (2 ranks x 1 threads)"), std::string::npos)
        << m.output;
    expect_same_files(one, two);
    EXPECT_NE(file_text(two / "provenance.toml").find("ranks = 2\nthreads = 1\n"),
              std::string::npos);

    // Again, and kill rank 1 once both sweeps have checkpointed a point: mpirun ends the run.
    const auto killed = dir / "killed";
    const auto log = dir / "killed.log";
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        const std::string command = mpirun(2) + " run " + config.string() + " --out " +
                                    killed.string() + " -j 1 >" + log.string() + " 2>&1";
        execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    const std::regex rank1("rank 1 of 2: pid ([0-9]+)");
    pid_t rank1_pid = 0;
    bool killed_mid_run = false;
    bool run_ended = false;
    int status = 0;
    // Polled until both sweeps have a point in their checkpoints (a sweep may be several
    // points ahead of the other by then) or the run has ended without that moment being seen.
    while (!killed_mid_run && !run_ended) {
        std::smatch match;
        const std::string output = file_text(log);
        if (rank1_pid == 0 && std::regex_search(output, match, rank1)) {
            rank1_pid = static_cast<pid_t>(std::stol(match[1]));
        }
        const bool both = points_done(killed / "checkpoints" / "H-0_1.5g.txt") >= 1 &&
                          points_done(killed / "checkpoints" / "H-0_3g.txt") >= 1;
        if (rank1_pid != 0 && both) {
            kill(rank1_pid, SIGKILL);
            killed_mid_run = true;
        } else {
            run_ended = waitpid(child, &status, WNOHANG) == child;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
    }
    if (!run_ended) waitpid(child, &status, 0);
    ASSERT_TRUE(killed_mid_run) << file_text(log);
    EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << file_text(log);
    ASSERT_FALSE(fs::exists(killed / "points.csv")) << "killed too late";

    // One rank finishes the run from the checkpoints: the same files.
    const auto resumed = run_command(mpirun(1) + " run " + config.string() + " --out " +
                                     killed.string() + " -j 1 2>&1");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    const std::regex taken("([0-9]+) taken from checkpoints");
    std::smatch match;
    ASSERT_TRUE(std::regex_search(resumed.output, match, taken)) << resumed.output;
    EXPECT_GE(std::stoi(match[1]), 2) << resumed.output;
    expect_same_files(one, killed);
}

/// calibration.toml without the lines that say how the run went (command, wall time,
/// simulations rather than cache hits).
std::string calibration_results(const fs::path& dir) {
    std::istringstream in(file_text(dir / "calibration.toml"));
    std::string kept;
    for (std::string line; std::getline(in, line);) {
        bool how = false;
        for (const char* key : {"command = ", "wall_time_s = ", "simulations = "}) {
            how = how || line.rfind(key, 0) == 0;
        }
        if (!how) kept += line + "\n";
    }
    return kept;
}

/// evaluations.csv without its last two columns (the simulation's wall time, the error).
std::string evaluations_without_times(const fs::path& dir) {
    std::istringstream in(file_text(dir / "evaluations.csv"));
    std::string kept;
    for (std::string line; std::getline(in, line);) {
        const auto error = line.rfind(',');
        const auto wall = line.rfind(',', error - 1);
        kept += line.substr(0, wall) + line.substr(error) + "\n";
    }
    return kept;
}

TEST(CliMpi, TwoRanksShareACalibrationsEvaluationsAndFindWhatOneProcessFinds) {
    const auto dir = temp_dir("mpi-calibrate-" + std::to_string(getpid()));
    const auto config = write_rigid_campaign(dir);
    const auto measured = dir / "measured";
    ASSERT_EQ(run("run " + config.string() + " --out " + measured.string() + " -q").exit_code, 0);
    const std::string calibrate =
        " calibrate " + config.string() + " --measured " + measured.string() +
        " --free structure.damping.default_ratio=0.002:0.02"
        " --free structure.beam.youngs_modulus_pa=60e9:80e9 --mode surrogate --budget 9 -j 1";
    const auto one = dir / "one-process";
    const auto r = run(calibrate.substr(1) + " --out " + one.string() + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;

    // Two ranks: the cache and the search on rank 0, the simulations on both.
    const auto two = dir / "two-ranks";
    const auto m = run_command(mpirun(2) + calibrate + " --out " + two.string() + " 2>&1");
    ASSERT_EQ(m.exit_code, 0) << m.output;
    const std::regex per_rank("evaluations run per rank: ([0-9]+) ([0-9]+) \\(2 ranks");
    std::smatch match;
    ASSERT_TRUE(std::regex_search(m.output, match, per_rank)) << m.output;
    EXPECT_GT(std::stoi(match[1]), 0) << m.output;
    EXPECT_GT(std::stoi(match[2]), 0) << m.output;
    EXPECT_EQ(calibration_results(one), calibration_results(two));
    // calibrated.toml's first line is the command, which names the output folder.
    const auto config_part = [](const fs::path& d) {
        const auto text = file_text(d / "calibrated.toml");
        return text.substr(text.find('\n'));
    };
    EXPECT_EQ(config_part(one), config_part(two));
    EXPECT_EQ(evaluations_without_times(one), evaluations_without_times(two));
    EXPECT_NE(file_text(two / "calibration.toml").find("simulations = 14\n"), std::string::npos);

    // Run again on two ranks: everything from rank 0's cache, nothing handed out.
    const auto again = run_command(mpirun(2) + calibrate + " --out " + two.string() + " 2>&1");
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find("evaluations run per rank: 0 0 (2 ranks"), std::string::npos)
        << again.output;
    EXPECT_EQ(calibration_results(one), calibration_results(two));
}

/// diagnosis.toml without the lines that say how it was made (command, wall time).
std::string diagnosis_results(const fs::path& dir) {
    std::istringstream in(file_text(dir / "diagnosis.toml"));
    std::string kept;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("command = ", 0) != 0 && line.rfind("wall_time_s = ", 0) != 0) {
            kept += line + "\n";
        }
    }
    return kept;
}

TEST(CliMpi, TwoRanksShareTheSweepsAndDriftEvaluationsOfADiagnosisAndSayWhatOneProcessSays) {
    const auto dir = temp_dir("mpi-diagnose-" + std::to_string(getpid()));
    const auto config = write_rigid_campaign(dir);
    // Three levels, measured with more damping than the config says.
    const std::string levels =
        " --set 'campaign.levels_g=[1.0, 2.0, 3.0]' --set campaign.frequencies.count=9"
        " --set campaign.frequencies.low_ratio=0.96 --set campaign.frequencies.high_ratio=1.04";
    const auto measured = dir / "measured";
    ASSERT_EQ(run("run " + config.string() + levels +
                  " --set structure.damping.default_ratio=0.008 --out " + measured.string() + " -q")
                  .exit_code,
              0);
    const std::string diagnose = " diagnose " + config.string() + levels + " --measured " +
                                 measured.string() +
                                 " --drift structure.damping.default_ratio=0.002:0.02"
                                 " --mode surrogate --budget 8 -j 1";
    const auto one = dir / "one-process";
    const auto r = run(diagnose.substr(1) + " --out " + one.string() + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;

    // Two ranks: the baseline's three sweeps and the drift calibrations' simulations handed
    // out to both.
    const auto two = dir / "two-ranks";
    const auto m = run_command(mpirun(2) + diagnose + " --out " + two.string() + " 2>&1");
    ASSERT_EQ(m.exit_code, 0) << m.output;
    const std::regex per_rank(
        "sweeps run per rank: ([0-9]+) ([0-9]+); evaluations run per rank: ([0-9]+) ([0-9]+) "
        "\\(2 ranks");
    std::smatch match;
    ASSERT_TRUE(std::regex_search(m.output, match, per_rank)) << m.output;
    // The three sweeps of a linear bench take milliseconds: whichever rank asks first may
    // run them all. The drift evaluations, a batch at a time, reach both.
    EXPECT_EQ(std::stoi(match[1]) + std::stoi(match[2]), 3) << m.output;
    EXPECT_GT(std::stoi(match[3]), 0) << m.output;
    EXPECT_GT(std::stoi(match[4]), 0) << m.output;
    EXPECT_NE(m.output.find("mismatch beyond the noise: H-0 damping ratio"), std::string::npos)
        << m.output;
    EXPECT_EQ(diagnosis_results(one), diagnosis_results(two));
    EXPECT_NE(diagnosis_results(two).find("[[drift]]"), std::string::npos);
}

TEST(CliMpi, TwoRanksShareACharacterisationsRunsAndWriteTheTableOfOneProcess) {
    const auto dir = temp_dir("mpi-characterize-" + std::to_string(getpid()));
    // The golden 30-particle bed: two frequencies and two fillings at one level, short runs.
    const std::string characterize =
        " characterize " + std::string(SB_SOURCE_DIR) +
        "/tests/bench/golden/small-h0.toml --levels-g 0.5 --frequency-count 2 --seeds 2"
        " --max-periods 12 --window-periods 3 --transient-periods 1 -j 1 --energy";
    const auto one = dir / "one-process";
    const auto r = run(characterize.substr(1) + " --out " + one.string() + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto two = dir / "two-ranks";
    const auto m = run_command(mpirun(2) + characterize + " --out " + two.string() + " 2>&1");
    ASSERT_EQ(m.exit_code, 0) << m.output;
    const std::regex per_rank("runs per rank: ([0-9]+) ([0-9]+) \\(2 ranks");
    std::smatch match;
    ASSERT_TRUE(std::regex_search(m.output, match, per_rank)) << m.output;
    EXPECT_EQ(std::stoi(match[1]) + std::stoi(match[2]), 4) << m.output;
    EXPECT_GT(std::stoi(match[2]), 0) << m.output;
    EXPECT_EQ(characterization_without_command(one), characterization_without_command(two));
    EXPECT_NE(characterization_without_command(two).find("\npd,H-0,0.5,"), std::string::npos);
    // Where the energy goes, the same from the ranks.
    for (const char* name : {"characterization_energy.csv", "energy_spectrum.csv"}) {
        EXPECT_EQ(without_command(file_text(one / name)), without_command(file_text(two / name)))
            << name;
    }

    // Rank 0 kept each run as it came in: with two of the four forgotten, the ranks run those
    // two only, and the table is the same.
    std::vector<fs::path> stored;
    for (const auto& entry : fs::directory_iterator(two / "results"))
        stored.push_back(entry.path());
    ASSERT_EQ(stored.size(), 4u);
    std::sort(stored.begin(), stored.end());
    fs::remove(stored[0]);
    fs::remove(stored[3]);
    const auto again = run_command(mpirun(2) + characterize + " --out " + two.string() + " 2>&1");
    ASSERT_EQ(again.exit_code, 0) << again.output;
    ASSERT_TRUE(std::regex_search(again.output, match, per_rank)) << again.output;
    EXPECT_EQ(std::stoi(match[1]) + std::stoi(match[2]), 2) << again.output;
    EXPECT_NE(again.output.find("2 of them taken from the store"), std::string::npos)
        << again.output;
    EXPECT_EQ(characterization_without_command(one), characterization_without_command(two));
}

}  // namespace

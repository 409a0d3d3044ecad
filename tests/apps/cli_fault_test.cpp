// Faults during long runs, through the shakerbench executable: hard kills at random moments, a
// full disk, an output folder that cannot be written, damaged checkpoints. Each must end in a
// clean error (exit code, the file named) or a resumed run whose files equal an uninterrupted
// one's; never in lost or silently wrong results.
#include <fcntl.h>
#include <grp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "campaign_files.hpp"
#include "cli_helpers.hpp"

namespace {

using namespace sb::test;
namespace fs = std::filesystem;

/// `shakerbench ARGUMENTS` in the background, its output to `log`.
pid_t start_in_background(const std::vector<std::string>& arguments, const fs::path& log) {
    std::vector<char*> argv{const_cast<char*>(SB_CLI)};
    for (const auto& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t child = fork();
    if (child == 0) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            dup2(fd, STDOUT_FILENO);
            dup2(fd, STDERR_FILENO);
        }
        execv(SB_CLI, argv.data());
        _exit(127);
    }
    return child;
}

/// `shakerbench run CONFIG --out OUT -j 1 -q` in the background, its output to `log`.
pid_t start_run(const fs::path& config, const fs::path& out, const fs::path& log) {
    return start_in_background({"run", config.string(), "--out", out.string(), "-j", "1", "-q"},
                               log);
}

/// Like start_run, its output to the pipe `*output` reads instead of a file (a file could not
/// take the message of a run whose file size limit is reached), and with SIGXFSZ ignored, so a
/// write past that limit fails with EFBIG as a write to a full disk fails with ENOSPC. With
/// `user`, the run has that user's ids.
pid_t start_run_into_pipe(const fs::path& config, const fs::path& out, int* output,
                          std::optional<uid_t> user = std::nullopt) {
    int ends[2];
    if (::pipe(ends) != 0) return -1;
    const pid_t child = fork();
    if (child == 0) {
        ::signal(SIGXFSZ, SIG_IGN);
        if (user &&
            (::setgroups(0, nullptr) != 0 || ::setgid(*user) != 0 || ::setuid(*user) != 0)) {
            _exit(126);
        }
        dup2(ends[1], STDOUT_FILENO);
        dup2(ends[1], STDERR_FILENO);
        ::close(ends[0]);
        ::close(ends[1]);
        execl(SB_CLI, SB_CLI, "run", config.c_str(), "--out", out.c_str(), "-j", "1", "-q",
              static_cast<char*>(nullptr));
        _exit(127);
    }
    ::close(ends[1]);
    *output = ends[0];
    return child;
}

/// Everything left to read from `fd`, which is then closed.
std::string read_all(int fd) {
    std::string text;
    char buffer[4096];
    ssize_t n = 0;
    while ((n = ::read(fd, buffer, sizeof buffer)) > 0) text.append(buffer, n);
    ::close(fd);
    return text;
}

/// The finished points a checkpoint records; -1 when there is none yet.
int points_done(const fs::path& checkpoint) {
    const std::string text = file_text(checkpoint);
    const auto at = text.find("\npoints_done ");
    return at == std::string::npos ? -1 : std::atoi(text.c_str() + at + 13);
}

/// Waits (at most a minute) until the checkpoint records at least `points` finished points.
bool wait_for_points(const fs::path& checkpoint, int points) {
    for (int i = 0; i < 12000; ++i) {
        if (points_done(checkpoint) >= points) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
}

/// The number in "N taken from checkpoints" of a run's summary line; -1 without one.
int taken_from_checkpoints(const std::string& output) {
    const auto at = output.find(" taken from checkpoints");
    if (at == std::string::npos) return -1;
    const auto begin = output.rfind(' ', at - 1);
    return std::atoi(output.c_str() + begin + 1);
}

/// Every file of `resumed` equals `whole`'s, byte for byte, and neither has a file the other
/// lacks; except the provenance (date, command) and the plot script (it names its directory).
void expect_same_recording(const fs::path& whole, const fs::path& resumed) {
    const auto names = [](const fs::path& dir) {
        std::set<std::string> out;
        for (const auto& entry : fs::recursive_directory_iterator(dir)) {
            if (!entry.is_regular_file()) continue;
            const auto name = fs::relative(entry.path(), dir).string();
            if (name != "provenance.toml" && name != "plots/plots.gp") out.insert(name);
        }
        return out;
    };
    const std::set<std::string> expected = names(whole);
    EXPECT_EQ(names(resumed), expected);
    for (const auto& name : expected) {
        EXPECT_EQ(file_text(whole / name), file_text(resumed / name)) << name;
    }
    EXPECT_TRUE(expected.count("checkpoints/H-0_2g.txt") == 1 && expected.count("points.csv") == 1);
}

/// A tmpfs of its own at `dir` for one test, unmounted at the end however the test ends.
class Tmpfs {
  public:
    /// SB_TEST_NO_MOUNT=1 leaves `dir` a plain folder, to try the tests' ways without a mount
    /// where mounting works.
    explicit Tmpfs(fs::path dir) : dir_(std::move(dir)) {
        fs::create_directories(dir_);
        const char* no_mount = std::getenv("SB_TEST_NO_MOUNT");
        if (no_mount != nullptr && std::string(no_mount) == "1") {
            error_ = "SB_TEST_NO_MOUNT=1";
            return;
        }
        mounted_ = ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, kOptions) == 0;
        if (!mounted_) error_ = std::strerror(errno);
    }
    ~Tmpfs() {
        if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    }
    Tmpfs(const Tmpfs&) = delete;
    Tmpfs& operator=(const Tmpfs&) = delete;
    [[nodiscard]] bool mounted() const { return mounted_; }
    [[nodiscard]] const std::string& error() const { return error_; }
    /// Read-only, or writable again.
    bool set_read_only(bool read_only) {
        unsigned long flags = MS_REMOUNT;
        if (read_only) flags |= MS_RDONLY;
        return ::mount("tmpfs", dir_.c_str(), "tmpfs", flags, kOptions) == 0;
    }

  private:
    /// Room for a whole small campaign (about 100 kB) several times over.
    static constexpr const char* kOptions = "size=4m,mode=0755";
    fs::path dir_;
    bool mounted_ = false;
    std::string error_;
};

#define SKIP_UNLESS_MOUNTED(tmpfs)                                                      \
    if (!(tmpfs).mounted()) {                                                           \
        GTEST_SKIP() << "no tmpfs of its own (mounting needs root with CAP_SYS_ADMIN; " \
                        "AWriteFailingMidRun... covers a failing write without one): "  \
                     << (tmpfs).error();                                                \
    }

/// Fills the file system holding `file` until it has no space left.
void fill_disk(const fs::path& file) {
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0) << std::strerror(errno);
    const std::string block(1 << 16, 'x');
    while (::write(fd, block.data(), block.size()) > 0) {
    }
    // The last pages a short write left.
    while (::write(fd, block.data(), 1) > 0) {
    }
    ::close(fd);
}

/// When an uninterrupted run reached each stage, in seconds from its start: [k] when its
/// checkpoint first recorded k finished points, the last entry when the run ended.
std::vector<double> run_timeline(const fs::path& config, const fs::path& out, const fs::path& log) {
    const auto started = std::chrono::steady_clock::now();
    const auto since = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    };
    const pid_t child = start_run(config, out, log);
    std::vector<double> at;
    int status = 0;
    while (waitpid(child, &status, WNOHANG) == 0) {
        const int done = points_done(out / "checkpoints" / "H-0_2g.txt");
        while (static_cast<int>(at.size()) <= done) at.push_back(since());
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    at.push_back(since());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << file_text(log);
    return at;
}

TEST(CliFaults, TwentyHardKillsAtRandomMomentsThenARunToTheEndGiveTheUninterruptedFiles) {
    const auto dir = temp_dir("kills-" + std::to_string(getpid()));
    const auto config = write_small_campaign(dir);
    const auto whole = dir / "whole";
    const std::vector<double> at = run_timeline(config, whole, dir / "whole.log");
    ASSERT_GE(at.size(), 3u);

    // Runs killed at random moments of three kinds, in turn: one after a random part (up to
    // one and a half times) of the uninterrupted run's first point (start-up, the bed's
    // settling, the first steps), and two after the run has moved the campaign on by one
    // point, a random part of the next point later: inside it, or while its checkpoint or the
    // recording's files are written. Timed from the run's own progress, not from the timeline
    // alone, so a host busier or idler than when the timeline was taken still spreads the kills
    // over the campaign instead of letting one run finish it.
    const auto resumed = dir / "resumed";
    const auto checkpoint = resumed / "checkpoints" / "H-0_2g.txt";
    std::mt19937 random(19);
    std::uniform_real_distribution<double> fraction(0.0, 1.5);
    std::uniform_real_distribution<double> within(0.0, 1.0);
    using Clock = std::chrono::steady_clock;
    const auto seconds_since = [](Clock::time_point t) {
        return std::chrono::duration<double>(Clock::now() - t).count();
    };
    int killed = 0;
    std::set<int> stages;  // finished points when a kill landed (-1: before the first checkpoint)
    for (int k = 0; k < 20; ++k) {
        const int done = points_done(checkpoint);
        const pid_t child = start_run(config, resumed, dir / "kill.log");
        ASSERT_GT(child, 0);
        const auto started = Clock::now();
        int status = 0;
        bool ended = false;
        // start-up or the first point (a resumed run's start-up is shorter than at[0], which
        // pours the bed)
        double delay_s = fraction(random) * (at[1] - at[0]);
        if (k % 3 != 0) {
            // until this run records a point more (or ends) ...
            while (points_done(checkpoint) <= done) {
                if (waitpid(child, &status, WNOHANG) == child) {
                    ended = true;
                    break;
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
            }
            // ... then a part of the next point as the timeline took it, stretched by how much
            // slower than the timeline this run came to here (start-up and that point)
            const std::size_t reached = static_cast<std::size_t>(done + 1);
            const std::size_t next = std::min(reached + 1, at.size() - 1);
            const double timeline_s =
                at[0] +
                (reached > 0 ? at[std::min(reached, at.size() - 1)] - at[reached - 1] : 0.0);
            const double slower = std::max(1.0, seconds_since(started) / timeline_s);
            delay_s = within(random) * (at[next] - at[next - 1]) * slower;
        }
        if (!ended) {
            std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
        }
        if (WIFSIGNALED(status)) {
            ++killed;
            stages.insert(points_done(checkpoint));
        } else {
            // Finished before its kill: a clean end is the only other outcome.
            ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
                << file_text(dir / "kill.log");
        }
    }
    std::string landed;
    for (const int stage : stages) landed += " " + std::to_string(stage);
    std::cout << killed << " of 20 runs killed, with finished points:" << landed << '\n';
    EXPECT_GE(killed, 5) << "most runs ended before their kill";
    EXPECT_GE(stages.size(), 3u) << "the kills landed at fewer than three stages";

    const auto again = run("run " + config.string() + " --out " + resumed.string() + " -j 1 -q");
    ASSERT_EQ(again.exit_code, 0) << again.output;
    expect_same_recording(whole, resumed);
}

/// `shakerbench characterize` of the golden bed (two levels, two frequencies, two fillings,
/// short runs, one thread, each run's progress saved after every period) into `out`: its
/// arguments.
std::vector<std::string> characterization_arguments(const fs::path& out) {
    return {"characterize",
            std::string(SB_SOURCE_DIR) + "/tests/bench/golden/small-h0.toml",
            "--out",
            out.string(),
            "--levels-g",
            "0.5,1",
            "--frequency-count",
            "2",
            "--seeds",
            "2",
            "--max-periods",
            "12",
            "--window-periods",
            "3",
            "--transient-periods",
            "1",
            "--checkpoint-seconds",
            "0",
            "-j",
            "1",
            "-q"};
}

/// Files in out/results whose name ends in `suffix`.
std::size_t results_ending_in(const fs::path& out, const std::string& suffix) {
    std::error_code error;
    std::size_t count = 0;
    for (auto it = fs::directory_iterator(out / "results", error);
         !error && it != fs::directory_iterator(); it.increment(error)) {
        const std::string name = it->path().filename().string();
        count += name.size() >= suffix.size() &&
                         name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0
                     ? 1
                     : 0;
    }
    return count;
}

/// Runs finished and stored.
std::size_t stored_runs(const fs::path& out) {
    return results_ending_in(out, ".txt") - results_ending_in(out, ".progress.txt");
}

TEST(CliFaults, AKilledCharacterisationResumesItsFinishedRunsToTheUninterruptedTable) {
    const auto dir = temp_dir("characterize-kills-" + std::to_string(getpid()));
    const auto whole = dir / "whole";
    const auto started = std::chrono::steady_clock::now();
    const pid_t first = start_in_background(characterization_arguments(whole), dir / "whole.log");
    ASSERT_GT(first, 0);
    int status = 0;
    waitpid(first, &status, 0);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << file_text(dir / "whole.log");
    const double whole_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    ASSERT_EQ(stored_runs(whole), 8u);

    // Killed at random moments of its second half until some runs, not all, are stored and
    // one run is cut short with its progress saved: what a kill leaves is resumed, never
    // rerun, the run in progress continued, and the table is the uninterrupted one.
    const auto resumed = dir / "resumed";
    std::mt19937 random(23);
    std::uniform_real_distribution<double> fraction(0.3, 0.95);
    std::size_t kept = 0;
    std::size_t in_progress = 0;
    for (int k = 0; k < 10 && (kept == 0 || kept == 8 || in_progress == 0); ++k) {
        fs::remove_all(resumed);
        const pid_t child =
            start_in_background(characterization_arguments(resumed), dir / "kill.log");
        ASSERT_GT(child, 0);
        std::this_thread::sleep_for(std::chrono::duration<double>(fraction(random) * whole_s));
        kill(child, SIGKILL);
        waitpid(child, &status, 0);
        kept = stored_runs(resumed);
        in_progress = results_ending_in(resumed, ".progress.txt");
    }
    ASSERT_GT(kept, 0u) << "no kill landed after the first run";
    ASSERT_LT(kept, 8u) << "no kill landed before the last run";
    ASSERT_EQ(in_progress, 1u) << "no kill landed inside a run (one thread: one run at a time)";
    std::string command;
    for (const auto& a : characterization_arguments(resumed)) command += a + " ";
    const auto again = run(command);
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_NE(again.output.find(std::to_string(kept) + " of them taken from the store"),
              std::string::npos)
        << again.output;
    EXPECT_EQ(characterization_without_command(resumed), characterization_without_command(whole));
    EXPECT_EQ(results_ending_in(resumed, ".progress.txt"), 0u);  // dropped as each run ended
}

TEST(CliFaults, AFullDiskStopsTheRunNamingTheFileAndARunWithSpaceResumesToTheSameFiles) {
    const auto dir = temp_dir("full-" + std::to_string(getpid()));
    Tmpfs disk(dir / "disk");
    SKIP_UNLESS_MOUNTED(disk);
    const auto config = write_small_campaign(dir);
    const auto whole = dir / "whole";
    const auto r = run("run " + config.string() + " --out " + whole.string() + " -j 1 -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;

    const auto out = dir / "disk" / "out";
    const auto checkpoint = out / "checkpoints" / "H-0_2g.txt";
    const pid_t child = start_run(config, out, dir / "full.log");
    ASSERT_GT(child, 0);
    const bool first_point = wait_for_points(checkpoint, 1);
    fill_disk(dir / "disk" / "filler");
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(first_point) << file_text(dir / "full.log");
    const std::string output = file_text(dir / "full.log");
    ASSERT_TRUE(WIFEXITED(status)) << output;
    EXPECT_EQ(WEXITSTATUS(status), 1) << output;
    // "shakerbench run: OUT/...: cannot be written (No space left on device); finished points
    // are kept in OUT/checkpoints: free space and run again to resume"
    EXPECT_NE(output.find("shakerbench run: " + out.string() + "/"), std::string::npos) << output;
    EXPECT_NE(output.find(": cannot be written (No space left on device)"), std::string::npos)
        << output;
    EXPECT_NE(output.find("finished points are kept in " + (out / "checkpoints").string() +
                          ": free space and run again to resume"),
              std::string::npos)
        << output;
    const int finished = points_done(checkpoint);
    EXPECT_GE(finished, 1);
    for (const auto& entry : fs::recursive_directory_iterator(out)) {
        EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
    }

    fs::remove(dir / "disk" / "filler");
    const auto again = run("run " + config.string() + " --out " + out.string() + " -j 1 -q");
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_EQ(taken_from_checkpoints(again.output), finished) << again.output;
    expect_same_recording(whole, out);
}

// The same fault without a mount (containers often forbid one): after the first point, the
// running process's file size limit drops to zero (prlimit), so its next write fails as on a
// full disk, with EFBIG instead of ENOSPC. Runs wherever the test runs.
TEST(CliFaults, AWriteFailingMidRunStopsItNamingTheFileAndARunWithRoomResumesToTheSameFiles) {
    const auto dir = temp_dir("fsize-" + std::to_string(getpid()));
    const auto config = write_small_campaign(dir);
    const auto whole = dir / "whole";
    const auto r = run("run " + config.string() + " --out " + whole.string() + " -j 1 -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;

    const auto out = dir / "out";
    const auto checkpoint = out / "checkpoints" / "H-0_2g.txt";
    int pipe_end = -1;
    const pid_t child = start_run_into_pipe(config, out, &pipe_end);
    ASSERT_GT(child, 0);
    const bool first_point = wait_for_points(checkpoint, 1);
    const rlimit none{0, 0};
    const int limited = ::prlimit(child, RLIMIT_FSIZE, &none, nullptr);
    const int limit_error = errno;
    const std::string output = read_all(pipe_end);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(first_point) << output;
    ASSERT_EQ(limited, 0) << std::strerror(limit_error);
    ASSERT_TRUE(WIFEXITED(status)) << output;
    EXPECT_EQ(WEXITSTATUS(status), 1) << output;
    EXPECT_NE(output.find("shakerbench run: " + out.string() + "/"), std::string::npos) << output;
    EXPECT_NE(output.find(": cannot be written (File too large)"), std::string::npos) << output;
    EXPECT_NE(output.find("raise the file-size limit (ulimit -f)"), std::string::npos) << output;
    EXPECT_NE(output.find("finished points are kept in " + (out / "checkpoints").string()),
              std::string::npos)
        << output;
    const int finished = points_done(checkpoint);
    EXPECT_GE(finished, 1);
    EXPECT_LT(finished, 7) << "the run ended before its limit was set";
    for (const auto& entry : fs::recursive_directory_iterator(out)) {
        EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
    }

    const auto again = run("run " + config.string() + " --out " + out.string() + " -j 1 -q");
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_EQ(taken_from_checkpoints(again.output), finished) << again.output;
    expect_same_recording(whole, out);
}

// A read-only file system (a tmpfs remounted read-only) where mounting is permitted; else the
// folder's permissions: removed for an ordinary user, and for root (whom permissions do not
// stop) the refused run has the ids of the user "nobody", to whom the folder does not belong.
TEST(CliFaults, AnUnwritableOutputFolderIsRefusedBeforeRunningAndItsCheckpointsStay) {
    const auto dir = temp_dir("read-only-" + std::to_string(getpid()));
    Tmpfs disk(dir / "disk");
    const auto config = write_small_campaign(dir);
    const auto whole = dir / "whole";
    const auto r = run("run " + config.string() + " --out " + whole.string() + " -j 1 -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;

    // A run killed after its first point, then its folder made unwritable.
    const auto out = dir / "disk" / "out";
    const auto checkpoint = out / "checkpoints" / "H-0_2g.txt";
    const pid_t child = start_run(config, out, dir / "ro.log");
    ASSERT_GT(child, 0);
    const bool first_point = wait_for_points(checkpoint, 1);
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(first_point) << file_text(dir / "ro.log");
    const std::string kept = file_text(checkpoint);

    const std::string command = "run " + config.string() + " --out " + out.string() + " -j 1 -q";
    constexpr uid_t kNobody = 65534;
    const auto write_bits =
        fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write;
    Result refused;
    std::string reason;
    if (disk.mounted()) {
        ASSERT_TRUE(disk.set_read_only(true)) << std::strerror(errno);
        reason = "Read-only file system";
        refused = run(command);
    } else if (::geteuid() != 0) {
        fs::permissions(out / "checkpoints", write_bits, fs::perm_options::remove);
        reason = "Permission denied";
        refused = run(command);
    } else {
        std::cout << "no tmpfs (" << disk.error() << "): the refused run as user " << kNobody
                  << '\n';
        int pipe_end = -1;
        const pid_t as_nobody = start_run_into_pipe(config, out, &pipe_end, kNobody);
        ASSERT_GT(as_nobody, 0);
        refused.output = read_all(pipe_end);
        waitpid(as_nobody, &status, 0);
        refused.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        reason = "Permission denied";
    }
    EXPECT_EQ(refused.exit_code, 1) << refused.output;
    EXPECT_NE(refused.output.find("shakerbench run: " + (out / "checkpoints").string() +
                                  ": cannot be written (" + reason + ")"),
              std::string::npos)
        << refused.output;
    EXPECT_NE(refused.output.find("make it writable and run again to resume"), std::string::npos)
        << refused.output;
    EXPECT_EQ(file_text(checkpoint), kept);

    if (disk.mounted()) {
        ASSERT_TRUE(disk.set_read_only(false)) << std::strerror(errno);
    } else {
        fs::permissions(out / "checkpoints", fs::perms::owner_write, fs::perm_options::add);
    }
    const auto again = run(command);
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_GE(taken_from_checkpoints(again.output), 1) << again.output;
    expect_same_recording(whole, out);
}

TEST(CliFaults, ADamagedCheckpointIsRefusedWithExitTwoNamingItAndTheWayOut) {
    const auto dir = temp_dir("damaged-" + std::to_string(getpid()));
    const auto config = write_rigid_campaign(dir);
    const auto out = dir / "out";
    const std::string command = "run " + config.string() + " --out " + out.string() + " -q";
    const auto first = run(command);
    ASSERT_EQ(first.exit_code, 0) << first.output;
    const auto checkpoint = out / "checkpoints" / "H-0_1g.txt";
    const std::string good = file_text(checkpoint);
    const std::string points = file_text(out / "points.csv");

    std::string changed = good;
    const auto digit = changed.find_first_of("123456789", changed.find("\nrow "));
    ASSERT_NE(digit, std::string::npos);
    changed[digit] = changed[digit] == '9' ? '8' : static_cast<char>(changed[digit] + 1);
    const std::pair<std::string, std::string> damages[] = {
        {good.substr(0, good.size() / 2), "truncated"}, {changed, "corrupted"}};
    for (const auto& [text, what] : damages) {
        std::ofstream(checkpoint, std::ios::binary) << text;
        const auto r = run(command);
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_NE(r.output.find(checkpoint.string() + ":"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("delete " + checkpoint.string()), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("--restart"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("nothing was simulated"), std::string::npos) << r.output;
        EXPECT_EQ(file_text(out / "points.csv"), points);
    }

    // Another config's checkpoint, intact: refused as such.
    std::ofstream(checkpoint, std::ios::binary) << good;
    const auto foreign = run(command + " --set dampers.pd.contact.sliding_friction=0.45");
    EXPECT_EQ(foreign.exit_code, 2) << foreign.output;
    EXPECT_NE(foreign.output.find("was written by another config"), std::string::npos)
        << foreign.output;

    // The way out the message gives: delete the damaged file, and that sweep is computed again.
    std::ofstream(checkpoint, std::ios::binary) << changed;
    fs::remove(checkpoint);
    const auto again = run(command);
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_EQ(taken_from_checkpoints(again.output), 0) << again.output;
    EXPECT_EQ(file_text(out / "points.csv"), points);
}

}  // namespace

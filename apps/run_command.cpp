// `shakerbench run`: runs or resumes a campaign and writes its recording directory.
#include "run_command.hpp"

#include <omp.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>

#include "bench/campaign.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "dem/solver.hpp"
#include "distributed/campaign.hpp"
#include "distributed/session.hpp"
#include "identification/file_error.hpp"
#include "load_config.hpp"

namespace sb::apps {
namespace {

struct RunOptions {
    std::string config;
    std::string out_dir;
    int threads = 0;
    bool quiet = false;
    bool restart = false;
    std::vector<std::string> overrides;
    std::string command_line;
};

/// What became of the finished points when the run could not write, and the way out.
std::string kept_points(const std::filesystem::path& out_dir, const std::string& remedy) {
    const auto dir = out_dir / "checkpoints";
    std::error_code error;
    bool any = false;
    for (auto it = std::filesystem::directory_iterator(dir, error);
         !error && it != std::filesystem::directory_iterator(); it.increment(error)) {
        any = any || it->path().extension() == ".txt";
    }
    if (!any) return "no point was finished: " + remedy + " and run again";
    return "finished points are kept in " + dir.string() + ": " + remedy +
           " and run again to resume";
}

/// A rank other than 0: runs the sweeps rank 0 hands out; rank 0 reports everything else.
int serve(distributed::Session& session, const bench::CampaignConfig& config,
          const RunOptions& options) {
    try {
        distributed::serve_campaign(*session.transport(), config, {}, options.threads);
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "shakerbench run (" << session.describe() << "): " << e.what() << '\n';
        session.abort(config::kExitFailure);  // rank 0 would wait for this rank forever
    }
}

int run(const RunOptions& options) {
    std::optional<distributed::Session> session;
    try {
        session.emplace();
    } catch (const std::exception& e) {
        std::cerr << "shakerbench run: " << e.what() << '\n';
        return config::kExitBadInput;
    }
    const bool root = session->rank() == 0;
    int exit_code = 0;
    // Every rank reads the config (the same file); rank 0 alone reports what is wrong with it.
    std::ostringstream silenced;
    const auto config = load_config_or_report(options.config, options.overrides, exit_code,
                                              root ? std::cerr : silenced);
    if (!config) {
        return exit_code;
    }
    if (session->size() > 1 && !options.quiet) {
        // One write per line: the ranks share mpirun's stderr, so pieces would interleave.
        std::cerr << session->describe() + ", " +
                         std::to_string(options.threads > 0 ? options.threads
                                                            : omp_get_max_threads()) +
                         " threads\n"
                  << std::flush;
    }
    if (!root) return serve(*session, *config, options);
    // Declared after the session: it releases the other ranks when the campaign cannot start.
    distributed::DistributedSweeps sweeps(session->transport(), options.threads);
    bench::CampaignRunOptions run;
    run.out_dir = options.out_dir.empty() ? std::filesystem::path("out") / config->name
                                          : std::filesystem::path(options.out_dir);
    run.threads = options.threads;
    run.progress = options.quiet ? nullptr : &std::cerr;
    run.config_text = options.config.empty() ? std::string(bench::builtin_config_text())
                                             : read_text_file(options.config);
    run.command_line = options.command_line;
    run.restart = options.restart;
    run.executor = session->size() > 1 ? &sweeps : nullptr;
    try {
        const auto summary = bench::run_campaign(*config, run);
        std::cout << "campaign " << config->name << ": " << summary.points << " points ("
                  << summary.converged << " converged, " << summary.limit_cycle
                  << " limit-cycle-2, " << summary.closest << " closest; " << summary.resumed_points
                  << " taken from checkpoints), " << summary.periods_simulated
                  << " periods simulated in " << std::fixed << std::setprecision(1)
                  << summary.wall_time_s << " s\n"
                  << "recording: " << run.out_dir.string() << '\n';
        if (session->size() > 1 && !options.quiet) {
            // One write, so that another stream's lines cannot cut it in pieces.
            std::string line = "sweeps run per rank:";
            for (const int n : sweeps.sweeps_per_rank()) line += ' ' + std::to_string(n);
            line += " (" + std::to_string(session->size()) + " ranks x " +
                    std::to_string(sweeps.threads()) + " threads)\n";
            std::cerr << line << std::flush;
        }
        return 0;
    } catch (const config::ConfigException& e) {
        std::cerr << e.what()
                  << "\nshakerbench run: the campaign cannot run; nothing was "
                     "simulated.\n";
        return config::kExitBadInput;
    } catch (const identification::FileError& e) {
        std::cerr << "shakerbench run: " << e.what() << '\n';
        return config::kExitBadInput;
    } catch (const bench::CheckpointError& e) {
        std::cerr << "shakerbench run: " << e.what() << "\nshakerbench run: that checkpoint cannot "
                  << "be resumed: delete " << e.file()
                  << " to compute its sweep again, or run again with --restart to start over.\n";
        return config::kExitBadInput;
    } catch (const FileWriteError& e) {
        // Not bad input: the same run succeeds once the disk has room or the folder is writable.
        std::cerr << "shakerbench run: " << e.what() << "; " << kept_points(run.out_dir, e.remedy())
                  << '\n';
        return config::kExitFailure;
    } catch (const std::filesystem::filesystem_error& e) {
        std::cerr << "shakerbench run: " << e.what() << "; "
                  << kept_points(run.out_dir, "remove the cause") << '\n';
        return config::kExitFailure;
    } catch (const dem::SimulationError& e) {
        std::cerr << "shakerbench run: simulation failed: " << e.what()
                  << "\nFinished points are kept in " << run.out_dir.string()
                  << "/checkpoints; fix the config and run again to resume.\n";
        return config::kExitFailure;
    } catch (const std::exception& e) {
        std::cerr << "shakerbench run: " << e.what() << '\n';
        return config::kExitFailure;
    }
}

}  // namespace

void register_run_command(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<RunOptions>();
    CLI::App* cmd = app.add_subcommand(
        "run",
        "Run the stepped-sine campaign of CONFIG (default: the built-in paper-000 H-0 "
        "campaign) into a recording directory. An interrupted run resumes from its "
        "checkpoints when run again with the same output directory. Under mpirun (a build "
        "with SB_WITH_MPI) the sweeps are shared among the ranks; rank 0 writes the files.");
    cmd->add_option("config", options->config, "campaign config (TOML)");
    cmd->add_option("-o,--out", options->out_dir,
                    "recording directory (default: out/<campaign name>)");
    cmd->add_option("-j,--threads", options->threads,
                    "sweeps run in parallel, per rank under mpirun (default: all cores)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("-q,--quiet", options->quiet, "no progress lines");
    add_set_option(*cmd, options->overrides);
    cmd->add_flag("--restart", options->restart,
                  "discard the checkpoints and settled beds in the output directory and start "
                  "over (needed when they were written by another config)");
    cmd->callback([options, &exit_code] {
        options->command_line = "shakerbench run";
        if (!options->config.empty()) options->command_line += " " + options->config;
        if (!options->out_dir.empty()) options->command_line += " --out " + options->out_dir;
        if (options->threads > 0) {
            options->command_line += " --threads " + std::to_string(options->threads);
        }
        options->command_line += overrides_text(options->overrides);
        if (options->restart) options->command_line += " --restart";
        exit_code = run(*options);
    });
}

}  // namespace sb::apps

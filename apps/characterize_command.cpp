// `shakerbench characterize`: the describing functions of a config's dampers.
#include "characterize_command.hpp"

#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "bench/characterization.hpp"
#include "bench/characterization_energy.hpp"
#include "bench/checkpoint_store.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "dem/solver.hpp"
#include "distributed/rounds.hpp"
#include "distributed/session.hpp"
#include "identification/file_error.hpp"
#include "load_config.hpp"

namespace sb::apps {
namespace {

struct CharacterizeArgs {
    std::string config;
    std::string out_dir;
    std::vector<double> levels_g;
    std::vector<double> frequencies_hz;
    int frequency_count = 0;
    int seeds = 3;
    std::string rotation = "mode";
    bench::SteadyStateOptions steady;
    int threads = 0;
    bool quiet = false;
    double progress_s = 60.0;
    double checkpoint_s = 120.0;
    bool energy = false;
    bool no_energy = false;
    bool restart = false;
    std::vector<std::string> overrides;
    std::string command_line;
};

std::string list_text(const std::vector<double>& values) {
    std::ostringstream out;
    for (std::size_t i = 0; i < values.size(); ++i) out << (i ? "," : "") << values[i];
    return out.str();
}

/// A rank other than 0: runs the grid's runs rank 0 hands out; rank 0 reports everything else.
int serve(distributed::Session& session, bench::CharacterizationWorker& worker, int threads) {
    try {
        distributed::serve_rounds(
            *session.transport(), 1,
            [&worker](const std::string& run, int /*threads*/) { return worker.run(run); },
            threads);
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "shakerbench characterize (" << session.describe() << "): " << e.what()
                  << '\n';
        session.abort(config::kExitFailure);  // rank 0 would wait for this rank forever
    }
}

int run(const CharacterizeArgs& args) {
    std::optional<distributed::Session> session;
    try {
        session.emplace();
    } catch (const std::exception& e) {
        std::cerr << "shakerbench characterize: " << e.what() << '\n';
        return config::kExitBadInput;
    }
    const bool root = session->rank() == 0;
    // Every rank reads the config (the same file); rank 0 alone reports what is wrong with it.
    std::ostringstream silenced;
    std::ostream& errors = root ? std::cerr : silenced;
    int exit_code = 0;
    const auto config = load_config_or_report(args.config, args.overrides, exit_code, errors);
    if (!config) return exit_code;
    const std::filesystem::path out_dir =
        args.out_dir.empty() ? std::filesystem::path("out") / (config->name + "-characterization")
                             : std::filesystem::path(args.out_dir);
    bench::CharacterizeOptions options;
    options.levels_g = args.levels_g;
    options.frequencies_hz = args.frequencies_hz;
    options.frequency_count = args.frequency_count;
    options.seeds = args.seeds;
    options.rotation = args.rotation == "mode";
    options.steady = args.steady;
    options.threads = args.threads;
    const bool energy = args.energy || (config->campaign.output.energy && !args.no_energy);
    if (energy) options.energy_layers = config->campaign.output.energy_layers;
    // Runs the config's output.energy stored with the energy serve a run without it.
    if (args.no_energy && config->campaign.output.energy) {
        options.stored_energy_layers = config->campaign.output.energy_layers;
    }
    options.command_line = args.command_line;
    // The runs and beds finished so far are kept in the output directory: an interrupted or
    // extended characterisation simulates only what is missing. Rank 0 alone writes it.
    bench::FileCheckpointStore store(out_dir);
    options.store = &store;
    options.restart = args.restart;
    if (!args.quiet && root) {
        options.progress = [](const std::string& line) { std::cerr << line << '\n' << std::flush; };
    }
    options.progress_interval_s = args.progress_s;
    options.checkpoint_interval_s = args.checkpoint_s;
    const int threads = args.threads > 0
                            ? args.threads
                            : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
    if (session->size() > 1 && !args.quiet) {
        // One write per line: the ranks share mpirun's stderr.
        std::cerr << session->describe() + ", " + std::to_string(threads) + " runs at a time\n"
                  << std::flush;
    }
    // Over several ranks every rank plans the grid (and rank 0 reports a config it cannot
    // characterise, the others end quietly with the same code).
    std::optional<bench::CharacterizationWorker> worker;
    if (session->size() > 1) {
        try {
            worker.emplace(*config, options);
        } catch (const config::ConfigException& e) {
            errors << e.what() << "\nshakerbench characterize: nothing was characterised.\n";
            return config::kExitBadInput;
        } catch (const std::exception& e) {
            errors << "shakerbench characterize: " << e.what() << '\n';
            return config::kExitFailure;
        }
    }
    if (!root) return serve(*session, *worker, threads);
    // Each run of the grid (a point on one filling) goes to whichever rank's thread is free;
    // every rank settles the beds its runs need. Declared after the session: it releases the
    // other ranks however the characterisation ends.
    distributed::DistributedRounds rounds(
        session->transport(), 1,
        [&worker](const std::string& run, int /*threads*/) { return worker->run(run); }, threads);
    if (session->size() > 1) {
        options.remote =
            [&rounds](const std::vector<std::string>& runs,
                      const std::function<void(std::size_t, const std::string&)>& on_result) {
                return rounds.run(runs, on_result);
            };
    }
    try {
        const bench::CharacterizeResult result = bench::characterize(*config, options);
        rounds.finish();
        if (session->size() > 1 && !args.quiet) {
            std::string line = "runs per rank:";
            for (const int n : rounds.evaluations_per_rank()) line += ' ' + std::to_string(n);
            line += " (" + std::to_string(session->size()) + " ranks x " + std::to_string(threads) +
                    " runs at a time)\n";
            std::cerr << line << std::flush;
        }
        std::filesystem::create_directories(out_dir);
        const auto file = out_dir / "characterization.csv";
        write_file_atomically(file, bench::characterization_csv_text(result.table));
        if (energy) {
            write_file_atomically(out_dir / "characterization_energy.csv",
                                  bench::bed_energy_csv_text(result));
            write_file_atomically(out_dir / "energy_spectrum.csv",
                                  bench::bed_spectrum_csv_text(result));
        }
        std::cout << "characterised " << result.table.rows.size() << " grid points (" << result.runs
                  << " runs over the fillings, " << result.resumed_runs
                  << " of them taken from the store, " << result.unsettled_runs << " not settled), "
                  << result.periods << " periods in " << std::fixed << std::setprecision(1)
                  << result.wall_time_s << " s\n"
                  << "characterisation: " << file.string() << '\n';
        return 0;
    } catch (const config::ConfigException& e) {
        std::cerr << e.what() << "\nshakerbench characterize: nothing was characterised.\n";
        return config::kExitBadInput;
    } catch (const identification::FileError& e) {
        std::cerr << "shakerbench characterize: " << e.what() << '\n';
        return config::kExitBadInput;
    } catch (const bench::CheckpointError& e) {
        std::cerr << "shakerbench characterize: " << e.what()
                  << "\nshakerbench characterize: that progress cannot be continued: delete "
                  << e.file()
                  << " to compute it from its start, or run again with --restart to start over.\n";
        return config::kExitBadInput;
    } catch (const FileWriteError& e) {
        // Not bad input: the same command succeeds once the disk has room or the folder is
        // writable, and resumes the runs stored before.
        std::cerr << "shakerbench characterize: " << e.what() << "; " << e.remedy()
                  << "; the runs finished before are kept in " << out_dir.string()
                  << "/results and resumed by the same command\n";
        return config::kExitFailure;
    } catch (const dem::SimulationError& e) {
        std::cerr << "shakerbench characterize: simulation failed: " << e.what()
                  << "\nFinished runs are kept in " << out_dir.string()
                  << "/results; fix the config and run again to resume.\n";
        return config::kExitFailure;
    } catch (const std::exception& e) {
        std::cerr << "shakerbench characterize: " << e.what() << '\n';
        return config::kExitFailure;
    }
}

}  // namespace

void register_characterize_command(CLI::App& app, int& exit_code) {
    auto args = std::make_shared<CharacterizeArgs>();
    CLI::App* cmd = app.add_subcommand(
        "characterize",
        "Characterise every DEM damper of CONFIG alone (no structure): its enclosure moved "
        "sinusoidally along the excitation direction with each arrangement's gravity and tilt, "
        "over a grid of levels and frequencies, on several fillings; writes the complex "
        "apparent mass, dissipated power, force harmonics and bed agitation to "
        "DIR/characterization.csv (docs/characterisation.md).");
    cmd->add_option("config", args->config, "campaign config (TOML)");
    cmd->add_option("-o,--out", args->out_dir,
                    "output directory (default: out/<campaign name>-characterization)");
    cmd->add_option("--levels-g", args->levels_g,
                    "RMS levels of the enclosure's acceleration [g], comma-separated (default: "
                    "campaign.levels_g)")
        ->delimiter(',');
    cmd->add_option("--frequencies-hz", args->frequencies_hz,
                    "frequencies [Hz], comma-separated (default: each arrangement's grid)")
        ->delimiter(',');
    cmd->add_option("--frequency-count", args->frequency_count,
                    "this many frequencies equally spaced over each arrangement's grid")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--seeds", args->seeds,
                    "fillings per grid point: campaign.seed, campaign.seed + 1, ... (default 3)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--rotation", args->rotation,
                    "mode: the point turns as in the driven mode (its shape at the point gives "
                    "the rotation per translation); none: translation only (default mode)")
        ->check(CLI::IsMember({"mode", "none"}));
    cmd->add_option("--transient-periods", args->steady.transient_periods,
                    "periods left out at the start (default 4)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--window-periods", args->steady.window_periods,
                    "periods per window of the steady-state test (default 8)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--tolerance", args->steady.tolerance,
                    "the last two windows' mean fundamentals agree within this fraction of a rigid "
                    "bed's force m |a1| (default 0.03)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--energy-tolerance", args->steady.energy_tolerance,
                    "also the bed's stored energy changes over the two windows by at most this "
                    "share of the walls' work over them (default 0: off)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--max-periods", args->steady.max_periods,
                    "budget of periods per grid point and filling (default 64)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("-j,--threads", args->threads,
                    "runs in parallel (default: all cores); the numbers do not depend on it")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("--energy", args->energy,
                  "also measure where the energy goes over the steady windows: dissipated power "
                  "per mechanism and per horizontal layer (output.energy_layers of them) in "
                  "DIR/characterization_energy.csv, the spectra of the bed's kinetic energy and "
                  "dissipated power in DIR/energy_spectrum.csv (as output.energy = true)");
    cmd->add_flag("--no-energy", args->no_energy,
                  "leave out where the energy goes even when the config's output.energy asks "
                  "for it: no per-contact energy ledger, about half of a dense bed's time; "
                  "runs stored with the energy are taken as they are")
        ->excludes("--energy");
    cmd->add_flag("-q,--quiet", args->quiet, "no progress lines");
    cmd->add_option("--progress-seconds", args->progress_s,
                    "seconds between the lines of a run still going: its periods so far and "
                    "their pace (default 60; 0: after every period)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--checkpoint-seconds", args->checkpoint_s,
                    "seconds between two saves of a run's progress in DIR/results (at the end of "
                    "a period; an interrupted run continues from its last save, giving the "
                    "numbers of an uninterrupted one; default 120; 0: after every period)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("--restart", args->restart,
                  "discard the runs and settled beds stored in the output directory for this "
                  "config and start over (by default a run already stored there is taken from "
                  "it, so an interrupted or extended characterisation simulates only what is "
                  "missing)");
    add_set_option(*cmd, args->overrides);
    cmd->callback([args, &exit_code] {
        std::string line = "shakerbench characterize";
        if (!args->config.empty()) line += " " + args->config;
        if (!args->out_dir.empty()) line += " --out " + args->out_dir;
        if (!args->levels_g.empty()) line += " --levels-g " + list_text(args->levels_g);
        if (!args->frequencies_hz.empty()) {
            line += " --frequencies-hz " + list_text(args->frequencies_hz);
        }
        if (args->frequency_count > 0) {
            line += " --frequency-count " + std::to_string(args->frequency_count);
        }
        line += " --seeds " + std::to_string(args->seeds) + " --rotation " + args->rotation;
        if (args->energy) line += " --energy";
        if (args->no_energy) line += " --no-energy";
        if (args->restart) line += " --restart";
        line += overrides_text(args->overrides);
        args->command_line = line;
        exit_code = run(*args);
    });
}

}  // namespace sb::apps

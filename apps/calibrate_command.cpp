// `shakerbench calibrate`: the free values of a config fitted to a measurement, within a budget
// of simulations, and the report of what the data identify.
#include "calibrate_command.hpp"

#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "correlation/calibration.hpp"
#include "distributed/rounds.hpp"
#include "distributed/session.hpp"
#include "identification/file_error.hpp"
#include "load_config.hpp"
#include "measured_options.hpp"

namespace sb::apps {
namespace {

struct CalibrateArgs {
    std::string config;
    std::string measured;
    std::vector<std::string> free;
    int budget = 30;
    std::string mode = "direct";
    std::string fidelity = "coupled";
    int characterization_frequencies = 3;
    std::string out_dir;
    int threads = 0;
    correlation::StatedUncertainty stated;
    bool quiet = false;
    std::vector<std::string> overrides;
    std::string command_line;
};

/// A rank other than 0: evaluates what rank 0 hands out; rank 0 reports everything else.
int serve(distributed::Session& session, const distributed::TextEvaluation& simulator,
          int threads) {
    try {
        distributed::serve_rounds(*session.transport(), threads, simulator);
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "shakerbench calibrate (" << session.describe() << "): " << e.what() << '\n';
        session.abort(config::kExitFailure);  // rank 0 would wait for this rank forever
    }
}

int run(const CalibrateArgs& args) {
    std::optional<distributed::Session> session;
    try {
        session.emplace();
    } catch (const std::exception& e) {
        std::cerr << "shakerbench calibrate: " << e.what() << '\n';
        return config::kExitBadInput;
    }
    const bool root = session->rank() == 0;
    // Every rank reads the config and the measurement (the same files); rank 0 alone reports
    // what is wrong with them.
    std::ostringstream silenced;
    std::ostream& errors = root ? std::cerr : silenced;
    int exit_code = 0;
    auto config = load_config_or_report(args.config, args.overrides, exit_code, errors);
    if (!config) return exit_code;
    try {
        const auto free = args.free.empty()
                              ? correlation::default_free_parameters(*config)
                              : correlation::parse_free_parameters(*config, args.free);
        const auto measurement = correlation::read_measurement(args.measured, args.stated);
        const std::filesystem::path out_dir =
            args.out_dir.empty() ? std::filesystem::path("out") / (config->name + "-calibrated")
                                 : std::filesystem::path(args.out_dir);
        correlation::CalibrationOptions options;
        options.search.mode = args.mode == "surrogate" ? correlation::SearchMode::surrogate
                                                       : correlation::SearchMode::direct;
        options.search.budget = args.budget;
        options.fidelity = args.fidelity == "two-fidelity" ? correlation::Fidelity::two_fidelity
                                                           : correlation::Fidelity::coupled;
        options.characterization_frequencies = args.characterization_frequencies;
        options.threads = args.threads;
        options.cache_dir = out_dir / "cache";
        const int threads =
            args.threads > 0 ? args.threads
                             : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
        const auto simulator =
            correlation::calibration_simulator(*config, measurement, free, options);
        if (session->size() > 1 && !args.quiet) {
            // One write per line: the ranks share mpirun's stderr.
            std::cerr << session->describe() + ", " + std::to_string(threads) + " threads\n"
                      << std::flush;
        }
        if (!root) return serve(*session, simulator, threads);
        // Rank 0 owns the cache and the search; each evaluation not in the cache runs on
        // whichever rank is free. Declared after the session: it releases the other ranks
        // when the calibration ends, however it ends.
        distributed::DistributedRounds rounds(session->transport(), threads, simulator);
        if (session->size() > 1) {
            options.remote = [&rounds](const std::vector<std::string>& inputs) {
                return rounds.run(inputs);
            };
        }
        if (!args.quiet) {
            std::cerr << "calibrating " << free.size() << " value(s) against "
                      << measurement.features.size() << " features of " << args.measured << " ("
                      << measurement.depth << "), "
                      << correlation::search_mode_name(options.search.mode) << " search, budget "
                      << args.budget << " evaluations";
            if (options.fidelity == correlation::Fidelity::two_fidelity) {
                std::cerr << " of the describing-function prediction (the damper characterised "
                             "on "
                          << args.characterization_frequencies
                          << " frequencies per level), corrected and confirmed coupled";
            }
            std::cerr << '\n';
            options.progress = [](const std::string& line) {
                std::cerr << line << '\n' << std::flush;
            };
        }
        const auto result = correlation::calibrate(*config, measurement, free, options);
        rounds.finish();
        correlation::write_calibration(out_dir, result, measurement, args.command_line);
        if (session->size() > 1 && !args.quiet) {
            std::string line = "evaluations run per rank:";
            for (const int n : rounds.evaluations_per_rank()) line += ' ' + std::to_string(n);
            line += " (" + std::to_string(session->size()) + " ranks x " + std::to_string(threads) +
                    " threads)\n";
            std::cerr << line << std::flush;
        }
        std::cout << "calibration " << config->name << ": ";
        if (result.fidelity == correlation::Fidelity::two_fidelity) {
            std::cout << result.low_fidelity_history.size() << " predicted evaluations ("
                      << result.low_fidelity_simulations << " simulated), " << result.simulations
                      << " coupled simulations, misfit ";
        } else {
            std::cout << result.outcome.evaluations << " evaluations (" << result.simulations
                      << " simulated), misfit ";
        }
        std::cout << std::setprecision(4) << result.start.misfit << " -> " << result.best.misfit
                  << '\n';
        for (std::size_t j = 0; j < free.size(); ++j) {
            std::cout << "  " << free[j].path << ": ";
            if (j < result.findings.size() && !result.findings[j].identifiable) {
                std::cout << "not identifiable (" << result.findings[j].reason << ")\n";
            } else if (j < result.findings.size()) {
                std::cout << result.findings[j].value << " (" << result.findings[j].reason << ")\n";
            } else {
                std::cout << result.best.values[j] << '\n';
            }
        }
        for (const auto& w : result.warnings) std::cout << "  warning: " << w << '\n';
        std::cout << "report: " << (out_dir / "report.md").string() << '\n';
        return 0;
    } catch (const config::ConfigException& e) {
        errors << e.what() << "\nshakerbench calibrate: nothing was simulated.\n";
        return config::kExitBadInput;
    } catch (const identification::FileError& e) {
        errors << "shakerbench calibrate: " << e.what() << '\n';
        return config::kExitBadInput;
    } catch (const std::invalid_argument& e) {
        errors << "shakerbench calibrate: " << e.what() << '\n';
        return config::kExitBadInput;
    } catch (const std::exception& e) {
        errors << "shakerbench calibrate: " << e.what() << '\n';
        return config::kExitFailure;
    }
}

}  // namespace

void register_calibrate_command(CLI::App& app, int& exit_code) {
    auto args = std::make_shared<CalibrateArgs>();
    CLI::App* cmd = app.add_subcommand(
        "calibrate",
        "Fit config values (default: the particles' sliding and rolling friction and "
        "restitution) to a measured recording directory: only its arrangements, levels and "
        "frequencies are simulated, every evaluation cached in OUT/cache, and the report says "
        "which values the data identify (docs/calibration.md).");
    cmd->add_option("config", args->config, "campaign config (TOML)");
    cmd->add_option("--measured", args->measured,
                    "measured recording directory (damping.csv, points.csv, time histories)")
        ->required();
    cmd->add_option("--free", args->free,
                    "a value to fit, KEY=MIN:MAX, KEY=MIN:MAX:log (searched on a log scale) or "
                    "KEY (its declared interval); repeatable");
    cmd->add_option("--budget", args->budget, "evaluations at most (default 30)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--mode", args->mode,
                    "direct (DIRECT-L then BOBYQA) or surrogate (emulator, expected improvement)")
        ->check(CLI::IsMember({"direct", "surrogate"}));
    cmd->add_option("--fidelity", args->fidelity,
                    "coupled (every evaluation a coupled campaign) or two-fidelity (the search "
                    "on the describing-function prediction, corrected and confirmed by coupled "
                    "campaigns; --budget counts the predictions)")
        ->check(CLI::IsMember({"coupled", "two-fidelity"}));
    cmd->add_option("--characterize-frequencies", args->characterization_frequencies,
                    "two-fidelity: frequencies per level the damper is characterised on, "
                    "equally spaced over the grid (default 3)")
        ->check(CLI::Range(2, 100));
    cmd->add_option("-o,--out", args->out_dir,
                    "output directory (default: out/<campaign name>-calibrated)");
    cmd->add_option("-j,--threads", args->threads, "threads (default: all cores)")
        ->check(CLI::NonNegativeNumber);
    add_uncertainty_options(*cmd, args->stated);
    cmd->add_flag("-q,--quiet", args->quiet, "no progress lines");
    add_set_option(*cmd, args->overrides);
    cmd->callback([args, &exit_code] {
        args->command_line = "shakerbench calibrate";
        if (!args->config.empty()) args->command_line += " " + args->config;
        args->command_line += " --measured " + args->measured;
        for (const auto& f : args->free) args->command_line += " --free " + f;
        args->command_line += " --budget " + std::to_string(args->budget) + " --mode " + args->mode;
        if (args->fidelity != "coupled") {
            args->command_line += " --fidelity " + args->fidelity + " --characterize-frequencies " +
                                  std::to_string(args->characterization_frequencies);
        }
        if (!args->out_dir.empty()) args->command_line += " --out " + args->out_dir;
        args->command_line += overrides_text(args->overrides);
        exit_code = run(*args);
    });
}

}  // namespace sb::apps

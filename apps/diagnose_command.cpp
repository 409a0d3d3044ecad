// `shakerbench diagnose`: the config simulated on the measured points, the features that
// disagree beyond the noise and how they scale with the level, values tested for drift; under
// mpirun the baseline's sweeps and the drift calibrations' simulations spread over the ranks.
#include "diagnose_command.hpp"

#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "correlation/diagnosis.hpp"
#include "distributed/campaign.hpp"
#include "distributed/rounds.hpp"
#include "distributed/session.hpp"
#include "identification/file_error.hpp"
#include "load_config.hpp"
#include "measured_options.hpp"

namespace sb::apps {
namespace {

struct DiagnoseArgs {
    std::string config;
    std::string measured;
    std::vector<std::string> drift;
    int budget = 15;
    std::string mode = "direct";
    int hypotheses = 3;
    int held_out = 1;
    bool no_confirm = false;
    std::string out_dir;
    int threads = 0;
    correlation::StatedUncertainty stated;
    bool quiet = false;
    std::vector<std::string> overrides;
    std::string command_line;
};

/// A rank other than 0: runs the baseline's sweeps, then the drift calibrations' evaluations,
/// that rank 0 hands out; rank 0 reports everything else.
int serve(distributed::Session& session, const bench::CampaignConfig& config,
          const correlation::Measurement& measurement, const correlation::DiagnosisOptions& options,
          int threads) {
    try {
        distributed::serve_campaign(*session.transport(), config, measurement.selection,
                                    options.calibration.threads);
        distributed::serve_rounds(*session.transport(), threads,
                                  correlation::diagnosis_simulator(config, measurement, options));
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "shakerbench diagnose (" << session.describe() << "): " << e.what() << '\n';
        session.abort(config::kExitFailure);  // rank 0 would wait for this rank forever
    }
}

int run(const DiagnoseArgs& args) {
    std::optional<distributed::Session> session;
    try {
        session.emplace();
    } catch (const std::exception& e) {
        std::cerr << "shakerbench diagnose: " << e.what() << '\n';
        return config::kExitBadInput;
    }
    const bool root = session->rank() == 0;
    // Every rank reads the config and the measurement (the same files); rank 0 alone reports
    // what is wrong with them.
    std::ostringstream silenced;
    std::ostream& errors = root ? std::cerr : silenced;
    int exit_code = 0;
    const auto config = load_config_or_report(args.config, args.overrides, exit_code, errors);
    if (!config) return exit_code;
    try {
        correlation::DiagnosisOptions options;
        options.stated = args.stated;
        if (!args.drift.empty()) {
            options.drift = correlation::parse_free_parameters(*config, args.drift);
        }
        const auto measurement = correlation::read_measurement(args.measured, args.stated);
        const std::filesystem::path out_dir =
            args.out_dir.empty() ? std::filesystem::path("out") / (config->name + "-diagnosis")
                                 : std::filesystem::path(args.out_dir);
        options.calibration.search.budget = args.budget;
        options.hypotheses = args.hypotheses;
        options.held_out_levels = args.held_out;
        options.confirm = !args.no_confirm;
        options.calibration.search.mode = args.mode == "surrogate"
                                              ? correlation::SearchMode::surrogate
                                              : correlation::SearchMode::direct;
        options.calibration.threads = args.threads;
        options.calibration.cache_dir = out_dir / "cache";
        const int threads =
            args.threads > 0 ? args.threads
                             : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
        if (session->size() > 1 && !args.quiet) {
            // One write per line: the ranks share mpirun's stderr.
            std::cerr << session->describe() + ", " + std::to_string(threads) + " threads\n"
                      << std::flush;
        }
        if (!root) return serve(*session, *config, measurement, options, threads);
        // Rank 0 owns the store of the baseline, the drift searches and their cache; sweeps and
        // evaluations run on whichever rank is free. Both are declared after the session (they
        // release the other ranks however the diagnosis ends), the sweeps' last: the other
        // ranks serve the baseline first, then the rounds.
        distributed::DistributedRounds rounds(
            session->transport(), threads,
            correlation::diagnosis_simulator(*config, measurement, options));
        distributed::DistributedSweeps sweeps(session->transport(), args.threads);
        if (session->size() > 1) {
            options.baseline_executor = &sweeps;
            options.remote = [&rounds](const std::vector<std::string>& inputs) {
                return rounds.run(inputs);
            };
        }
        if (!args.quiet) {
            options.progress = [](const std::string& line) {
                std::cerr << line << '\n' << std::flush;
            };
        }
        const auto result = correlation::diagnose(*config, args.measured, options);
        rounds.finish();
        correlation::write_diagnosis(out_dir, result, args.command_line);
        if (session->size() > 1 && !args.quiet) {
            std::string line = "sweeps run per rank:";
            for (const int n : sweeps.sweeps_per_rank()) line += ' ' + std::to_string(n);
            line += "; evaluations run per rank:";
            for (const int n : rounds.evaluations_per_rank()) line += ' ' + std::to_string(n);
            line += " (" + std::to_string(session->size()) + " ranks x " + std::to_string(threads) +
                    " threads)\n";
            std::cerr << line << std::flush;
        }
        std::cout << "diagnosis " << config->name << ": " << result.verdict << '\n';
        for (const auto& m : result.mismatches) {
            if (m.beyond_noise) std::cout << "  " << m.sentence << '\n';
        }
        for (const auto& d : result.drifts) std::cout << "  " << d.sentence << '\n';
        std::cout << "report: " << (out_dir / "report.md").string() << '\n';
        return 0;
    } catch (const config::ConfigException& e) {
        errors << e.what() << "\nshakerbench diagnose: nothing was simulated.\n";
        return config::kExitBadInput;
    } catch (const identification::FileError& e) {
        errors << "shakerbench diagnose: " << e.what() << '\n';
        return config::kExitBadInput;
    } catch (const std::invalid_argument& e) {
        errors << "shakerbench diagnose: " << e.what() << '\n';
        return config::kExitBadInput;
    } catch (const std::exception& e) {
        errors << "shakerbench diagnose: " << e.what() << '\n';
        return config::kExitFailure;
    }
}

}  // namespace

void register_diagnose_command(CLI::App& app, int& exit_code) {
    auto args = std::make_shared<DiagnoseArgs>();
    CLI::App* cmd = app.add_subcommand(
        "diagnose",
        "Say where CONFIG's simulation and a measured recording disagree: the config simulated "
        "on the measured points, both reduced to natural frequency, damping, peak |H| and its "
        "phase, harmonic ratios and drive per level, the features beyond the noise and how "
        "they scale with the level, values that drift when calibrated level by level, and "
        "which physics of the catalogue the model left out: ranked by signature, fitted, "
        "compared by BIC and checked on the held-out highest level (docs/diagnosis.md).");
    cmd->add_option("config", args->config, "campaign config (TOML)");
    cmd->add_option("--measured", args->measured,
                    "measured recording directory (damping.csv, points.csv, time histories)")
        ->required();
    cmd->add_option("--drift", args->drift,
                    "a value to calibrate level by level and test for a trend, KEY=MIN:MAX, "
                    "KEY=MIN:MAX:log (searched on a log scale) or KEY (its declared interval); "
                    "repeatable");
    cmd->add_option("--budget", args->budget,
                    "evaluations per level for each --drift calibration (default 15)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--mode", args->mode,
                    "the --drift calibrations' search: direct (DIRECT-L then BOBYQA, one "
                    "evaluation at a time) or surrogate (emulator, expected improvement; its "
                    "batches spread over MPI ranks)")
        ->check(CLI::IsMember({"direct", "surrogate"}));
    cmd->add_option("--hypotheses", args->hypotheses,
                    "catalogue physics to fit, at most, when a feature disagrees: the best-ranked "
                    "by signature, each switched on and fitted on all but the highest level "
                    "(default 3; 0: none)")
        ->check(CLI::Range(0, 100));
    cmd->add_option("--held-out", args->held_out,
                    "highest levels of each arrangement the hypotheses are not fitted on but "
                    "checked against (default 1; kept only where two levels or more remain)")
        ->check(CLI::Range(0, 100));
    cmd->add_flag("--no-confirm", args->no_confirm,
                  "do not simulate the winner again by the coupled campaign (describing-function "
                  "dampers as their DEM beds) when it was fitted on the prediction");
    cmd->add_option("-o,--out", args->out_dir,
                    "output directory (default: out/<campaign name>-diagnosis)");
    cmd->add_option("-j,--threads", args->threads, "threads (default: all cores)")
        ->check(CLI::NonNegativeNumber);
    add_uncertainty_options(*cmd, args->stated);
    cmd->add_flag("-q,--quiet", args->quiet, "no progress lines");
    add_set_option(*cmd, args->overrides);
    cmd->callback([args, &exit_code] {
        args->command_line = "shakerbench diagnose";
        if (!args->config.empty()) args->command_line += " " + args->config;
        args->command_line += " --measured " + args->measured;
        for (const auto& d : args->drift) args->command_line += " --drift " + d;
        if (!args->drift.empty()) {
            args->command_line +=
                " --budget " + std::to_string(args->budget) + " --mode " + args->mode;
        }
        if (args->hypotheses != 3) {
            args->command_line += " --hypotheses " + std::to_string(args->hypotheses);
        }
        if (args->held_out != 1) {
            args->command_line += " --held-out " + std::to_string(args->held_out);
        }
        if (args->no_confirm) args->command_line += " --no-confirm";
        if (!args->out_dir.empty()) args->command_line += " --out " + args->out_dir;
        args->command_line += overrides_text(args->overrides);
        exit_code = run(*args);
    });
}

}  // namespace sb::apps

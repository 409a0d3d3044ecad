// `shakerbench diagnose`: the config simulated on the measured points, the features that
// disagree beyond the noise and how they scale with the level, values tested for drift.
#include "diagnose_command.hpp"

#include <iostream>
#include <memory>

#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "correlation/diagnosis.hpp"
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
    std::string out_dir;
    int threads = 0;
    correlation::StatedUncertainty stated;
    bool quiet = false;
    std::vector<std::string> overrides;
    std::string command_line;
};

int run(const DiagnoseArgs& args) {
    int exit_code = 0;
    const auto config = load_config_or_report(args.config, args.overrides, exit_code);
    if (!config) return exit_code;
    try {
        correlation::DiagnosisOptions options;
        options.stated = args.stated;
        if (!args.drift.empty()) {
            options.drift = correlation::parse_free_parameters(*config, args.drift);
        }
        const std::filesystem::path out_dir =
            args.out_dir.empty() ? std::filesystem::path("out") / (config->name + "-diagnosis")
                                 : std::filesystem::path(args.out_dir);
        options.calibration.search.budget = args.budget;
        options.calibration.threads = args.threads;
        options.calibration.cache_dir = out_dir / "cache";
        if (!args.quiet) {
            options.progress = [](const std::string& line) {
                std::cerr << line << '\n' << std::flush;
            };
        }
        const auto result = correlation::diagnose(*config, args.measured, options);
        correlation::write_diagnosis(out_dir, result, args.command_line);
        std::cout << "diagnosis " << config->name << ": " << result.verdict << '\n';
        for (const auto& m : result.mismatches) {
            if (m.beyond_noise) std::cout << "  " << m.sentence << '\n';
        }
        for (const auto& d : result.drifts) std::cout << "  " << d.sentence << '\n';
        std::cout << "report: " << (out_dir / "report.md").string() << '\n';
        return 0;
    } catch (const config::ConfigException& e) {
        std::cerr << e.what() << "\nshakerbench diagnose: nothing was simulated.\n";
        return config::kExitBadInput;
    } catch (const identification::FileError& e) {
        std::cerr << "shakerbench diagnose: " << e.what() << '\n';
        return config::kExitBadInput;
    } catch (const std::invalid_argument& e) {
        std::cerr << "shakerbench diagnose: " << e.what() << '\n';
        return config::kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << "shakerbench diagnose: " << e.what() << '\n';
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
        "they scale with the level, and values that drift when calibrated level by level "
        "(docs/diagnosis.md).");
    cmd->add_option("config", args->config, "campaign config (TOML)");
    cmd->add_option("--measured", args->measured,
                    "measured recording directory (damping.csv, points.csv, time histories)")
        ->required();
    cmd->add_option("--drift", args->drift,
                    "a value to calibrate level by level and test for a trend, KEY=MIN:MAX or "
                    "KEY (its declared interval); repeatable");
    cmd->add_option("--budget", args->budget,
                    "evaluations per level for each --drift calibration (default 15)")
        ->check(CLI::Range(1, 100000));
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
        if (!args->out_dir.empty()) args->command_line += " --out " + args->out_dir;
        args->command_line += overrides_text(args->overrides);
        exit_code = run(*args);
    });
}

}  // namespace sb::apps

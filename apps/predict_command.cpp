// `shakerbench predict`: a campaign by harmonic balance, written as a recording directory.
#include "predict_command.hpp"

#include <iomanip>
#include <iostream>
#include <memory>

#include "bench/campaign_output.hpp"
#include "bench/prediction.hpp"
#include "config/errors.hpp"
#include "config/value.hpp"
#include "core/text_file.hpp"
#include "identification/file_error.hpp"
#include "load_config.hpp"

namespace sb::apps {
namespace {

struct PredictArgs {
    std::string config;
    std::string out_dir;
    std::string characterization;
    double scale = 1.0;
    bool quiet = false;
    std::vector<std::string> overrides;
    std::string command_line;
};

int run(const PredictArgs& args) {
    int exit_code = 0;
    auto config = load_config_or_report(args.config, args.overrides, exit_code);
    if (!config) return exit_code;
    if (!args.characterization.empty()) {
        *config = bench::with_describing_functions(*config, args.characterization, args.scale);
    }
    const std::filesystem::path out_dir =
        args.out_dir.empty() ? std::filesystem::path("out") / (config->name + "-predicted")
                             : std::filesystem::path(args.out_dir);
    bench::PredictContext context;
    if (!args.quiet) {
        context.progress = [](const std::string& line) { std::cerr << line << '\n' << std::flush; };
    }
    try {
        const bench::CampaignResult result = bench::predict_campaign(*config, context);
        bench::RecordingDirectory directory;
        directory.out_dir = out_dir;
        directory.config_text = args.config.empty() ? std::string(bench::builtin_config_text())
                                                    : read_text_file(args.config);
        directory.command_line = args.command_line;
        bench::write_campaign_output(*config, result, directory);
        int predicted = 0;
        int extrapolated = 0;
        int uncertain = 0;
        for (const auto& p : result.recording.points) {
            predicted += p.status == "predicted";
            extrapolated += p.status == "extrapolated";
            uncertain += p.status == "uncertain";
        }
        std::cout << "prediction " << config->name << ": " << result.summary.points << " points ("
                  << predicted << " predicted, " << extrapolated << " extrapolated, " << uncertain
                  << " uncertain) in " << std::fixed << std::setprecision(3)
                  << result.summary.wall_time_s << " s\n"
                  << "recording: " << out_dir.string() << '\n';
        return 0;
    } catch (const config::ConfigException& e) {
        std::cerr << e.what() << "\nshakerbench predict: the campaign cannot be predicted.\n";
        return config::kExitBadInput;
    } catch (const identification::FileError& e) {
        std::cerr << "shakerbench predict: " << e.what() << '\n';
        return config::kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << "shakerbench predict: " << e.what() << '\n';
        return config::kExitFailure;
    }
}

}  // namespace

void register_predict_command(CLI::App& app, int& exit_code) {
    auto args = std::make_shared<PredictArgs>();
    CLI::App* cmd = app.add_subcommand(
        "predict",
        "Predict the stepped-sine campaign of CONFIG in seconds: every point solved by harmonic "
        "balance of the structure with the dampers' describing functions (model = "
        "\"describing-function\", or --characterization FILE for every DEM damper), the drive "
        "set to hold the control point's RMS target. Writes a recording directory like run's "
        "(docs/characterisation.md).");
    cmd->add_option("config", args->config, "campaign config (TOML)");
    cmd->add_option("-o,--out", args->out_dir,
                    "recording directory (default: out/<campaign name>-predicted)");
    CLI::Option* characterization =
        cmd->add_option("--characterization", args->characterization,
                        "characterization.csv for every damper whose model is dem");
    cmd->add_option("--scale", args->scale,
                    "with --characterization: how many times the characterised bed each damper "
                    "holds (dampers.NAME.characterization_scale; a quarter of the footprint "
                    "characterised: 4)")
        ->check(CLI::PositiveNumber)
        ->needs(characterization);
    cmd->add_flag("-q,--quiet", args->quiet, "no progress lines");
    add_set_option(*cmd, args->overrides);
    cmd->callback([args, &exit_code] {
        args->command_line = "shakerbench predict";
        if (!args->config.empty()) args->command_line += " " + args->config;
        if (!args->out_dir.empty()) args->command_line += " --out " + args->out_dir;
        if (!args->characterization.empty()) {
            args->command_line += " --characterization " + args->characterization;
        }
        if (args->scale != 1.0)
            args->command_line += " --scale " + config::number_text(args->scale);
        args->command_line += overrides_text(args->overrides);
        exit_code = run(*args);
    });
}

}  // namespace sb::apps

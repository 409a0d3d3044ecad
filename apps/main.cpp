// shakerbench: the command-line entry point. Each subcommand lives in its own file.
#include <CLI/CLI.hpp>
#include <iostream>

#include "calibrate_command.hpp"
#include "characterize_command.hpp"
#include "config/errors.hpp"
#include "diagnose_command.hpp"
#include "identify_command.hpp"
#include "keys_command.hpp"
#include "modes_command.hpp"
#include "predict_command.hpp"
#include "run_command.hpp"

int main(int argc, char** argv) {
    CLI::App app{
        "ShakerBench: a virtual shaker test bench for structures carrying particle dampers.\n"
        "Stepped-sine campaigns with RMS amplitude control, DEM particles coupled to the\n"
        "structure, transfer functions and damping curves, correlation with recordings."};
    app.set_version_flag("--version", std::string("shakerbench ") + SB_VERSION);
    app.require_subcommand(1);
    app.footer(
        "Run 'shakerbench SUBCOMMAND --help' for the options of a subcommand.\n"
        "Exit codes: 0 success, 1 simulation failure, 2 bad input (config, data, "
        "command line).");

    int exit_code = 0;
    sb::apps::register_run_command(app, exit_code);
    sb::apps::register_characterize_command(app, exit_code);
    sb::apps::register_predict_command(app, exit_code);
    sb::apps::register_modes_command(app, exit_code);
    sb::apps::register_identify_command(app, exit_code);
    sb::apps::register_keys_command(app, exit_code);
    sb::apps::register_calibrate_command(app, exit_code);
    sb::apps::register_diagnose_command(app, exit_code);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        // CLI11 returns 0 for --help and --version; any other parse error is bad input.
        return code == 0 ? 0 : sb::config::kExitBadInput;
    }
    return exit_code;
}

// `shakerbench calibrate`: config values fitted to a measured recording (docs/calibration.md).
#pragma once

#include <CLI/CLI.hpp>

namespace sb::apps {

/// Adds the `calibrate` subcommand; its callback stores the exit code in `exit_code`.
void register_calibrate_command(CLI::App& app, int& exit_code);

}  // namespace sb::apps

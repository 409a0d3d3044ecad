// `shakerbench characterize`: every DEM damper of a config alone under a prescribed harmonic
// motion, its complex apparent mass over a grid of amplitudes and frequencies.
#pragma once

#include <CLI/CLI.hpp>

namespace sb::apps {

/// Adds the `characterize` subcommand; its callback stores the exit code in `exit_code`.
void register_characterize_command(CLI::App& app, int& exit_code);

}  // namespace sb::apps

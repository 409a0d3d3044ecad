// `shakerbench modes`: modal analysis of the structure of a config.
#pragma once

#include <CLI/CLI.hpp>

namespace sb::apps {

/// Adds the `modes` subcommand; its callback stores the process exit code in `exit_code`.
void register_modes_command(CLI::App& app, int& exit_code);

}  // namespace sb::apps

// `shakerbench run`: the stepped-sine campaign of a config (default: the built-in one).
#pragma once

#include <CLI/CLI.hpp>

namespace sb::apps {

/// Adds the `run` subcommand; its callback stores the process exit code in `exit_code`.
void register_run_command(CLI::App& app, int& exit_code);

}  // namespace sb::apps

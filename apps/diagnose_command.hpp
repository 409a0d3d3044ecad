// `shakerbench diagnose`: where a config's simulation and a measured recording disagree
// (docs/diagnosis.md).
#pragma once

#include <CLI/CLI.hpp>

namespace sb::apps {

/// Adds the `diagnose` subcommand; its callback stores the exit code in `exit_code`.
void register_diagnose_command(CLI::App& app, int& exit_code);

}  // namespace sb::apps

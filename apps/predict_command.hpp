// `shakerbench predict`: a campaign solved by harmonic balance with describing functions.
#pragma once

#include <CLI/CLI.hpp>

namespace sb::apps {

/// Adds the `predict` subcommand; its callback stores the exit code in `exit_code`.
void register_predict_command(CLI::App& app, int& exit_code);

}  // namespace sb::apps

// `shakerbench identify DIR|FILE.uff [--out DIR]`: natural frequency and damping per level.
#pragma once

namespace CLI {
class App;
}

namespace sb::apps {

/// Adds the `identify` subcommand to `app`. On a bad input file it prints the FileError
/// (file:line:col: message) to stderr and sets exit_code = 2.
void register_identify_command(CLI::App& app, int& exit_code);

}  // namespace sb::apps

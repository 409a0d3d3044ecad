// `shakerbench identify DIR|FILE.uff [options]`: natural frequency and damping per level.
#pragma once

namespace CLI {
class App;
}

namespace sb::apps {

/// Adds the `identify` subcommand to `app` (options in docs/identification.md). On a bad input
/// file it prints the FileError (file:line:col: message) to stderr, on an option that does
/// not fit the input a message naming the option; both set exit_code = 2.
void register_identify_command(CLI::App& app, int& exit_code);

}  // namespace sb::apps

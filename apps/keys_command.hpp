// `shakerbench keys [CONFIG]`: every key a config can set, by dotted path.
#pragma once

namespace CLI {
class App;
}

namespace sb::apps {

/// Adds the `keys` subcommand; its callback stores the process exit code in `exit_code`.
void register_keys_command(CLI::App& app, int& exit_code);

}  // namespace sb::apps

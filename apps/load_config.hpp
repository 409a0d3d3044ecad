// Loading a config for a subcommand: the file given (or the built-in default campaign), with
// the command line's --set overrides applied.
#pragma once

#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "bench/campaign_config.hpp"

namespace CLI {
class App;
}

namespace sb::apps {

/// Loads `path` (empty: the built-in default) and applies `overrides` (KEY=VALUE, in order).
/// On a bad config or override prints every error to `errors`, sets exit_code to 2 and returns
/// nothing.
std::optional<bench::CampaignConfig> load_config_or_report(
    const std::string& path, const std::vector<std::string>& overrides, int& exit_code,
    std::ostream& errors = std::cerr);

/// Adds the repeatable `--set KEY=VALUE` option to a subcommand.
void add_set_option(CLI::App& command, std::vector<std::string>& overrides);

/// " --set 'KEY=VALUE'" for each override, as a shell would take it back (provenance).
std::string overrides_text(const std::vector<std::string>& overrides);

}  // namespace sb::apps

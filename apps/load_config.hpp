// Loading a config for a subcommand: the file given, or the built-in default campaign.
#pragma once

#include <optional>
#include <string>

#include "bench/campaign_config.hpp"

namespace sb::apps {

/// Loads `path` (empty: the built-in default). On a bad config prints every error to stderr,
/// sets exit_code to 2 and returns nothing.
std::optional<bench::CampaignConfig> load_config_or_report(const std::string& path, int& exit_code);

}  // namespace sb::apps

// The campaign config with every default filled in, as a loadable TOML file.
#pragma once

#include <string>
#include <string_view>

#include "bench/campaign_config.hpp"

namespace sb::bench {

/// TOML text of `config` with every campaign, arrangement, damper, controller and output key
/// written out, defaults included; the [structure] tables are copied from `raw_text` (the
/// config as read). Loading the text gives the same campaign.
std::string resolved_config_toml(const CampaignConfig& config, std::string_view raw_text);

}  // namespace sb::bench

// The campaign config as run: every value written out, its canonical text and its hash.
#pragma once

#include <string>

#include "bench/campaign_config.hpp"

namespace sb::bench {

/// TOML text of `config` with every key that applies written out from the typed model,
/// defaults included ("automatic" for values the bench chooses). Loading it gives the same
/// campaign and the same config_hash().
std::string resolved_config_toml(const CampaignConfig& config);

/// Every resolved value, one sorted `path = value` line each (config::canonical_text).
std::string canonical_config_text(const CampaignConfig& config);

/// 16 hexadecimal digits identifying the resolved config: the same hash, the same numbers.
/// Independent of key order, comments and formatting in the file.
std::string config_hash(const CampaignConfig& config);

}  // namespace sb::bench

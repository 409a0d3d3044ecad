// Writing the resolved campaign config and its identity.
#include "bench/resolved_config.hpp"

#include "bench/config_schema.hpp"
#include "config/write.hpp"

namespace sb::bench {

std::string resolved_config_toml(const CampaignConfig& config) {
    return config::write_toml(
        campaign_schema(), &config,
        "# The campaign as run: every value written out (shakerbench run reads it back).\n"
        "# config_hash = \"" +
            config_hash(config) + "\"");
}

std::string canonical_config_text(const CampaignConfig& config) {
    return config::canonical_text(campaign_schema(), &config);
}

std::string config_hash(const CampaignConfig& config) {
    return config::identity_hash(campaign_schema(), &config);
}

}  // namespace sb::bench

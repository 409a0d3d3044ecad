// Reading the campaign tables of a config: levels, grid, arrangements, controller, output.
#pragma once

#include "bench/campaign_spec.hpp"
#include "bench/config_reader.hpp"

namespace sb::bench {

/// Reads the campaign keys of [campaign] (levels_g, arrangements, control_point, ...),
/// [campaign.frequencies], [arrangements.NAME], [dampers.NAME], [controller] and [output].
/// `campaign` must already have had its identity keys (name, description) read.
CampaignSpec read_campaign(Section& root, Section& campaign);

}  // namespace sb::bench

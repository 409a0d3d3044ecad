// The declarations of every key of a campaign config, bound to CampaignConfig.
#pragma once

#include "config/schema.hpp"

namespace sb::bench {

/// The root table: [campaign], [arrangements.NAME], [dampers.NAME], [controller], [output] and
/// [structure], each key declared once (bench/config_schema.cpp, bench/damper_schema.cpp,
/// bench/structure_schema.cpp). The object it fills is a CampaignConfig.
const config::Table& campaign_schema();

}  // namespace sb::bench

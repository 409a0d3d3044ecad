// Reading [dampers.NAME] of a campaign config into DamperSpec.
#pragma once

#include <vector>

#include "bench/campaign_spec.hpp"
#include "bench/config_reader.hpp"

namespace sb::bench {

/// Every [dampers.NAME] table, checked with the DEM module's own validation.
std::vector<DamperSpec> read_dampers(Section dampers);

}  // namespace sb::bench

// The low fidelity of a two-fidelity calibration: the damper characterised alone at the
// measured levels, then the campaign predicted from its describing functions on the measured
// points (bench/characterization.hpp, bench/prediction.hpp; docs/characterisation.md).
#pragma once

#include <filesystem>
#include <functional>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"

namespace sb::correlation {

using Simulation = std::function<bench::CampaignResult(const bench::CampaignConfig&,
                                                       const bench::Selection&, int)>;

/// Characterises every DEM damper of the config at the selection's arrangements and levels,
/// on `frequencies` frequencies equally spaced over each arrangement's grid and
/// campaign.seeds fillings, writes the table to `folder`/characterization-HASH.csv (HASH the
/// config's; `predict --characterization` takes it as it is), and predicts the selection from
/// it. Throws what characterize and predict_campaign throw.
Simulation describing_function_simulation(std::filesystem::path folder, int frequencies);

}  // namespace sb::correlation

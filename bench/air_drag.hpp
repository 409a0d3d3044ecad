// The beam's air drag (physics.air_drag) as strips at named points: the points a prepared
// arrangement adds to its beam, the attachments a sweep steps, and the describing functions a
// prediction balances.
#pragma once

#include <string>
#include <vector>

#include "bench/attachment.hpp"
#include "bench/campaign_config.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// The midpoints of `stations` equal strips of the beam, named "air_drag_1" ... in order
/// along it.
std::vector<structure::NamedPoint> air_drag_points(const structure::BeamSpec& beam, int stations);

/// One strip at each of those points (none when the drag is off): k = 1/2 rho C_D b l with
/// the beam's width b and the strip's length l, along the wide face's normal z.
std::vector<Attachment> air_drag_attachments(const CampaignConfig& config);

}  // namespace sb::bench

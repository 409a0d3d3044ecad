// The catalogue physics a config switches on ([physics]) as attachments at named points: the
// beam's air drag as strips (the points a prepared arrangement adds to its beam), microslip
// as a dashpot at the joint's point, a joint's slip as an Iwan element there. A sweep steps them; a
// prediction balances their describing functions.
#pragma once

#include <string>
#include <vector>

#include "bench/attachment.hpp"
#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// The midpoints of `stations` equal strips of the beam, named "air_drag_1" ... in order
/// along it.
std::vector<structure::NamedPoint> air_drag_points(const structure::BeamSpec& beam, int stations);

/// One strip at each of those points (none when the drag is off): k = 1/2 rho C_D b l with
/// the beam's width b and the strip's length l, along the wide face's normal z.
std::vector<Attachment> air_drag_attachments(const CampaignConfig& config);

/// Every catalogue physics of `config` that is on, as attachments in `prepared` (its points'
/// rest positions): the air-drag strips, then the microslip dashpot, the cubic spring and the
/// Iwan joint (along the excitation direction at their points).
std::vector<Attachment> physics_attachments(const CampaignConfig& config,
                                            const PreparedArrangement& prepared);

/// The describing function of a catalogue attachment (an AirDragStrip, MicroslipDashpot,
/// CubicSpring or IwanJoint) at the peak acceleration [m/s^2] and frequency [Hz]; throws
/// std::invalid_argument for another model.
DescribingFunction::Value physics_describing(const Attachment& attachment, double acceleration_m_s2,
                                             double frequency_hz);

}  // namespace sb::bench

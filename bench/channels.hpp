// The channels a campaign records, resolved from the config: the reference's companions in
// recording order (control acceleration, response accelerations, then the further channels
// of [[campaign.channels]]), each with its quantity, unit and direction.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bench/campaign_spec.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// One recorded channel after the reference.
struct RecordedChannel {
    using Quantity = ChannelSpec::Quantity;
    std::string name;  ///< column name in points.csv and series/
    Quantity quantity = Quantity::acceleration;
    std::string point;   ///< the named point read (motion), or the damper's point (force)
    std::string damper;  ///< damper-force: the damper's name
    Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit vector of the reading

    /// The recording's quantity and SI unit ("acceleration", "m/s^2"; a damper force is a
    /// "force" in "N").
    [[nodiscard]] std::string quantity_name() const;
    [[nodiscard]] std::string unit() const;
    /// Where the channel sits for recording.toml: the point, or "damper:NAME".
    [[nodiscard]] std::string location() const;
};

/// An acceleration channel "acc_<point>" along `direction`.
RecordedChannel acceleration_channel(const std::string& point, const Eigen::Vector3d& direction);

/// The campaign's channels after the reference: the control point's acceleration along the
/// excitation direction first, the response points', then [[campaign.channels]] (their
/// default names and directions filled in).
std::vector<RecordedChannel> recorded_channels(const CampaignSpec& campaign,
                                               const structure::ExcitationSpec& excitation);

/// The default name of a further channel: a prefix of its quantity (acc, vel, disp,
/// force), its point (or damper) and, off the excitation direction, the axis it reads
/// ("acc_bracket_y"; "_dir" for a direction that is no axis).
std::string default_channel_name(const ChannelSpec& channel, const Eigen::Vector3d& excitation);

}  // namespace sb::bench

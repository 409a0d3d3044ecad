// The channels a campaign records.
#include "bench/channels.hpp"

#include <cmath>

namespace sb::bench {
namespace {

Eigen::Vector3d direction_of(const ChannelSpec& channel, const Eigen::Vector3d& excitation) {
    return channel.direction ? channel.direction->normalized() : excitation.normalized();
}

/// "x", "y", "z" (or "-x", ...) for a direction along an axis, else "dir".
std::string axis_text(const Eigen::Vector3d& d) {
    static const char* const kAxes[] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
        if (std::abs(std::abs(d[k]) - 1.0) < 1e-12) {
            return std::string(d[k] < 0.0 ? "-" : "") + kAxes[k];
        }
    }
    return "dir";
}

}  // namespace

std::string RecordedChannel::quantity_name() const {
    switch (quantity) {
        case Quantity::acceleration:
            return "acceleration";
        case Quantity::velocity:
            return "velocity";
        case Quantity::displacement:
            return "displacement";
        case Quantity::damper_force:
            return "force";
    }
    return "acceleration";
}

std::string RecordedChannel::unit() const {
    switch (quantity) {
        case Quantity::acceleration:
            return "m/s^2";
        case Quantity::velocity:
            return "m/s";
        case Quantity::displacement:
            return "m";
        case Quantity::damper_force:
            return "N";
    }
    return "m/s^2";
}

std::string RecordedChannel::location() const {
    return quantity == Quantity::damper_force ? "damper:" + damper : point;
}

RecordedChannel acceleration_channel(const std::string& point, const Eigen::Vector3d& direction) {
    RecordedChannel c;
    c.name = "acc_" + point;
    c.point = point;
    c.direction = direction.normalized();
    return c;
}

std::string default_channel_name(const ChannelSpec& channel, const Eigen::Vector3d& excitation) {
    using Q = ChannelSpec::Quantity;
    const char* prefix = channel.quantity == Q::acceleration   ? "acc"
                         : channel.quantity == Q::velocity     ? "vel"
                         : channel.quantity == Q::displacement ? "disp"
                                                               : "force";
    const std::string& where = channel.quantity == Q::damper_force ? channel.damper : channel.point;
    std::string name = std::string(prefix) + "_" + where;
    const Eigen::Vector3d d = direction_of(channel, excitation);
    if (!d.isApprox(excitation.normalized())) name += "_" + axis_text(d);
    return name;
}

std::vector<RecordedChannel> recorded_channels(const CampaignSpec& campaign,
                                               const structure::ExcitationSpec& excitation) {
    const Eigen::Vector3d along = excitation.direction.normalized();
    std::vector<RecordedChannel> out{acceleration_channel(campaign.control_point, along)};
    for (const auto& p : campaign.response_points) {
        if (p != campaign.control_point) out.push_back(acceleration_channel(p, along));
    }
    for (const auto& spec : campaign.channels) {
        RecordedChannel c;
        c.name = spec.name.empty() ? default_channel_name(spec, along) : spec.name;
        c.quantity = spec.quantity;
        c.direction = direction_of(spec, along);
        c.damper = spec.damper;
        c.point = spec.point;
        if (spec.quantity == ChannelSpec::Quantity::damper_force) {
            for (const auto& d : campaign.dampers) {
                if (d.name == spec.damper) c.point = d.point;
            }
        }
        out.push_back(c);
    }
    return out;
}

}  // namespace sb::bench

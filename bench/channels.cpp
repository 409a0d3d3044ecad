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

/// What each quantity is called in a default channel name and in recording.toml, and its
/// SI unit: one row per quantity.
struct QuantityNames {
    ChannelSpec::Quantity quantity;
    const char* prefix;
    const char* recorded;
    const char* unit;
};
constexpr QuantityNames kQuantities[] = {
    {ChannelSpec::Quantity::acceleration, "acc", "acceleration", "m/s^2"},
    {ChannelSpec::Quantity::velocity, "vel", "velocity", "m/s"},
    {ChannelSpec::Quantity::displacement, "disp", "displacement", "m"},
    {ChannelSpec::Quantity::damper_force, "force", "force", "N"}};

const QuantityNames& quantity_of(ChannelSpec::Quantity quantity) {
    for (const auto& row : kQuantities) {
        if (row.quantity == quantity) return row;
    }
    return kQuantities[0];
}

}  // namespace

std::string RecordedChannel::quantity_name() const { return quantity_of(quantity).recorded; }

std::string RecordedChannel::unit() const { return quantity_of(quantity).unit; }

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
    const bool force = channel.quantity == ChannelSpec::Quantity::damper_force;
    std::string name = std::string(quantity_of(channel.quantity).prefix) + "_" +
                       (force ? channel.damper : channel.point);
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

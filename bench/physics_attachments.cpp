#include "bench/physics_attachments.hpp"

#include <stdexcept>

namespace sb::bench {

std::vector<structure::NamedPoint> air_drag_points(const structure::BeamSpec& beam, int stations) {
    std::vector<structure::NamedPoint> points;
    const double strip_m = beam.length_m / stations;
    for (int k = 0; k < stations; ++k) {
        points.push_back({"air_drag_" + std::to_string(k + 1), (k + 0.5) * strip_m});
    }
    return points;
}

std::vector<Attachment> air_drag_attachments(const CampaignConfig& config) {
    const AirDragSpec& drag = config.physics.air_drag;
    std::vector<Attachment> out;
    if (!drag.on()) return out;
    const auto& beam = config.structure.beam;
    const double strip_m = beam.length_m / drag.stations;
    // The wide face (width b along y) faces z: the section's thickness axis.
    const double k = 0.5 * drag.air_density_kg_m3 * drag.drag_coefficient * beam.width_m * strip_m;
    for (const auto& p : air_drag_points(beam, drag.stations)) {
        out.push_back({p.name, p.name, AirDragStrip(Eigen::Vector3d::UnitZ(), k)});
    }
    return out;
}

std::vector<Attachment> physics_attachments(const CampaignConfig& config,
                                            const PreparedArrangement& prepared) {
    std::vector<Attachment> out = air_drag_attachments(config);
    const MicroslipSpec& slip = config.physics.microslip;
    if (slip.on()) {
        out.push_back(
            {"microslip", slip.point,
             MicroslipDashpot(config.structure.excitation.direction, slip.damping_n_s_per_m,
                              slip.exponent, slip.reference_velocity_m_s)});
    }
    const CubicSpringSpec& cubic = config.physics.cubic_spring;
    if (cubic.on()) {
        out.push_back({"cubic spring", cubic.point,
                       CubicSpring(config.structure.excitation.direction, cubic.stiffness_n_per_m3,
                                   prepared.model.point(cubic.point).position_m)});
    }
    const IwanJointSpec& joint = config.physics.iwan_joint;
    if (joint.on()) {
        out.push_back({"iwan joint", joint.point,
                       IwanJoint(config.structure.excitation.direction, joint.stiffness_n_per_m,
                                 joint.macroslip_displacement_m, joint.exponent, joint.elements,
                                 prepared.model.point(joint.point).position_m)});
    }
    const ShakerSpec& shaker = config.physics.shaker;
    const auto& excitation = config.structure.excitation;
    if (shaker.on() && excitation.kind == structure::ExcitationSpec::Kind::force) {
        out.push_back({"shaker", excitation.point,
                       ShakerCoil(excitation.direction, shaker,
                                  prepared.model.point(excitation.point).position_m)});
    }
    return out;
}

DescribingFunction::Value physics_describing(const Attachment& attachment, double acceleration_m_s2,
                                             double frequency_hz) {
    if (const auto* strip = std::get_if<AirDragStrip>(&attachment.model)) {
        return strip->describing(acceleration_m_s2, frequency_hz);
    }
    if (const auto* slip = std::get_if<MicroslipDashpot>(&attachment.model)) {
        return slip->describing(acceleration_m_s2, frequency_hz);
    }
    if (const auto* cubic = std::get_if<CubicSpring>(&attachment.model)) {
        return cubic->describing(acceleration_m_s2, frequency_hz);
    }
    if (const auto* joint = std::get_if<IwanJoint>(&attachment.model)) {
        return joint->describing(acceleration_m_s2, frequency_hz);
    }
    if (const auto* coil = std::get_if<ShakerCoil>(&attachment.model)) {
        return coil->describing(acceleration_m_s2, frequency_hz);
    }
    throw std::invalid_argument("attachment " + attachment.name +
                                " is not a catalogue physics with a describing function");
}

}  // namespace sb::bench

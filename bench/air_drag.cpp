#include "bench/air_drag.hpp"

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

}  // namespace sb::bench

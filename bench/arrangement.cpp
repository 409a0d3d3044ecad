// Geometry of an arrangement.
#include "bench/arrangement.hpp"

#include <cmath>

#include "core/units.hpp"

namespace sb::bench {

Eigen::Vector3d arrangement_gravity(const ArrangementSpec& arrangement) {
    if (arrangement.oscillation == ArrangementSpec::Oscillation::vertical) {
        return {0.0, 0.0, -kStandardGravity};
    }
    return {0.0, -kStandardGravity, 0.0};
}

Eigen::Matrix3d mounting_rotation(const ArrangementSpec& arrangement) {
    const double angle = deg_to_rad(arrangement.damper_angle_deg);
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    Eigen::Matrix3d r;
    // Columns: the enclosure's local x, y, z axes in the structure frame (right-handed).
    r.col(0) = Eigen::Vector3d::UnitX();
    r.col(1) = Eigen::Vector3d(0.0, c, -s);
    r.col(2) = Eigen::Vector3d(0.0, s, c);
    return r;
}

}  // namespace sb::bench

// Geometry of an arrangement.
#include "bench/arrangement.hpp"

#include <cmath>

#include "core/units.hpp"

namespace sb::bench {

Eigen::Vector3d arrangement_gravity(const ArrangementSpec& arrangement, double g_m_s2) {
    const Eigen::Vector3d nominal =
        arrangement.oscillation == ArrangementSpec::Oscillation::vertical
            ? Eigen::Vector3d(0.0, 0.0, -g_m_s2)
            : Eigen::Vector3d(0.0, -g_m_s2, 0.0);
    if (arrangement.gravity_tilt_deg == 0.0) return nominal;
    const double angle = deg_to_rad(arrangement.gravity_tilt_deg);
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    // The rotation about x: (y, z) -> (c y - s z, s y + c z).
    return {nominal.x(), c * nominal.y() - s * nominal.z(), s * nominal.y() + c * nominal.z()};
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

DamperMounting damper_mounting(const ArrangementSpec& arrangement, const DamperSpec& damper) {
    DamperMounting m;
    m.rotation = mounting_rotation(arrangement);
    const Eigen::Vector3d bottom(0.0, 0.0, damper.bottom_thickness_m);
    // Where the enclosure stands at 0 deg: the beam face under it.
    const Eigen::Vector3d on_beam = damper.mount_offset_m - bottom;
    // The wedge lies on one cathetus across y, from -c/2 to +c/2 under the enclosure, its
    // right angle at y = -c/2 (the axis tilts towards +y). The hypotenuse's midpoint, where
    // the enclosure stands, is c/2 above the beam face; the triangle's centroid is a third
    // of the way from the right angle along each leg.
    const double c = arrangement.block_cathetus_m;
    m.mounting_face_m = on_beam + Eigen::Vector3d(0.0, 0.0, 0.5 * c) + arrangement.mount_lift_m;
    m.block_cg_m = on_beam + Eigen::Vector3d(0.0, -c / 2.0 + c / 3.0, c / 3.0);
    m.origin_m = m.mounting_face_m + m.rotation * bottom;
    return m;
}

}  // namespace sb::bench

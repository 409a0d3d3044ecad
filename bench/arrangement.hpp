// Geometry of an arrangement: gravity in the structure frame, the damper's mounting rotation,
// and where the enclosure, its lumped mass and the mounting block sit (paper 000, Figs. 1-2,
// Table 1).
#pragma once

#include <Eigen/Core>

#include "bench/campaign_spec.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// Gravity of magnitude `g_m_s2` in the structure frame [m/s^2]. The shaker drives z.
/// Horizontal oscillation: the section's long side (y) is vertical, gravity along -y.
/// Vertical oscillation: gravity along -z. Either turned about the beam axis x by the
/// arrangement's gravity_tilt_deg.
Eigen::Vector3d arrangement_gravity(const ArrangementSpec& arrangement, double g_m_s2);

/// Rotation from the enclosure frame (axis = local z) to the structure frame: the axis tilted
/// from the motion (z) by the damper angle about the beam axis x, towards +y. At 0 deg the
/// axis is the motion; at 90 deg it is the section's long side (vertical when horizontal).
Eigen::Matrix3d mounting_rotation(const ArrangementSpec& arrangement);

/// Where one damper sits in one arrangement, relative to its point, structure frame.
struct DamperMounting {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< enclosure -> structure
    /// The enclosure's outer bottom face centre, on the beam face or on the block [m].
    Eigen::Vector3d mounting_face_m = Eigen::Vector3d::Zero();
    /// The enclosure frame origin (inner bottom centre) [m].
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
    /// Centre of gravity of the mounting block (when the arrangement has one) [m].
    Eigen::Vector3d block_cg_m = Eigen::Vector3d::Zero();

    /// A point given in the enclosure frame, from the damper's point, structure frame [m].
    [[nodiscard]] Eigen::Vector3d from_enclosure(const Eigen::Vector3d& local_m) const {
        return origin_m + rotation * local_m;
    }
};

/// The mounting of `damper` in `arrangement`. At 0 deg with no block the enclosure origin is
/// damper.mount_offset_m; its outer bottom face lies damper.bottom_thickness_m below the
/// origin along the axis. The enclosure turns about that face's centre, which the block (a
/// right isosceles wedge of cathetus c lying on one cathetus, the enclosure on its
/// hypotenuse) raises by c / 2 and arrangement.mount_lift_m moves further.
DamperMounting damper_mounting(const ArrangementSpec& arrangement, const DamperSpec& damper);

/// The enclosure's mass (a beam's lumped mass or an imported model's point mass, given for
/// 0 deg, no block) moved and turned with the enclosure: its centre of gravity follows the
/// mounting; its principal inertia about the enclosure axes is rotated, I' = R I R^T,
/// keeping the diagonal (such a mass carries no products of inertia; for paper 000's
/// enclosure the dropped product at 45 deg is (Iyy - Izz) / 2 = 1.2e-6 kg m^2, which couples
/// the first bending mode only to the stiff lateral rotation).
template <class Mass>
Mass mounted_enclosure_mass(const Mass& at_zero, const DamperSpec& damper,
                            const DamperMounting& mounting) {
    Mass m = at_zero;
    // At 0 deg the enclosure frame is the structure frame shifted to mount_offset_m.
    m.offset_m = mounting.from_enclosure(at_zero.offset_m - damper.mount_offset_m);
    const Eigen::Matrix3d inertia =
        mounting.rotation * at_zero.inertia_kg_m2.asDiagonal() * mounting.rotation.transpose();
    m.inertia_kg_m2 = inertia.diagonal();
    return m;
}

}  // namespace sb::bench

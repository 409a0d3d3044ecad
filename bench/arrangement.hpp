// Geometry of an arrangement: gravity in the structure frame and the damper's mounting
// rotation (paper 000, Figs. 1-2).
#pragma once

#include <Eigen/Core>

#include "bench/campaign_spec.hpp"

namespace sb::bench {

/// Gravity in the structure frame [m/s^2]. The shaker drives z. Horizontal oscillation: the
/// section's long side (y) is vertical, gravity along -y. Vertical oscillation: gravity
/// along -z.
Eigen::Vector3d arrangement_gravity(const ArrangementSpec& arrangement);

/// Rotation from the enclosure frame (axis = local z) to the structure frame: the axis tilted
/// from the motion (z) by the damper angle about the beam axis x, towards +y. At 0 deg the
/// axis is the motion; at 90 deg it is the section's long side (vertical when horizontal).
Eigen::Matrix3d mounting_rotation(const ArrangementSpec& arrangement);

}  // namespace sb::bench

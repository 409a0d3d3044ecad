// What an attachment at a point of the structure exchanges with it: the point's motion in, a
// load out, and the state it carries from one point to the next and through checkpoints.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "dem/solver_state.hpp"

namespace sb::bench {

/// Where a point of the structure is and how it moves (structure frame).
struct PointMotion {
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();    ///< rest position + displacement
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< of the point's small rotation
    Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();
    Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();
    /// The point's acceleration now, from the structure's last step (zero where a caller does
    /// not know it): what a load applied at the step's end extrapolates its velocity with.
    Eigen::Vector3d acceleration_m_s2 = Eigen::Vector3d::Zero();
};

/// Force [N] and moment [N m] at a point, structure frame.
struct PointLoad {
    Eigen::Vector3d force_n = Eigen::Vector3d::Zero();
    Eigen::Vector3d moment_nm = Eigen::Vector3d::Zero();
};

/// Particles a lock holds as one rigid body moving with a point (structure frame, at rest).
struct HeldBody {
    double mass_kg = 0.0;
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();       ///< centre of gravity from the point
    Eigen::Matrix3d inertia_kg_m2 = Eigen::Matrix3d::Zero();  ///< about the centre
};

/// What a describing-function damper carries between points: what it knows of its point's
/// motion.
struct DescribingState {
    double acceleration_m_s2 = 0.0;    ///< peak |a1| of the point's last whole period [m/s^2]
    double mean_displacement_m = 0.0;  ///< mean displacement along the direction over it [m]
};

/// What an attachment carries between points and through a checkpoint.
struct AttachmentState {
    std::optional<dem::SolverState> dem;         ///< a DEM damper's particles, histories and clock
    std::optional<DescribingState> describing;   ///< a describing-function damper's amplitude
    std::optional<std::vector<double>> sliders;  ///< an Iwan joint's slider positions [m]
    std::optional<double> coil_current_a;        ///< a shaker coil's back-EMF current [A]
};

}  // namespace sb::bench

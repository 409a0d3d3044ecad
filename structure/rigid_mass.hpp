// The 6x6 mass matrix of a rigid body referred to a node away from its centre of gravity.
#pragma once

#include <Eigen/Core>

namespace sb::structure {

/// Skew matrix [r]x with [r]x v = r x v.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
    Eigen::Matrix3d s;
    s << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
    return s;
}

/// Mass matrix on the node DOFs (ux, uy, uz, rx, ry, rz) of a rigid body of mass m [kg],
/// principal inertia j_cg [kg m^2] about its centre of gravity, the CG at offset r [m] from the
/// node. With v_cg = v + w x r = v - [r]x w, the kinetic energy T = 1/2 m |v_cg|^2 +
/// 1/2 w^T J w gives [m I, -m[r]x; m[r]x, J - m [r]x [r]x] (parallel-axis theorem in
/// matrix form; Shabana, Dynamics of Multibody Systems, eq. 3.124).
/// `j_cg`: the full inertia tensor about the centre of gravity, node axes.
inline Eigen::Matrix<double, 6, 6> rigid_body_mass(double m, const Eigen::Matrix3d& j_cg,
                                                   const Eigen::Vector3d& r) {
    const Eigen::Matrix3d s = skew(r);
    Eigen::Matrix<double, 6, 6> out;
    out.topLeftCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
    out.topRightCorner<3, 3>() = -m * s;
    out.bottomLeftCorner<3, 3>() = m * s;
    out.bottomRightCorner<3, 3>() = j_cg - m * s * s;
    return out;
}

/// `j_cg`: principal moments about axes parallel to the node's.
inline Eigen::Matrix<double, 6, 6> rigid_body_mass(double m, const Eigen::Vector3d& j_cg,
                                                   const Eigen::Vector3d& r) {
    return rigid_body_mass(m, Eigen::Matrix3d(j_cg.asDiagonal()), r);
}

}  // namespace sb::structure

// Stiffness and consistent mass of a straight two-node 3D beam element (12 DOFs).
#pragma once

#include <Eigen/Core>

#include "structure/section.hpp"

namespace sb::structure {

/// 12x12 element matrix; DOFs per node in order ux, uy, uz, rx, ry, rz (node 1 then node 2).
using ElementMatrix = Eigen::Matrix<double, 12, 12>;

/// Material and section of a beam element, SI.
struct BeamElementProperties {
    RectangularSection section;
    double density_kg_m3 = 0.0;
    double youngs_modulus_pa = 0.0;
    double shear_modulus_pa = 0.0;  ///< used for torsion, and for shear if timoshenko
    bool timoshenko = false;        ///< shear deformation and rotary inertia in bending
};

/// Stiffness matrix [N/m, N, N m] of an element of length length_m along the x axis.
ElementMatrix beam_element_stiffness(const BeamElementProperties& p, double length_m);

/// Consistent mass matrix [kg, kg m, kg m^2] of an element of length length_m along x.
ElementMatrix beam_element_mass(const BeamElementProperties& p, double length_m);

}  // namespace sb::structure

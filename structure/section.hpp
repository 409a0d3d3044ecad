// Properties of a solid rectangular beam section (areas, second moments, torsion constant).
#pragma once

namespace sb::structure {

/// Section of width b (along y) and thickness t (along z), in the beam frame of spec.hpp.
struct RectangularSection {
    double area_m2 = 0.0;              ///< A = b t [m^2]
    double second_moment_y_m4 = 0.0;   ///< I_y = b t^3 / 12, bending in the x-z plane (weak) [m^4]
    double second_moment_z_m4 = 0.0;   ///< I_z = t b^3 / 12, bending in the x-y plane (stiff) [m^4]
    double torsion_constant_m4 = 0.0;  ///< Saint-Venant torsion constant J [m^4]
    double shear_factor = 5.0 / 6.0;   ///< Timoshenko shear coefficient kappa of a rectangle [-]
};

/// Section properties of a b x t rectangle [m].
RectangularSection rectangular_section(double width_m, double thickness_m);

}  // namespace sb::structure

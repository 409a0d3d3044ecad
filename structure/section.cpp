// Properties of a solid rectangular beam section.
#include "structure/section.hpp"

#include <algorithm>
#include <cmath>

namespace sb::structure {

RectangularSection rectangular_section(double width_m, double thickness_m) {
    RectangularSection s;
    s.area_m2 = width_m * thickness_m;
    s.second_moment_y_m4 = width_m * std::pow(thickness_m, 3) / 12.0;
    s.second_moment_z_m4 = thickness_m * std::pow(width_m, 3) / 12.0;
    const double a = std::max(width_m, thickness_m);  // long side
    const double b = std::min(width_m, thickness_m);  // short side
    // Roark's Formulas for Stress and Strain, 7th ed., Table 10.7 case 4 (a >= b):
    // J = a b^3 [1/3 - 0.21 (b/a) (1 - b^4 / (12 a^4))].
    const double r = b / a;
    s.torsion_constant_m4 =
        a * std::pow(b, 3) * (1.0 / 3.0 - 0.21 * r * (1.0 - std::pow(r, 4) / 12.0));
    s.shear_factor = 5.0 / 6.0;  // Cowper/Timoshenko value for a rectangle, Cook et al. sec. 2.9
    return s;
}

}  // namespace sb::structure

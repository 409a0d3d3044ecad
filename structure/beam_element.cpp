// Stiffness and consistent mass of a straight two-node 3D beam element (12 DOFs).
#include "structure/beam_element.hpp"

#include <array>

namespace sb::structure {
namespace {

using Matrix4 = Eigen::Matrix4d;

/// Bending in one plane, DOFs (v1, theta1, v2, theta2) with theta = dv/dx.
/// Shear-deformable (Timoshenko) element with interdependent shape functions:
/// Przemieniecki, Theory of Matrix Structural Analysis (1968), eq. 5.116 (stiffness);
/// Phi = 12 E I / (kappa G A L^2); Phi = 0 gives the Euler-Bernoulli element.
Matrix4 bending_stiffness(double ei, double phi, double l) {
    Matrix4 k;
    k << 12.0, 6.0 * l, -12.0, 6.0 * l,                               //
        6.0 * l, (4.0 + phi) * l * l, -6.0 * l, (2.0 - phi) * l * l,  //
        -12.0, -6.0 * l, 12.0, -6.0 * l,                              //
        6.0 * l, (2.0 - phi) * l * l, -6.0 * l, (4.0 + phi) * l * l;
    return k * (ei / ((1.0 + phi) * l * l * l));
}

/// Consistent translational mass of the same element: Przemieniecki (1968) eq. 11.41;
/// also Friedman & Kosmatka, Computers & Structures 47 (1993) 473, eq. 21.
Matrix4 bending_translational_mass(double rho_a, double phi, double l) {
    const double p2 = phi * phi;
    const double m11 = 13.0 / 35.0 + 7.0 * phi / 10.0 + p2 / 3.0;
    const double m12 = (11.0 / 210.0 + 11.0 * phi / 120.0 + p2 / 24.0) * l;
    const double m13 = 9.0 / 70.0 + 3.0 * phi / 10.0 + p2 / 6.0;
    const double m14 = -(13.0 / 420.0 + 3.0 * phi / 40.0 + p2 / 24.0) * l;
    const double m22 = (1.0 / 105.0 + phi / 60.0 + p2 / 120.0) * l * l;
    const double m24 = -(1.0 / 140.0 + phi / 60.0 + p2 / 120.0) * l * l;
    Matrix4 m;
    m << m11, m12, m13, m14,   //
        m12, m22, -m14, m24,   //
        m13, -m14, m11, -m12,  //
        m14, m24, -m12, m22;
    return m * (rho_a * l / ((1.0 + phi) * (1.0 + phi)));
}

/// Consistent rotary-inertia mass of the same element: Przemieniecki (1968) eq. 11.42.
Matrix4 bending_rotary_mass(double rho_i, double phi, double l) {
    const double p2 = phi * phi;
    const double r11 = 6.0 / 5.0;
    const double r12 = (1.0 / 10.0 - phi / 2.0) * l;
    const double r22 = (2.0 / 15.0 + phi / 6.0 + p2 / 3.0) * l * l;
    const double r24 = (-1.0 / 30.0 - phi / 6.0 + p2 / 6.0) * l * l;
    Matrix4 m;
    m << r11, r12, -r11, r12,   //
        r12, r22, -r12, r24,    //
        -r11, -r12, r11, -r12,  //
        r12, r24, -r12, r22;
    return m * (rho_i / ((1.0 + phi) * (1.0 + phi) * l));
}

/// Two-node bar matrix c [1 -1; -1 1] or c/6 [2 1; 1 2] scattered to DOF d of both nodes.
void add_bar(ElementMatrix& out, int d, const Eigen::Matrix2d& m) {
    const std::array<int, 2> idx{d, d + 6};
    for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j) out(idx[i], idx[j]) += m(i, j);
    }
}

/// Scatters a bending-plane 4x4 matrix. Plane x-y: v = uy, theta = rz = dv/dx.
/// Plane x-z: v = uz, theta = -ry (since ry = -dw/dx), hence the sign on the rotations.
void add_plane(ElementMatrix& out, bool xz_plane, const Matrix4& m) {
    const std::array<int, 4> idx =
        xz_plane ? std::array<int, 4>{2, 4, 8, 10} : std::array<int, 4>{1, 5, 7, 11};
    const std::array<double, 4> sign = xz_plane ? std::array<double, 4>{1.0, -1.0, 1.0, -1.0}
                                                : std::array<double, 4>{1.0, 1.0, 1.0, 1.0};
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
            out(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]) +=
                sign[static_cast<std::size_t>(i)] * sign[static_cast<std::size_t>(j)] * m(i, j);
        }
    }
}

/// Shear parameter Phi = 12 E I / (kappa G A L^2) (Przemieniecki 1968, eq. 5.101).
double shear_parameter(const BeamElementProperties& p, double second_moment, double l) {
    if (!p.timoshenko) return 0.0;
    return 12.0 * p.youngs_modulus_pa * second_moment /
           (p.section.shear_factor * p.shear_modulus_pa * p.section.area_m2 * l * l);
}

}  // namespace

ElementMatrix beam_element_stiffness(const BeamElementProperties& p, double length_m) {
    const double l = length_m;
    const auto& s = p.section;
    ElementMatrix k = ElementMatrix::Zero();
    Eigen::Matrix2d bar;
    bar << 1.0, -1.0, -1.0, 1.0;
    add_bar(k, 0, bar * (p.youngs_modulus_pa * s.area_m2 / l));             // axial EA/L
    add_bar(k, 3, bar * (p.shear_modulus_pa * s.torsion_constant_m4 / l));  // torsion GJ/L
    add_plane(k, false,
              bending_stiffness(p.youngs_modulus_pa * s.second_moment_z_m4,
                                shear_parameter(p, s.second_moment_z_m4, l), l));
    add_plane(k, true,
              bending_stiffness(p.youngs_modulus_pa * s.second_moment_y_m4,
                                shear_parameter(p, s.second_moment_y_m4, l), l));
    return k;
}

ElementMatrix beam_element_mass(const BeamElementProperties& p, double length_m) {
    const double l = length_m;
    const auto& s = p.section;
    const double rho = p.density_kg_m3;
    ElementMatrix m = ElementMatrix::Zero();
    Eigen::Matrix2d bar;
    bar << 2.0, 1.0, 1.0, 2.0;
    add_bar(m, 0, bar * (rho * s.area_m2 * l / 6.0));  // axial, linear shape functions
    // Torsion: rotary inertia per length rho I_p, I_p = I_y + I_z (polar moment of area).
    add_bar(m, 3, bar * (rho * (s.second_moment_y_m4 + s.second_moment_z_m4) * l / 6.0));
    for (const bool xz : {false, true}) {
        const double second_moment = xz ? s.second_moment_y_m4 : s.second_moment_z_m4;
        const double phi = shear_parameter(p, second_moment, l);
        add_plane(m, xz, bending_translational_mass(rho * s.area_m2, phi, l));
        // Euler-Bernoulli: classical theory without rotary inertia; Timoshenko: with it.
        if (p.timoshenko) add_plane(m, xz, bending_rotary_mass(rho * second_moment, phi, l));
    }
    return m;
}

}  // namespace sb::structure

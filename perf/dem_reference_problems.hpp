// Set-up shared by the DEM benchmarks (dem_benchmark, dem_throughput): the enclosure motion
// and paper 002's cavity.
#pragma once

#include <cmath>

#include "dem/solver.hpp"

namespace sb::dem::perf {

/// Enclosure moved along z as z = A (1 - cos wt) from rest, like LAMMPS's `wiggle` and
/// validation/lammps/in.damper.
inline EnclosureState axial_wiggle(double t_s, double amplitude_m, double omega_rad_s) {
    EnclosureState e;
    e.position_m = Eigen::Vector3d(0, 0, amplitude_m * (1.0 - std::cos(omega_rad_s * t_s)));
    e.velocity_m_s = Eigen::Vector3d(0, 0, amplitude_m * omega_rad_s * std::sin(omega_rad_s * t_s));
    return e;
}

/// `count` 2 mm spheres in paper 002's 30 x 30 x 50 mm cavity, Hooke k = 1e5 N/m.
inline SolverOptions paper002_cavity_options(int count) {
    SolverOptions o;
    o.particles.count = count;
    o.particles.diameter_m = 2e-3;
    o.enclosure.shape = EnclosureShape::box;
    o.enclosure.length_x_m = 30e-3;
    o.enclosure.length_y_m = 30e-3;
    o.enclosure.height_m = 50e-3;
    o.contact.normal_stiffness = 1e5;
    return o;
}

}  // namespace sb::dem::perf

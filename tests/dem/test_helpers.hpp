// Shared set-ups for the DEM tests.
#pragma once

#include "dem/setup.hpp"
#include "dem/solver.hpp"

namespace sb::dem::test {

/// A 0.1 m box without gravity or friction, `count` 3 mm steel spheres.
inline SolverOptions free_box_options(int count, NormalLaw law) {
    SolverOptions o;
    o.particles.count = count;
    o.particles.diameter_m = 3e-3;
    o.enclosure.shape = EnclosureShape::box;
    o.enclosure.length_x_m = 0.1;
    o.enclosure.length_y_m = 0.1;
    o.enclosure.height_m = 0.1;
    o.gravity_m_s2.setZero();
    o.contact.normal = law;
    o.contact.normal_stiffness = law == NormalLaw::hooke ? 1e5 : 0.0;
    o.contact.tangential = TangentialLaw::none;
    o.contact.rolling = RollingLaw::none;
    return o;
}

inline ParticleSet particles_at(std::vector<Eigen::Vector3d> x, double radius,
                                std::vector<Eigen::Vector3d> v = {}) {
    ParticleSet s;
    s.radii_m.assign(x.size(), radius);
    s.positions_m = std::move(x);
    s.velocities_m_s = std::move(v);
    return s;
}

/// Paper-000 damper: 120 x 3 mm steel spheres in a 19 mm x 25 mm cylinder (Table 1).
inline SolverOptions paper000_options() {
    SolverOptions o;
    o.particles.count = 120;
    o.particles.diameter_m = 3e-3;
    o.contact.normal = NormalLaw::hooke;
    o.contact.normal_stiffness = 2e4;
    o.contact.particle_particle = {0.9, 0.6, 0.01};
    o.contact.particle_wall = {0.9, 0.6, 0.01};
    return o;
}

}  // namespace sb::dem::test

// Shared set-ups for the DEM tests.
#pragma once

#include <algorithm>
#include <cmath>

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

/// Simple cubic lattice of 2 mm spheres pressed 2 um into each other and into the walls and
/// the floor, jittered by up to 0.5 um: every particle starts with several contacts.
inline ParticleSet pressed_lattice(int per_side, double spacing) {
    ParticleSet p;
    const double r = 1e-3;
    const double x0 = -0.5 * (per_side - 1) * spacing;
    for (int iz = 0; iz < per_side; ++iz) {
        for (int iy = 0; iy < per_side; ++iy) {
            for (int ix = 0; ix < per_side; ++ix) {
                const int id = (iz * per_side + iy) * per_side + ix;
                auto jitter = [id](int axis) {  // deterministic, in [-0.5, 0.5] um
                    return 1e-6 *
                           (static_cast<double>((id * 7919 + axis * 104729) % 1001) / 1000.0 - 0.5);
                };
                p.positions_m.emplace_back(x0 + ix * spacing + jitter(0),
                                           x0 + iy * spacing + jitter(1),
                                           r - 2e-6 + iz * spacing + jitter(2));
                p.radii_m.push_back(r);
            }
        }
    }
    return p;
}

/// Solid fraction of the axis-aligned region [lo, hi] (enclosure frame): the share of a
/// regular lattice of m^3 sample points (cell centres) that lies inside a sphere. Counted per
/// sphere over the lattice points of its bounding box, so the cost is N (2 r m / L)^3. The
/// lattice error is about the surface-to-volume ratio times the spacing squared, well below
/// 1e-2 for spacings under a tenth of the radius.
inline double packing_fraction_in(const ParticleSet& p, const Eigen::Vector3d& lo,
                                  const Eigen::Vector3d& hi, int m) {
    const Eigen::Vector3d h = (hi - lo) / m;
    long long inside = 0;
    for (std::size_t i = 0; i < p.positions_m.size(); ++i) {
        const Eigen::Vector3d& x = p.positions_m[i];
        const double r = p.radii_m[i];
        int a0[3], a1[3];
        for (int a = 0; a < 3; ++a) {
            a0[a] = std::max(0, static_cast<int>(std::floor((x[a] - r - lo[a]) / h[a] - 0.5)));
            a1[a] = std::min(m - 1, static_cast<int>(std::ceil((x[a] + r - lo[a]) / h[a] - 0.5)));
        }
        for (int u = a0[0]; u <= a1[0]; ++u) {
            for (int v = a0[1]; v <= a1[1]; ++v) {
                for (int w = a0[2]; w <= a1[2]; ++w) {
                    const Eigen::Vector3d q =
                        lo +
                        Eigen::Vector3d((u + 0.5) * h.x(), (v + 0.5) * h.y(), (w + 0.5) * h.z());
                    if ((q - x).squaredNorm() < r * r) ++inside;
                }
            }
        }
    }
    return static_cast<double>(inside) / (static_cast<double>(m) * m * m);
}

/// Largest pair overlap / smaller radius over all pairs (O(N^2), for small tests) [-].
inline double largest_pair_overlap_fraction(const ParticleSet& p) {
    double worst = 0.0;
    for (std::size_t i = 0; i < p.positions_m.size(); ++i) {
        for (std::size_t j = 0; j < i; ++j) {
            const double gap =
                (p.positions_m[i] - p.positions_m[j]).norm() - (p.radii_m[i] + p.radii_m[j]);
            worst = std::max(worst, -gap / std::min(p.radii_m[i], p.radii_m[j]));
        }
    }
    return worst;
}

}  // namespace sb::dem::test

// Rigid enclosure geometry in its own frame (cylinder or box, rods, plates) and its motion.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dem/options.hpp"

namespace sb::dem {

/// Pose and rigid-body velocity of the enclosure, world (structure) frame.
struct EnclosureState {
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();              ///< frame origin [m]
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();            ///< local -> world
    Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();            ///< of the origin [m/s]
    Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();  ///< world [rad/s]

    /// Wall velocity at world point x: v + omega x (x - x_c) [m/s]. Per wall contact in the
    /// sweep, where the compiler left it as a call (4 % of a step of paper 002's grid bed):
    /// forced inline.
    [[gnu::always_inline]] Eigen::Vector3d velocity_at(const Eigen::Vector3d& x) const {
        return velocity_m_s + angular_velocity_rad_s.cross(x - position_m);
    }
    // to_local and rotate run per particle and per wall contact in the DEM sweep, where the
    // compiler left them as calls (about 8 % of a step of a rocking enclosure): forced inline.
    [[gnu::always_inline]] Eigen::Vector3d to_local(const Eigen::Vector3d& x) const {
        const Eigen::Vector3d d = x - position_m;  // R^T d, written out so that it inlines
        return {rotation.col(0).dot(d), rotation.col(1).dot(d), rotation.col(2).dot(d)};
    }
    Eigen::Vector3d to_world(const Eigen::Vector3d& xl) const {
        return position_m + rotation.col(0) * xl.x() + rotation.col(1) * xl.y() +
               rotation.col(2) * xl.z();
    }
    /// A local direction in world coordinates.
    [[gnu::always_inline]] Eigen::Vector3d rotate(const Eigen::Vector3d& nl) const {
        return rotation.col(0) * nl.x() + rotation.col(1) * nl.y() + rotation.col(2) * nl.z();
    }
    /// False if any component of the pose or velocity is NaN or infinite.
    bool finite() const {
        return position_m.allFinite() && rotation.allFinite() && velocity_m_s.allFinite() &&
               angular_velocity_rad_s.allFinite();
    }
};

/// Geometry queries in the enclosure frame.
class Enclosure {
  public:
    explicit Enclosure(const EnclosureOptions& options);

    const EnclosureOptions& options() const { return options_; }
    /// Axis-aligned bounds of the cavity [m].
    const Eigen::Vector3d& lower() const { return lo_; }
    const Eigen::Vector3d& upper() const { return hi_; }
    /// Cavity volume without obstacles [m^3].
    double volume() const;
    /// True if the centre xl lies inside the cavity and not inside a solid obstacle (a plate
    /// or a rod of the obstacle grid). False for a non-finite xl.
    bool contains(const Eigen::Vector3d& xl) const {
        return inside_walls(xl) && !inside_obstacle(xl);
    }
    /// True if the centre xl lies inside the outer walls (obstacles ignored).
    bool inside_walls(const Eigen::Vector3d& xl) const {
        // written so that NaN compares as outside
        if (!(xl.z() >= lo_.z() && xl.z() <= hi_.z())) return false;
        if (options_.shape == EnclosureShape::cylinder) {
            return xl.x() * xl.x() + xl.y() * xl.y() <= radius_ * radius_;
        }
        return xl.x() >= lo_.x() && xl.x() <= hi_.x() && xl.y() >= lo_.y() && xl.y() <= hi_.y();
    }
    /// True if the point xl lies strictly inside a plate or a rod.
    bool inside_obstacle(const Eigen::Vector3d& xl) const;
    /// Shortest distance from xl to the walls and obstacles (negative if inside a solid) [m].
    double clearance(const Eigen::Vector3d& xl) const;

    /// Calls emit(wall_id, n_local, delta) for each wall or obstacle the sphere (xl, r)
    /// overlaps; n points from the wall into the cavity (towards the sphere centre).
    template <class Emit>
    void for_each_contact(const Eigen::Vector3d& xl, double r, Emit&& emit) const;
    /// for_each_contact(xl, r, emit), returning contains(xl): the rod lattice's nearest nodes,
    /// which both need, found once (the DEM sweep's outside guard and wall contacts of a
    /// sphere among rods; twice as many rounded divisions cost a sixth of a grid bed's step).
    template <class Emit>
    bool contacts_and_contains(const Eigen::Vector3d& xl, double r, Emit&& emit) const;
    /// Wall ids below this one are the lateral surface (the walls along the axis: the
    /// cylinder's side, the box's four faces), the rest the ends, plates and rods.
    std::uint32_t lateral_wall_ids() const {
        return options_.shape == EnclosureShape::cylinder ? 1u : 4u;
    }

  private:
    /// The rod lattice's nearest node along each enclosure axis (a whole number of cells from
    /// the origin) and the centre's offset from it [m].
    struct RodNodes {
        double node[3];
        double offset[3];
    };
    RodNodes rod_nodes(const Eigen::Vector3d& xl) const;
    bool inside_plate(const Eigen::Vector3d& xl) const;
    template <class Emit>
    void walls_and_plates_contacts(const Eigen::Vector3d& xl, double r, Emit& emit) const;
    /// Emits the rods the sphere overlaps; true if its centre lies strictly inside one (the
    /// outside guard's test, from the squared distances computed here anyway).
    template <class Emit>
    bool rods_contacts(const RodNodes& nodes, double r, Emit& emit) const;

    EnclosureOptions options_;
    Eigen::Vector3d lo_, hi_;
    double radius_ = 0.0;
    int rod_lo_[3]{0, 0, 0}, rod_hi_[3]{-1, -1, -1};  ///< lattice index range per axis
};

/// Wall ids: cylinder side 0, bottom 1, top 2; box faces 0..5 (-x,+x,-y,+y,bottom,top);
/// plates from kPlateBase; rods from kRodBase.
inline constexpr std::uint32_t kPlateBase = 16;
inline constexpr std::uint32_t kRodBase = 1u << 16;

/// Horizontal layers of the cavity for the energy dissipation per layer (paper 002, Fig. 13:
/// layers counted upwards from the bottom of the bed). `count` slabs of equal thickness
/// normal to `up`, the direction against gravity in the enclosure frame, spanning the
/// cavity's extent along `up`. With the axis vertical (up = local z) the slabs are those along
/// local z; with the axis horizontal they still stack along gravity.
class HorizontalLayers {
  public:
    HorizontalLayers() = default;
    /// up_local need not be unit; zero means local z.
    HorizontalLayers(const Enclosure& enclosure, const Eigen::Vector3d& up_local, int count);
    /// Layers for gravity g (world frame) with the enclosure at `pose` (the rest pose): up is
    /// -g expressed in the enclosure frame; the layers then move with the enclosure.
    static HorizontalLayers for_gravity(const Enclosure& enclosure, const EnclosureState& pose,
                                        const Eigen::Vector3d& gravity_world, int count);

    int count() const { return count_; }
    const Eigen::Vector3d& up() const { return up_; }
    /// Height range of the cavity along up [m].
    double lowest() const { return lo_; }
    double highest() const { return lo_ + span_; }
    /// Layer of the enclosure-frame point xl, 0 = bottom; points beyond the range go to the
    /// first or last layer.
    int index(const Eigen::Vector3d& xl) const {
        const double h = up_.x() * xl.x() + up_.y() * xl.y() + up_.z() * xl.z();
        const double f = (h - lo_) / span_ * count_;
        if (!(f > 0.0)) return 0;  // also NaN
        return f >= count_ ? count_ - 1 : static_cast<int>(f);
    }

  private:
    Eigen::Vector3d up_{0.0, 0.0, 1.0};
    double lo_ = 0.0, span_ = 1.0;
    int count_ = 0;
};

inline Enclosure::RodNodes Enclosure::rod_nodes(const Eigen::Vector3d& xl) const {
    const auto& g = options_.rods;
    const double s = g.cell_size_m;
    RodNodes n;
    for (int k = 0; k < 3; ++k) {
        n.node[k] = std::round((xl[k] - g.origin_m[k]) / s);
        n.offset[k] = xl[k] - (g.origin_m[k] + n.node[k] * s);
    }
    return n;
}

inline bool Enclosure::inside_plate(const Eigen::Vector3d& xl) const {
    for (const auto& pl : options_.plates) {
        if ((xl.array() > pl.min_corner_m.array()).all() &&
            (xl.array() < pl.max_corner_m.array()).all()) {
            return true;
        }
    }
    return false;
}

inline bool Enclosure::inside_obstacle(const Eigen::Vector3d& xl) const {
    if (inside_plate(xl)) return true;
    if (!options_.rods.enabled) return false;
    auto ignore = [](std::uint32_t, const Eigen::Vector3d&, double) {};
    return rods_contacts(rod_nodes(xl), 0.0, ignore);  // its centre test, no contacts wanted
}

template <class Emit>
void Enclosure::for_each_contact(const Eigen::Vector3d& xl, double r, Emit&& emit) const {
    walls_and_plates_contacts(xl, r, emit);
    if (options_.rods.enabled) rods_contacts(rod_nodes(xl), r, emit);
}

template <class Emit>
bool Enclosure::contacts_and_contains(const Eigen::Vector3d& xl, double r, Emit&& emit) const {
    walls_and_plates_contacts(xl, r, emit);
    const bool inside = inside_walls(xl) && !inside_plate(xl);
    if (!options_.rods.enabled) return inside;
    const bool in_rod = rods_contacts(rod_nodes(xl), r, emit);
    return inside && !in_rod;
}

template <class Emit>
void Enclosure::walls_and_plates_contacts(const Eigen::Vector3d& xl, double r, Emit& emit) const {
    if (options_.shape == EnclosureShape::cylinder) {
        const double rho = std::sqrt(xl.x() * xl.x() + xl.y() * xl.y());
        const double d = rho + r - radius_;
        if (d > 0.0) {
            Eigen::Vector3d n = rho > 0.0 ? Eigen::Vector3d(-xl.x() / rho, -xl.y() / rho, 0.0)
                                          : Eigen::Vector3d(-1.0, 0.0, 0.0);
            emit(0u, n, d);
        }
        if (xl.z() - r < lo_.z()) emit(1u, Eigen::Vector3d(0, 0, 1), lo_.z() - (xl.z() - r));
        if (xl.z() + r > hi_.z()) emit(2u, Eigen::Vector3d(0, 0, -1), xl.z() + r - hi_.z());
    } else {
        for (int a = 0; a < 3; ++a) {
            if (xl[a] - r < lo_[a]) {
                Eigen::Vector3d n = Eigen::Vector3d::Zero();
                n[a] = 1.0;
                emit(static_cast<std::uint32_t>(2 * a), n, lo_[a] - (xl[a] - r));
            }
            if (xl[a] + r > hi_[a]) {
                Eigen::Vector3d n = Eigen::Vector3d::Zero();
                n[a] = -1.0;
                emit(static_cast<std::uint32_t>(2 * a + 1), n, xl[a] + r - hi_[a]);
            }
        }
    }
    for (std::size_t p = 0; p < options_.plates.size(); ++p) {
        const auto& pl = options_.plates[p];
        const Eigen::Vector3d q = xl.cwiseMax(pl.min_corner_m).cwiseMin(pl.max_corner_m);
        const Eigen::Vector3d d = xl - q;
        const double dist = d.norm();
        if (dist >= r) continue;
        Eigen::Vector3d n;
        double delta;
        if (dist > 0.0) {
            n = d / dist;
            delta = r - dist;
        } else {  // centre inside the solid: push out through the nearest face
            double best = 1e300;
            n = Eigen::Vector3d(0, 0, 1);
            for (int a = 0; a < 3; ++a) {
                const double dl = xl[a] - pl.min_corner_m[a], dh = pl.max_corner_m[a] - xl[a];
                if (dl < best) {
                    best = dl;
                    n = Eigen::Vector3d::Zero();
                    n[a] = -1.0;
                }
                if (dh < best) {
                    best = dh;
                    n = Eigen::Vector3d::Zero();
                    n[a] = 1.0;
                }
            }
            delta = r + best;
        }
        emit(kPlateBase + static_cast<std::uint32_t>(p), n, delta);
    }
}

template <class Emit>
bool Enclosure::rods_contacts(const RodNodes& nodes, double r, Emit& emit) const {
    const double rr = 0.5 * options_.rods.rod_diameter_m;
    bool in_rod = false;
    // Rods along axis a sit at lattice nodes of the two other axes; the nearest line per axis
    // is the only candidate because validate() demands d_particle + d_rod <= cell size.
    for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        const double fb = nodes.node[b], fc = nodes.node[c];
        // compared as doubles first: a non-finite centre (NaN nodes) fails here, before the
        // conversion to int, which would be undefined for it
        if (!(fb >= rod_lo_[b] && fb <= rod_hi_[b] && fc >= rod_lo_[c] && fc <= rod_hi_[c])) {
            continue;
        }
        const int ib = static_cast<int>(fb), ic = static_cast<int>(fc);
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        d[b] = nodes.offset[b];
        d[c] = nodes.offset[c];
        const double d2 = d.squaredNorm();
        if (d2 < rr * rr) in_rod = true;
        const double dist = std::sqrt(d2);
        const double delta = r + rr - dist;
        if (delta <= 0.0) continue;
        Eigen::Vector3d n = dist > 0.0 ? Eigen::Vector3d(d / dist) : Eigen::Vector3d(0, 0, 1);
        if (dist <= 0.0 && a == 2) n = Eigen::Vector3d(1, 0, 0);
        const auto id = kRodBase + static_cast<std::uint32_t>(a) * (1u << 14) +
                        static_cast<std::uint32_t>((ib + 64) & 127) * 128u +
                        static_cast<std::uint32_t>((ic + 64) & 127);
        emit(id, n, delta);
    }
    return in_rod;
}

}  // namespace sb::dem

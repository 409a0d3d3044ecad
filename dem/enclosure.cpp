// Enclosure geometry set-up, queries that are not on the hot path, horizontal layers.
#include "dem/enclosure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/units.hpp"

namespace sb::dem {

Enclosure::Enclosure(const EnclosureOptions& options) : options_(options) {
    if (options_.shape == EnclosureShape::cylinder) {
        radius_ = 0.5 * options_.inner_diameter_m;
        lo_ = Eigen::Vector3d(-radius_, -radius_, 0.0);
        hi_ = Eigen::Vector3d(radius_, radius_, options_.height_m);
    } else {
        lo_ = Eigen::Vector3d(-0.5 * options_.length_x_m, -0.5 * options_.length_y_m, 0.0);
        hi_ = Eigen::Vector3d(0.5 * options_.length_x_m, 0.5 * options_.length_y_m,
                              options_.height_m);
    }
    if (options_.rods.enabled && options_.rods.cell_size_m > 0.0) {
        const auto& g = options_.rods;
        for (int a = 0; a < 3; ++a) {
            rod_lo_[a] = static_cast<int>(std::ceil((lo_[a] - g.origin_m[a]) / g.cell_size_m));
            rod_hi_[a] = static_cast<int>(std::floor((hi_[a] - g.origin_m[a]) / g.cell_size_m));
            // rods lying on the walls themselves are not obstacles
            if (g.origin_m[a] + rod_lo_[a] * g.cell_size_m <= lo_[a] + 1e-12) ++rod_lo_[a];
            if (g.origin_m[a] + rod_hi_[a] * g.cell_size_m >= hi_[a] - 1e-12) --rod_hi_[a];
        }
    }
}

double Enclosure::volume() const {
    if (options_.shape == EnclosureShape::cylinder) return kPi * radius_ * radius_ * hi_.z();
    return (hi_ - lo_).prod();
}

double Enclosure::clearance(const Eigen::Vector3d& xl) const {
    // Largest r with no contact: probe with a big sphere and take the smallest gap.
    const double big = (hi_ - lo_).norm();
    double gap = std::numeric_limits<double>::infinity();
    for_each_contact(xl, big, [&](std::uint32_t, const Eigen::Vector3d&, double delta) {
        gap = std::min(gap, big - delta);
    });
    return gap;
}

HorizontalLayers::HorizontalLayers(const Enclosure& enclosure, const Eigen::Vector3d& up_local,
                                   int count)
    : count_(std::max(0, count)) {
    const double norm = up_local.norm();
    up_ = norm > 0.0 && std::isfinite(norm) ? Eigen::Vector3d(up_local / norm)
                                            : Eigen::Vector3d(0.0, 0.0, 1.0);
    // Support function of the cavity along up: the box corners, or for the cylinder the axis
    // segment widened by the radius times the lateral part of up.
    const Eigen::Vector3d lo = enclosure.lower(), hi = enclosure.upper();
    double h_lo = 0.0, h_hi = 0.0;
    if (enclosure.options().shape == EnclosureShape::cylinder) {
        const double lateral = std::sqrt(up_.x() * up_.x() + up_.y() * up_.y());
        const double r = 0.5 * enclosure.options().inner_diameter_m;
        h_lo = std::min(up_.z() * lo.z(), up_.z() * hi.z()) - r * lateral;
        h_hi = std::max(up_.z() * lo.z(), up_.z() * hi.z()) + r * lateral;
    } else {
        for (int a = 0; a < 3; ++a) {
            h_lo += std::min(up_[a] * lo[a], up_[a] * hi[a]);
            h_hi += std::max(up_[a] * lo[a], up_[a] * hi[a]);
        }
    }
    lo_ = h_lo;
    span_ = h_hi - h_lo;
}

HorizontalLayers HorizontalLayers::for_gravity(const Enclosure& enclosure,
                                               const EnclosureState& pose,
                                               const Eigen::Vector3d& gravity_world, int count) {
    return HorizontalLayers(enclosure, pose.rotation.transpose() * (-gravity_world), count);
}

}  // namespace sb::dem

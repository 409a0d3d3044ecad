// Enclosure geometry set-up and queries that are not on the hot path.
#include "dem/enclosure.hpp"

#include <algorithm>
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

}  // namespace sb::dem

// Validation of the DEM option structs: every violation is collected, keys relative to the struct.
#include "dem/options.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sb::dem {

Violations Material::validate() const {
    Violations out;
    require_positive(out, "density_kg_m3", density_kg_m3, "mass density [kg/m^3]");
    require_positive(out, "youngs_modulus_pa", youngs_modulus_pa, "Young's modulus [Pa]");
    require_in_range(out, "poisson_ratio", poisson_ratio, -0.999, 0.4999, "Poisson ratio [-]");
    return out;
}

Violations PairProperties::validate() const {
    Violations out;
    if (!(restitution > 0.0 && restitution <= 1.0)) {
        out.push_back({"restitution", format_value(restitution), "must be in (0, 1]",
                       "normal coefficient of restitution [-]"});
    }
    require_non_negative(out, "sliding_friction", sliding_friction, "sliding friction [-]");
    require_non_negative(out, "rolling_friction", rolling_friction, "rolling friction [-]");
    require_non_negative(out, "dissipative_constant_s", dissipative_constant_s,
                         "viscoelastic dissipative constant [s]");
    require_non_negative(out, "dashpot_n_s_per_m", dashpot_n_s_per_m,
                         "viscous dashpot coefficient [N s/m]");
    return out;
}

Violations ParticleOptions::validate() const {
    Violations out;
    if (count < 1) {
        out.push_back({"count", std::to_string(count), "must be >= 1", "number of particles"});
    }
    if (size_distribution.empty()) {
        require_positive(out, "diameter_m", diameter_m, "particle diameter [m]");
    } else {
        double sum = 0.0;
        for (std::size_t k = 0; k < size_distribution.size(); ++k) {
            const std::string key = "size_distribution[" + std::to_string(k) + "]";
            require_positive(out, key + ".diameter_m", size_distribution[k].diameter_m,
                             "particle diameter [m]");
            require_positive(out, key + ".number_fraction", size_distribution[k].number_fraction,
                             "share of the particle count [-]");
            sum += size_distribution[k].number_fraction;
        }
        if (std::abs(sum - 1.0) > 1e-6) {
            out.push_back({"size_distribution", format_value(sum), "fractions must sum to 1",
                           "number fractions of the size classes"});
        }
    }
    require_in_range(out, "diameter_scatter", diameter_scatter, 0.0, kMaxDiameterScatter,
                     "relative standard deviation of the diameters [-]");
    append_prefixed(out, "material", material.validate());
    return out;
}

double ParticleOptions::largest_diameter_m() const {
    double d = size_distribution.empty() ? diameter_m : 0.0;
    for (const auto& s : size_distribution) d = std::max(d, s.diameter_m);
    // u in make_radii reaches sqrt(3): the bound of a uniform law of unit variance.
    return d * (1.0 + std::sqrt(3.0) * diameter_scatter);
}

double ParticleOptions::smallest_diameter_m() const {
    double d = size_distribution.empty() ? diameter_m : std::numeric_limits<double>::infinity();
    for (const auto& s : size_distribution) d = std::min(d, s.diameter_m);
    return d * (1.0 - std::sqrt(3.0) * diameter_scatter);
}

namespace {
const char* normal_name(NormalLaw n) { return n == NormalLaw::hooke ? "hooke" : "hertz"; }
}  // namespace

Violations ContactOptions::validate() const {
    Violations out;
    if (normal == NormalLaw::hooke) {
        require_positive(out, "normal_stiffness", normal_stiffness,
                         "Hooke normal spring constant [N/m]");
    } else {
        require_non_negative(out, "normal_stiffness", normal_stiffness,
                             "Hertz constant [N/m^1.5] (0 = from the materials)");
    }
    require_non_negative(out, "wall_normal_stiffness", wall_normal_stiffness,
                         "wall spring constant [N/m] (0 = normal_stiffness)");
    if (normal == NormalLaw::hertz && wall_normal_stiffness > 0.0) {
        out.push_back({"wall_normal_stiffness", format_value(wall_normal_stiffness),
                       "only with normal = hooke", "wall spring constant [N/m]"});
    }
    if (damping == DampingLaw::linear_dashpot && normal == NormalLaw::hertz) {
        out.push_back({"damping", "linear_dashpot", "incompatible with normal = hertz",
                       "damping piece (use hertz_dashpot or restitution)"});
    }
    if (damping == DampingLaw::viscoelastic && normal == NormalLaw::hooke) {
        out.push_back({"damping", "viscoelastic", "incompatible with normal = hooke",
                       "damping piece (viscoelastic needs normal = hertz)"});
    }
    if (damping == DampingLaw::hertz_dashpot && normal == NormalLaw::hooke) {
        out.push_back({"damping", "hertz_dashpot",
                       std::string("incompatible with normal = ") + normal_name(normal),
                       "damping piece (use linear_dashpot or restitution)"});
    }
    require_positive(out, "tangential_stiffness_ratio", tangential_stiffness_ratio,
                     "tangential / normal stiffness [-]");
    require_positive(out, "slip_regularisation_m_s", slip_regularisation_m_s,
                     "slip speed of the friction ramp [m/s]");
    append_prefixed(out, "particle_particle", particle_particle.validate());
    append_prefixed(out, "particle_wall", particle_wall.validate());
    append_prefixed(out, "wall_material", wall_material.validate());
    if (particle_side) append_prefixed(out, "particle_side", particle_side->validate());
    if (side_material) append_prefixed(out, "side_material", side_material->validate());
    if (particle_rod) append_prefixed(out, "particle_rod", particle_rod->validate());
    if (rod_material) append_prefixed(out, "rod_material", rod_material->validate());
    return out;
}

Violations RodGridOptions::validate() const {
    Violations out;
    if (!enabled) return out;
    require_positive(out, "rod_diameter_m", rod_diameter_m, "rod diameter [m]");
    require_positive(out, "cell_size_m", cell_size_m, "lattice spacing [m]");
    return out;
}

Violations EnclosureOptions::validate() const {
    Violations out;
    if (shape == EnclosureShape::cylinder) {
        require_positive(out, "inner_diameter_m", inner_diameter_m, "cylinder inner diameter [m]");
    } else {
        require_positive(out, "length_x_m", length_x_m, "box inner length along x [m]");
        require_positive(out, "length_y_m", length_y_m, "box inner length along y [m]");
    }
    require_positive(out, "height_m", height_m, "inner height [m]");
    append_prefixed(out, "rods", rods.validate());
    for (std::size_t k = 0; k < plates.size(); ++k) {
        const auto& p = plates[k];
        if (!(p.min_corner_m.array() < p.max_corner_m.array()).all()) {
            out.push_back({"plates[" + std::to_string(k) + "]", "min_corner_m >= max_corner_m",
                           "min_corner_m < max_corner_m on every axis", "plate extent [m]"});
        }
    }
    return out;
}

Violations LockOptions::validate() const {
    Violations out;
    require_in_range(out, "fraction", fraction, 0.0, 1.0, "share of locked particles [-]");
    require_non_negative(out, "release_time_s", release_time_s, "release time [s]");
    require_in_range(out, "release_fraction", release_fraction, 0.0, 1.0,
                     "share of particles freed at the release [-]");
    for (std::size_t k = 0; k < particle_ids.size(); ++k) {
        if (particle_ids[k] < 0) {
            out.push_back({"particle_ids[" + std::to_string(k) + "]",
                           std::to_string(particle_ids[k]), "must be >= 0", "locked particle id"});
        }
    }
    return out;
}

Violations SolverOptions::validate() const {
    Violations out;
    append_prefixed(out, "particles", particles.validate());
    append_prefixed(out, "contact", contact.validate());
    append_prefixed(out, "enclosure", enclosure.validate());
    append_prefixed(out, "lock", lock.validate());
    for (std::size_t k = 0; k < lock.particle_ids.size(); ++k) {
        if (lock.particle_ids[k] >= particles.count) {
            out.push_back({"lock.particle_ids[" + std::to_string(k) + "]",
                           std::to_string(lock.particle_ids[k]), "must be < particles.count",
                           "locked particle id"});
        }
    }
    if (!gravity_m_s2.allFinite()) {
        out.push_back({"gravity_m_s2", "non-finite", "must be finite", "gravity [m/s^2]"});
    }
    require_in_range(out, "max_overlap_fraction", max_overlap_fraction, 1e-6, 1.0,
                     "largest overlap / radius before the guard fires [-]");
    require_in_range(out, "neighbor_skin_fraction", neighbor_skin_fraction, 0.0, 1.0,
                     "Verlet skin / largest diameter [-]");
    if (threads < 0) {
        out.push_back({"threads", std::to_string(threads), "must be >= 0", "OpenMP threads"});
    }
    if (parallel_grain < 1) {
        out.push_back({"parallel_grain", std::to_string(parallel_grain), "must be >= 1",
                       "smallest loop share per OpenMP thread"});
    }
    if (energy_layers < 0) {
        out.push_back({"energy_layers", std::to_string(energy_layers), "must be >= 0",
                       "number of layers for the dissipation per layer"});
    }
    if (enclosure.rods.enabled) {
        const double need = particles.largest_diameter_m() + enclosure.rods.rod_diameter_m;
        if (need > enclosure.rods.cell_size_m) {
            out.push_back(
                {"enclosure.rods.cell_size_m", format_value(enclosure.rods.cell_size_m),
                 "must be >= largest particle diameter + rod diameter (" + format_value(need) + ")",
                 "obstacle grid spacing [m]"});
        }
    }
    return out;
}

}  // namespace sb::dem

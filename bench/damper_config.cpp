// Reading [dampers.NAME]: enclosure, particles, contact law, automatic stiffness, settling.
#include "bench/damper_config.hpp"

namespace sb::bench {
namespace {

void read_enclosure(Section s, dem::EnclosureOptions& e) {
    const std::string shape = s.choice("shape", "cylinder", {"cylinder", "box"}, "cavity shape");
    e.shape = shape == "box" ? dem::EnclosureShape::box : dem::EnclosureShape::cylinder;
    e.inner_diameter_m =
        s.number("inner_diameter_m", e.inner_diameter_m, "cylinder inner diameter [m]");
    e.height_m = s.number("height_m", e.height_m, "inner height along the damper axis [m]");
    e.length_x_m = s.number("length_x_m", e.length_x_m, "box inner size along local x [m]");
    e.length_y_m = s.number("length_y_m", e.length_y_m, "box inner size along local y [m]");
    Section rods = s.table("rods", "obstacle grid of thin rods (paper 002)");
    if (rods.present()) {
        e.rods.enabled = rods.boolean("enabled", true, "obstacle grid on");
        e.rods.rod_diameter_m =
            rods.number("rod_diameter_m", e.rods.rod_diameter_m, "rod diameter [m]");
        e.rods.cell_size_m =
            rods.number("cell_size_m", e.rods.cell_size_m, "edge of the cubic cells [m]");
        e.rods.origin_m =
            rods.vector3("origin_m", e.rods.origin_m, "one lattice node, enclosure frame [m]");
        rods.finish();
    }
    for (Section plate : s.array_of_tables("plates", "partition ribs")) {
        dem::PlateOptions p;
        p.min_corner_m = plate.vector3("min_corner_m", p.min_corner_m,
                                       "plate corner with the smallest coordinates [m]");
        p.max_corner_m = plate.vector3("max_corner_m", p.max_corner_m,
                                       "plate corner with the largest coordinates [m]");
        plate.finish();
        e.plates.push_back(p);
    }
    s.finish();
}

void read_particles(Section s, dem::ParticleOptions& p) {
    p.count = s.integer("count", p.count, "number of spheres");
    p.diameter_m = s.number("diameter_m", p.diameter_m, "sphere diameter [m]");
    p.material.density_kg_m3 =
        s.number("density_kg_m3", p.material.density_kg_m3, "particle density [kg/m^3]");
    p.material.youngs_modulus_pa = s.number("youngs_modulus_pa", p.material.youngs_modulus_pa,
                                            "particle Young's modulus [Pa] (Hertz)");
    p.material.poisson_ratio =
        s.number("poisson_ratio", p.material.poisson_ratio, "particle Poisson ratio [-]");
    for (Section fraction : s.array_of_tables("sizes", "size distribution")) {
        dem::SizeFraction f;
        f.diameter_m = fraction.required_number("diameter_m", "diameter of the class [m]");
        f.number_fraction =
            fraction.required_number("number_fraction", "share of the particle count [-]");
        fraction.finish();
        p.size_distribution.push_back(f);
    }
    s.finish();
}

void read_contact(Section s, DamperSpec& d) {
    auto& c = d.solver.contact;
    const std::string normal = s.choice("normal", "hooke", {"hooke", "hertz"}, "normal law");
    c.normal = normal == "hertz" ? dem::NormalLaw::hertz : dem::NormalLaw::hooke;
    const std::string damping =
        s.choice("damping", "restitution", {"none", "restitution"}, "normal damping");
    c.damping = damping == "none" ? dem::DampingLaw::none : dem::DampingLaw::restitution;
    const std::string tangential =
        s.choice("tangential", "directional_coulomb",
                 {"none", "directional_coulomb", "coulomb_spring"}, "tangential law");
    c.tangential = tangential == "none"             ? dem::TangentialLaw::none
                   : tangential == "coulomb_spring" ? dem::TangentialLaw::coulomb_spring
                                                    : dem::TangentialLaw::directional_coulomb;
    const std::string rolling =
        s.choice("rolling", "constant_torque", {"none", "constant_torque"}, "rolling resistance");
    c.rolling = rolling == "none" ? dem::RollingLaw::none : dem::RollingLaw::constant_torque;
    c.normal_stiffness =
        s.number("normal_stiffness", 0.0, "Hooke [N/m] or Hertz [N/m^1.5]; 0: automatic");
    c.tangential_stiffness_ratio =
        s.number("tangential_stiffness_ratio", c.tangential_stiffness_ratio,
                 "coulomb_spring: tangential / normal stiffness [-]");
    c.slip_regularisation_m_s = s.number("slip_regularisation_m_s", c.slip_regularisation_m_s,
                                         "directional Coulomb: slip speed of full friction [m/s]");
    c.particle_particle.restitution =
        s.number("restitution", c.particle_particle.restitution, "particle-particle [-]");
    c.particle_particle.sliding_friction =
        s.number("sliding_friction", c.particle_particle.sliding_friction, "particle-particle [-]");
    c.particle_particle.rolling_friction =
        s.number("rolling_friction", c.particle_particle.rolling_friction, "particle-particle [-]");
    c.particle_wall.restitution = s.number("wall_restitution", c.particle_particle.restitution,
                                           "particle-wall [-] (default: restitution)");
    c.particle_wall.sliding_friction =
        s.number("wall_sliding_friction", c.particle_particle.sliding_friction,
                 "particle-wall [-] (default: sliding_friction)");
    c.particle_wall.rolling_friction =
        s.number("wall_rolling_friction", c.particle_particle.rolling_friction,
                 "particle-wall [-] (default: rolling_friction)");
    c.wall_material.youngs_modulus_pa = s.number(
        "wall_youngs_modulus_pa", c.wall_material.youngs_modulus_pa, "wall Young's modulus [Pa]");
    c.wall_material.poisson_ratio =
        s.number("wall_poisson_ratio", c.wall_material.poisson_ratio, "wall Poisson ratio [-]");
    d.max_overlap_fraction = s.number("max_overlap_fraction", d.max_overlap_fraction,
                                      "automatic stiffness: largest overlap / diameter [-]");
    d.time_step_fraction =
        s.number("time_step_fraction", d.time_step_fraction, "DEM time step / contact time [-]");
    s.finish();
}

/// The DEM module names fields by struct; the config flattens a few of them.
std::string config_key(const std::string& dem_key) {
    const std::pair<const char*, const char*> renames[] = {
        {"contact.particle_particle.", "contact."},
        {"contact.particle_wall.", "contact.wall_"},
        {"contact.wall_material.", "contact.wall_"},
        {"particles.material.", "particles."},
        {"particles.size_distribution", "particles.sizes"},
        {"max_overlap_fraction", "guard_overlap_fraction"},
    };
    for (const auto& [from, to] : renames) {
        if (dem_key.rfind(from, 0) == 0) {
            return to + dem_key.substr(std::string(from).size());
        }
    }
    return dem_key;
}

}  // namespace

std::vector<DamperSpec> read_dampers(Section dampers) {
    std::vector<DamperSpec> out;
    for (auto& [name, s] : dampers.named_tables("a damper")) {
        DamperSpec d;
        d.name = name;
        d.point = s.required_string("point", "named point the damper is attached to");
        d.mount_offset_m = s.vector3("mount_offset_m", d.mount_offset_m,
                                     "enclosure origin (inner bottom centre) from the point [m]");
        d.bottom_thickness_m =
            s.number("bottom_thickness_m", d.bottom_thickness_m,
                     "enclosure bottom plate: its outer face stands on the mounting [m]");
        d.enclosure_mass = s.string("enclosure_mass", "",
                                    "structure mass that is this enclosure (turned with it)");
        d.locked = s.boolean("locked", false, "particles locked to the enclosure");
        const std::string model = s.choice("model", "dem", {"dem", "rigid"},
                                           "dem: simulated particles; rigid: equal rigid mass");
        d.model = model == "rigid" ? DamperSpec::Model::rigid : DamperSpec::Model::dem;
        d.solver.threads = s.integer("threads", 1, "OpenMP threads of this damper's DEM");
        d.solver.max_overlap_fraction =
            s.number("guard_overlap_fraction", d.solver.max_overlap_fraction,
                     "guard: overlap / radius beyond which the run stops [-]");
        read_enclosure(s.table("enclosure", "the cavity"), d.solver.enclosure);
        read_particles(s.table("particles", "the particles"), d.solver.particles);
        read_contact(s.table("contact", "the contact law"), d);
        Section settle = s.table("settle", "settling under gravity");
        d.settle.dt_s = settle.number("dt_s", d.settle.dt_s, "settling time step [s]");
        d.settle.max_time_s = settle.number("max_time_s", d.settle.max_time_s, "give up after [s]");
        d.settle.kinetic_threshold_j = settle.number(
            "kinetic_threshold_j", d.settle.kinetic_threshold_j, "at rest below this energy [J]");
        d.fill = settle.choice("fill", "random", {"random", "pour"},
                               "random: insert into the whole cavity, then settle; pour: "
                               "batches settled under gravity (dense beds)") == "pour"
                     ? DamperSpec::Fill::pour
                     : DamperSpec::Fill::random;
        settle.finish();
        s.finish();

        dem::SolverOptions checked = d.solver;
        if (checked.contact.normal_stiffness == 0.0) {
            checked.contact.normal_stiffness = 1.0;  // automatic: chosen per sweep
        }
        Violations v;
        for (auto violation : checked.validate()) {
            violation.key = config_key(violation.key);
            v.push_back(std::move(violation));
        }
        append_prefixed(v, "settle", d.settle.validate());
        require_non_negative(v, "bottom_thickness_m", d.bottom_thickness_m,
                             "enclosure bottom plate [m]");
        require_in_range(v, "contact.max_overlap_fraction", d.max_overlap_fraction, 1e-6, 0.2,
                         "automatic stiffness: largest overlap / diameter [-]");
        require_in_range(v, "contact.time_step_fraction", d.time_step_fraction, 1e-3, 0.5,
                         "DEM time step / contact time [-]");
        s.report(v);
        out.push_back(std::move(d));
    }
    dampers.finish();
    return out;
}

}  // namespace sb::bench

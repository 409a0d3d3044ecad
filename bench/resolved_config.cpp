// Writing the resolved campaign config.
#include "bench/resolved_config.hpp"

#include <toml++/toml.h>

#include <sstream>

namespace sb::bench {
namespace {

toml::array numbers(const std::vector<double>& values) {
    toml::array a;
    for (double v : values) a.push_back(v);
    return a;
}

toml::array vector3(const Eigen::Vector3d& v) {
    toml::array a;
    for (int i = 0; i < 3; ++i) a.push_back(v[i]);
    return a;
}

toml::array strings(const std::vector<std::string>& values) {
    toml::array a;
    for (const auto& v : values) a.push_back(v);
    return a;
}

toml::table frequencies(const FrequencyGridSpec& g) {
    toml::table t;
    if (!g.values_hz.empty()) {
        t.insert("values_hz", numbers(g.values_hz));
    } else {
        t.insert("low_ratio", g.low_ratio);
        t.insert("high_ratio", g.high_ratio);
        t.insert("count", g.count);
        t.insert("grid_damping_ratio", g.grid_damping_ratio);
    }
    t.insert("direction", g.descending ? "down" : "up");
    return t;
}

toml::table arrangement(const ArrangementSpec& a) {
    toml::table t;
    t.insert("oscillation",
             a.oscillation == ArrangementSpec::Oscillation::vertical ? "vertical" : "horizontal");
    t.insert("damper_angle_deg", a.damper_angle_deg);
    t.insert("block_mass_kg", a.block_mass_kg);
    t.insert("block_cathetus_m", a.block_cathetus_m);
    t.insert("mount_lift_m", vector3(a.mount_lift_m));
    return t;
}

toml::table enclosure(const dem::EnclosureOptions& e) {
    toml::table t;
    t.insert("shape", e.shape == dem::EnclosureShape::box ? "box" : "cylinder");
    t.insert("inner_diameter_m", e.inner_diameter_m);
    t.insert("height_m", e.height_m);
    t.insert("length_x_m", e.length_x_m);
    t.insert("length_y_m", e.length_y_m);
    if (e.rods.enabled) {
        toml::table rods;
        rods.insert("enabled", true);
        rods.insert("rod_diameter_m", e.rods.rod_diameter_m);
        rods.insert("cell_size_m", e.rods.cell_size_m);
        rods.insert("origin_m", vector3(e.rods.origin_m));
        t.insert("rods", rods);
    }
    if (!e.plates.empty()) {
        toml::array plates;
        for (const auto& p : e.plates) {
            toml::table plate;
            plate.insert("min_corner_m", vector3(p.min_corner_m));
            plate.insert("max_corner_m", vector3(p.max_corner_m));
            plates.push_back(plate);
        }
        t.insert("plates", plates);
    }
    return t;
}

toml::table particles(const dem::ParticleOptions& p) {
    toml::table t;
    t.insert("count", p.count);
    t.insert("diameter_m", p.diameter_m);
    t.insert("density_kg_m3", p.material.density_kg_m3);
    t.insert("youngs_modulus_pa", p.material.youngs_modulus_pa);
    t.insert("poisson_ratio", p.material.poisson_ratio);
    if (!p.size_distribution.empty()) {
        toml::array sizes;
        for (const auto& f : p.size_distribution) {
            toml::table size;
            size.insert("diameter_m", f.diameter_m);
            size.insert("number_fraction", f.number_fraction);
            sizes.push_back(size);
        }
        t.insert("sizes", sizes);
    }
    return t;
}

toml::table contact(const DamperSpec& d) {
    const auto& c = d.solver.contact;
    toml::table t;
    t.insert("normal", c.normal == dem::NormalLaw::hertz ? "hertz" : "hooke");
    t.insert("damping", c.damping == dem::DampingLaw::none ? "none" : "restitution");
    t.insert("tangential", c.tangential == dem::TangentialLaw::none ? "none"
                           : c.tangential == dem::TangentialLaw::coulomb_spring
                               ? "coulomb_spring"
                               : "directional_coulomb");
    t.insert("rolling", c.rolling == dem::RollingLaw::none ? "none" : "constant_torque");
    t.insert("normal_stiffness", c.normal_stiffness);
    t.insert("tangential_stiffness_ratio", c.tangential_stiffness_ratio);
    t.insert("slip_regularisation_m_s", c.slip_regularisation_m_s);
    t.insert("restitution", c.particle_particle.restitution);
    t.insert("sliding_friction", c.particle_particle.sliding_friction);
    t.insert("rolling_friction", c.particle_particle.rolling_friction);
    t.insert("wall_restitution", c.particle_wall.restitution);
    t.insert("wall_sliding_friction", c.particle_wall.sliding_friction);
    t.insert("wall_rolling_friction", c.particle_wall.rolling_friction);
    t.insert("wall_youngs_modulus_pa", c.wall_material.youngs_modulus_pa);
    t.insert("wall_poisson_ratio", c.wall_material.poisson_ratio);
    t.insert("max_overlap_fraction", d.max_overlap_fraction);
    t.insert("time_step_fraction", d.time_step_fraction);
    return t;
}

toml::table damper(const DamperSpec& d) {
    toml::table t;
    t.insert("point", d.point);
    t.insert("mount_offset_m", vector3(d.mount_offset_m));
    t.insert("bottom_thickness_m", d.bottom_thickness_m);
    t.insert("enclosure_mass", d.enclosure_mass);
    t.insert("model", d.model == DamperSpec::Model::rigid ? "rigid" : "dem");
    t.insert("locked", d.locked);
    t.insert("threads", d.solver.threads);
    t.insert("guard_overlap_fraction", d.solver.max_overlap_fraction);
    t.insert("enclosure", enclosure(d.solver.enclosure));
    t.insert("particles", particles(d.solver.particles));
    t.insert("contact", contact(d));
    toml::table settle;
    settle.insert("dt_s", d.settle.dt_s);
    settle.insert("max_time_s", d.settle.max_time_s);
    settle.insert("kinetic_threshold_j", d.settle.kinetic_threshold_j);
    settle.insert("fill", d.fill == DamperSpec::Fill::pour ? "pour" : "random");
    t.insert("settle", settle);
    return t;
}

toml::table controller(const control::ControllerOptions& c) {
    toml::table t;
    t.insert("tolerance", c.tolerance);
    t.insert("window_periods", c.window_periods);
    t.insert("early_periods", c.early_periods);
    t.insert("transient_periods", c.transient_periods);
    t.insert("max_periods", c.max_periods);
    t.insert("closest_rerun_periods", c.closest_rerun_periods);
    t.insert("initial_amplitude", c.initial_amplitude);
    t.insert("min_amplitude", c.min_amplitude);
    t.insert("max_amplitude", c.max_amplitude);
    t.insert("max_step_factor", c.max_step_factor);
    t.insert("overshoot", c.overshoot);
    t.insert("limit_cycle_jump", c.limit_cycle_jump);
    t.insert("limit_cycle_periods", c.limit_cycle_periods);
    t.insert("max_restarts", c.max_restarts);
    t.insert("drift_horizon_periods", c.drift_horizon_periods);
    return t;
}

}  // namespace

std::string resolved_config_toml(const CampaignConfig& config, std::string_view raw_text) {
    const CampaignSpec& c = config.campaign;
    toml::table root;
    toml::table campaign;
    campaign.insert("name", config.name);
    campaign.insert("description", config.description);
    campaign.insert("levels_g", numbers(c.levels_g));
    std::vector<std::string> names;
    for (const auto& a : c.arrangements) names.push_back(a.name);
    campaign.insert("arrangements", strings(names));
    campaign.insert("control_point", c.control_point);
    campaign.insert("response_points", strings(c.response_points));
    campaign.insert("point_start",
                    c.point_start == CampaignSpec::PointStart::linear_steady_state
                        ? "linear-steady-state"
                    : c.point_start == CampaignSpec::PointStart::equivalent_steady_state
                        ? "equivalent-steady-state"
                        : "previous-state");
    campaign.insert("scale_response_on_update", c.scale_response_on_update);
    campaign.insert("seed", static_cast<std::int64_t>(c.seed));
    campaign.insert("frequencies", frequencies(c.frequencies));
    root.insert("campaign", campaign);

    toml::table arrangements;
    for (const auto& a : c.arrangements) arrangements.insert(a.name, arrangement(a));
    root.insert("arrangements", arrangements);
    toml::table dampers;
    for (const auto& d : c.dampers) dampers.insert(d.name, damper(d));
    root.insert("dampers", dampers);
    root.insert("controller", controller(c.controller));
    toml::table output;
    output.insert("series", c.output.series);
    output.insert("series_samples_per_period", c.output.series_samples_per_period);
    output.insert("uff", c.output.uff);
    output.insert("plots", c.output.plots);
    root.insert("output", output);

    // The structure as given: its keys and defaults are the structure module's
    // (docs/config.md); the raw text already parsed once when the config was loaded.
    try {
        const toml::table raw = toml::parse(raw_text);
        if (const toml::table* s = raw["structure"].as_table()) {
            root.insert("structure", *s);
        }
    } catch (const toml::parse_error&) {
        // Not reached for a loaded config; the resolved file then lacks only [structure].
    }

    std::ostringstream text;
    text << "# The campaign as run, every default written out (shakerbench run reads it back).\n"
         << toml::toml_formatter(root) << '\n';
    return text.str();
}

}  // namespace sb::bench

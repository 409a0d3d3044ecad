// Planning a campaign: prepared arrangements and sweep tasks.
#include "bench/campaign_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bench/arrangement.hpp"
#include "bench/frequency_grid.hpp"
#include "bench/linear_estimate.hpp"
#include "bench/physics_attachments.hpp"
#include "bench/shaker.hpp"
#include "config/errors.hpp"
#include "config/write.hpp"
#include "core/significant_text.hpp"
#include "core/units.hpp"
#include "dem/setup.hpp"

namespace sb::bench {
namespace {

/// Depth of a settled bed (random close packing about 0.6) on the enclosure floor [m].
double bed_depth_m(const DamperSpec& damper, double mass_kg) {
    const auto& e = damper.enclosure;
    const double floor_m2 = e.shape == dem::EnclosureShape::cylinder
                                ? kPi * e.inner_diameter_m * e.inner_diameter_m / 4.0
                                : e.length_x_m * e.length_y_m;
    constexpr double kPackingFraction = 0.6;
    return std::min(e.height_m, mass_kg / damper.particles.material.density_kg_m3 /
                                    kPackingFraction / floor_m2);
}

double point_position_m(const structure::StructureSpec& spec, const std::string& point) {
    for (const auto& p : spec.beam.points) {
        if (p.name == point) return p.x_m;
    }
    for (const auto& m : spec.beam.masses) {
        if (m.name == point) return m.x_m;
    }
    throw std::runtime_error("no beam point named '" + point + "'");
}

/// Adds a rigid mass at a damper's point (beam: a lumped mass with its centre offset;
/// lumped model: added to the named mass; imported model: a mass at the named point).
void add_mass(structure::StructureSpec& spec, const std::string& point, const std::string& name,
              double mass_kg, const Eigen::Vector3d& offset_m) {
    using Kind = structure::StructureSpec::Kind;
    if (spec.kind == Kind::beam) {
        structure::LumpedMass m;
        m.name = name;
        m.x_m = point_position_m(spec, point);
        m.mass_kg = mass_kg;
        m.offset_m = offset_m;
        spec.beam.masses.push_back(m);
    } else if (spec.kind == Kind::lumped) {
        for (auto& m : spec.lumped.masses) {
            if (m.name == point) m.mass_kg += mass_kg;
        }
    } else {
        structure::PointMass m;
        m.name = name;
        m.point = point;
        m.mass_kg = mass_kg;
        m.offset_m = offset_m;
        spec.matrix.masses.push_back(m);
    }
}

PreparedArrangement prepare(const CampaignConfig& config, const ArrangementSpec& arrangement) {
    PreparedArrangement p;
    p.arrangement = arrangement;
    p.structure = arrangement_structure(config, arrangement, false);
    const structure::StructureSpec estimate = arrangement_structure(config, arrangement, true);
    p.model = structure::build_linear_model(p.structure, config.base_dir);
    p.basis = structure::compute_modes(p.model, p.structure.damping, p.structure.modes);
    p.estimate_model = structure::build_linear_model(estimate, config.base_dir);
    p.estimate_basis = structure::compute_modes(p.estimate_model, estimate.damping, estimate.modes);
    p.first_mode_hz = first_driven_mode_hz(p.estimate_basis, p.structure.excitation.direction);
    const TransientSpec& transient = config.campaign.transient;
    p.frequencies_hz = transient.on() && transient.frequency_hz
                           ? std::vector<double>{*transient.frequency_hz}
                           : frequency_grid(config.campaign.frequencies, p.first_mode_hz);
    return p;
}

/// "_1g" for a controlled level; a fixed drive's amplitude carries its unit's tag.
std::string sweep_key(const CampaignConfig& config, const std::string& arrangement, double level_g,
                      const std::vector<double>& given_hz) {
    std::string unit = level_unit(config);
    if (unit == "m/s^2") unit = "mps2";
    std::string key = arrangement + "_" + significant_text(level_g) + unit;
    if (!given_hz.empty()) {
        std::string list;
        for (double f : given_hz) list += config::number_text(f) + ";";
        key += "_f" + config::fnv1a_hex(list).substr(0, 8);
    }
    std::replace_if(
        key.begin(), key.end(),
        [](char c) { return !(std::isalnum(c) || c == '-' || c == '.' || c == '_'); }, '_');
    return key;
}

config::ConfigError problem(const CampaignConfig& config, std::string key, std::string value,
                            std::string constraint, std::string meaning) {
    return {config.source,     0, 0, std::move(key), std::move(value), std::move(constraint),
            std::move(meaning)};
}

}  // namespace

std::string level_unit(const CampaignConfig& config) {
    const DriveSpec& drive = config.campaign.drive;
    if (!drive.fixed()) return "g";
    if (drive.quantity == DriveSpec::Quantity::base_displacement) return "m";
    if (config.physics.shaker.on()) return "V";
    return config.structure.excitation.kind == structure::ExcitationSpec::Kind::base ? "m/s^2"
                                                                                     : "N";
}

double fixed_drive_level_g(const CampaignConfig& config, const PreparedArrangement& prepared) {
    const DriveSpec& drive = config.campaign.drive;
    double largest_amplitude = 0.0;
    for (double a : drive.amplitudes) largest_amplitude = std::max(largest_amplitude, a);
    const ShakerSpec& shaker = config.physics.shaker;
    double largest_peak = 0.0;
    for (double f : prepared.frequencies_hz) {
        double per_unit = linear_response_per_unit_input(
            prepared.estimate_model, prepared.estimate_basis, prepared.structure.excitation,
            config.campaign.control_point, f);
        if (shaker.on()) per_unit *= std::abs(blocked_force_per_volt(shaker, f));
        largest_peak =
            std::max(largest_peak, per_unit * drive.excitation_amplitude(largest_amplitude, f));
    }
    return m_s2_to_g(largest_peak / std::sqrt(2.0));
}

Selection Selection::of(const CampaignConfig& config, std::vector<std::string> arrangements,
                        std::vector<double> levels_g, std::vector<double> frequencies_hz) {
    if (arrangements.empty()) {
        for (const auto& a : config.campaign.selected_arrangements())
            arrangements.push_back(a.name);
    }
    if (levels_g.empty()) levels_g = config.campaign.levels();
    Selection s;
    for (const auto& a : arrangements) {
        for (double level : levels_g) s.sweeps.push_back({a, level, frequencies_hz});
    }
    return s;
}

int CampaignPlan::points() const {
    int n = 0;
    for (const auto& t : tasks) n += static_cast<int>(t.frequencies_hz.size());
    return n;
}

CampaignPlan plan_campaign(const CampaignConfig& config, const Selection& selection) {
    const CampaignSpec& campaign = config.campaign;
    const Selection wanted = selection.sweeps.empty() ? Selection::of(config, {}, {}) : selection;
    std::vector<config::ConfigError> problems;
    if (campaign.levels().empty() && selection.sweeps.empty()) {
        problems.push_back(
            campaign.drive.fixed()
                ? problem(config, "campaign.drive.amplitudes", "", "is required",
                          "peak amplitudes of a fixed drive: a campaign needs at least one")
                : problem(config, "campaign.levels_g", "", "is required",
                          "target RMS levels [g]: a campaign needs at least one"));
    }
    if (campaign.selected_arrangements().empty() && selection.sweeps.empty()) {
        problems.push_back(problem(config, "arrangements", "", "is required",
                                   "at least one [arrangements.NAME] table"));
    }
    for (const auto& s : wanted.sweeps) {
        const auto& defined = campaign.arrangements;
        if (std::none_of(defined.begin(), defined.end(),
                         [&](const ArrangementSpec& a) { return a.name == s.arrangement; })) {
            problems.push_back(problem(config, "selection", config::quoted(s.arrangement),
                                       "must name an arrangement of the config",
                                       "arrangement of a selected sweep"));
        }
        if (!(s.level_g > 0.0 && std::isfinite(s.level_g))) {
            problems.push_back(problem(config, "selection", significant_text(s.level_g),
                                       "must be > 0", "level of a selected sweep [g]"));
        }
        for (double f : s.frequencies_hz) {
            if (!(f > 0.0 && std::isfinite(f))) {
                problems.push_back(problem(config, "selection", significant_text(f), "must be > 0",
                                           "frequency of a selected sweep [Hz]"));
            }
        }
    }
    if (!problems.empty()) throw config::ConfigException(problems);

    CampaignPlan plan;
    std::vector<std::string> names;
    for (const auto& s : wanted.sweeps) {
        if (std::find(names.begin(), names.end(), s.arrangement) == names.end()) {
            names.push_back(s.arrangement);
        }
    }
    plan.arrangements.reserve(names.size());
    for (const auto& name : names) {
        for (const auto& a : campaign.arrangements) {
            if (a.name == name) plan.arrangements.push_back(prepare(config, a));
        }
    }
    // One stiffness for the whole campaign: sized for its largest level (under a fixed drive
    // the largest RMS the linear model gives at the control point: see fixed_drive_level_g).
    double largest_g = 0.0;
    for (double level : campaign.levels_g) largest_g = std::max(largest_g, level);
    if (campaign.drive.fixed()) {
        for (const auto& p : plan.arrangements) {
            largest_g = std::max(largest_g, fixed_drive_level_g(config, p));
        }
    }
    for (const auto& s : wanted.sweeps) {
        for (int filling = 0; filling < campaign.seeds; ++filling) {
            SweepTask t;
            t.index = plan.tasks.size();
            for (const auto& p : plan.arrangements) {
                if (p.arrangement.name == s.arrangement) t.prepared = &p;
            }
            t.level_g = s.level_g;
            t.level_unit = level_unit(config);
            t.frequencies_hz =
                s.frequencies_hz.empty() ? t.prepared->frequencies_hz : s.frequencies_hz;
            t.filling = filling;
            t.seed = campaign.seed + static_cast<std::uint64_t>(filling);
            t.stiffness_level_g =
                campaign.drive.fixed() ? largest_g : std::max(largest_g, s.level_g);
            t.refine =
                s.frequencies_hz.empty() && !campaign.transient.on() && !campaign.random.on();
            t.key = sweep_key(config, s.arrangement, s.level_g, s.frequencies_hz);
            if (filling > 0) t.key += "_s" + std::to_string(filling);
            plan.tasks.push_back(std::move(t));
        }
    }
    return plan;
}

double particle_mass_kg(const DamperSpec& damper, std::uint64_t seed) {
    double mass = 0.0;
    for (double r : dem::make_radii(damper.particles, seed)) {
        mass += damper.particles.material.density_kg_m3 * 4.0 / 3.0 * kPi * r * r * r;
    }
    return mass;
}

structure::StructureSpec arrangement_structure(const CampaignConfig& config,
                                               const ArrangementSpec& arrangement,
                                               bool all_particles_rigid) {
    structure::StructureSpec spec = config.structure;
    spec.beam = spec.beam.resolved();  // masses at named points placed there
    // The config's gravity gives the magnitude, the arrangement its direction.
    spec.gravity_m_s2 = arrangement_gravity(arrangement, config.structure.gravity_m_s2.norm());
    const ShakerSpec& shaker = config.physics.shaker;
    if (shaker.on() && shaker.armature_mass_kg > 0.0) {
        // The armature moves with the drive point (a rigid stinger): its mass is the
        // structure's, exact in the modes rather than an explicit inertia load.
        add_mass(spec, spec.excitation.point, "shaker armature", shaker.armature_mass_kg,
                 Eigen::Vector3d::Zero());
    }
    if (config.physics.air_drag.on() && spec.kind == structure::StructureSpec::Kind::beam) {
        for (auto& p : air_drag_points(spec.beam, config.physics.air_drag.stations)) {
            spec.beam.points.push_back(std::move(p));
        }
    }
    for (const auto& d : config.campaign.dampers) {
        const DamperMounting mounting = damper_mounting(arrangement, d);
        if (!d.enclosure_mass.empty()) {
            // The enclosure's mass turns and moves with the DEM enclosure.
            if (spec.kind == structure::StructureSpec::Kind::matrix) {
                for (auto& m : spec.matrix.masses) {
                    const std::string& label = m.name.empty() ? m.point : m.name;
                    if (label == d.enclosure_mass && m.point == d.point) {
                        m = mounted_enclosure_mass(m, d, mounting);
                    }
                }
            } else {
                for (auto& m : spec.beam.masses) {
                    if (m.name == d.enclosure_mass && m.x_m == point_position_m(spec, d.point)) {
                        m = mounted_enclosure_mass(m, d, mounting);
                    }
                }
            }
        }
        if (arrangement.block_mass_kg > 0.0) {
            add_mass(spec, d.point, d.name + " block", arrangement.block_mass_kg,
                     mounting.block_cg_m);
        }
        if (all_particles_rigid || d.model == DamperSpec::Model::rigid) {
            const double mass = particle_mass_kg(d, config.campaign.seed);
            const Eigen::Vector3d centre =
                mounting.from_enclosure(Eigen::Vector3d(0.0, 0.0, 0.5 * bed_depth_m(d, mass)));
            add_mass(spec, d.point, d.name + " particles (rigid)", mass, centre);
        }
    }
    return spec;
}

}  // namespace sb::bench

#include "correlation/physics_catalogue.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "config/schema.hpp"
#include "correlation/free_parameters.hpp"

namespace sb::correlation {
namespace {

using Kind = structure::StructureSpec::Kind;

/// Name of the mass the sensor-mass row adds at the control point.
constexpr const char* kSensorMass = "sensor mass (catalogue)";
/// Suffix of the rotational springs the clamp-compliance row adds at a clamp.
constexpr const char* kClampSpring = "_rotational_spring";

/// Whether `d` is a DEM damper whose `part` (its contact, its particles) `lacks` says leaves
/// a physics out.
template <class Part>
bool dem_damper_lacking(const bench::DamperSpec& d, Part bench::DamperSpec::*part,
                        std::type_identity_t<bool (*)(const Part&)> lacks) {
    return d.model == bench::DamperSpec::Model::dem && lacks(d.*part);
}

/// A damper-side row's verbs: switching it on changes (`change`) the `part` of every DEM
/// damper that `lacks` the physics and frees `key` of each (relative to the damper's table,
/// with ":MIN:MAX..." when it has one); it applies while one such damper is left.
template <class Part>
std::function<std::vector<std::string>(bench::CampaignConfig&)> switch_dampers(
    Part bench::DamperSpec::*part, std::type_identity_t<bool (*)(const Part&)> lacks,
    std::type_identity_t<void (*)(Part&)> change, std::string key) {
    return [part, lacks, change, key](bench::CampaignConfig& c) {
        std::vector<std::string> keys;
        for (auto& d : c.campaign.dampers) {
            if (!dem_damper_lacking(d, part, lacks)) continue;
            change(d.*part);
            keys.push_back(config::join_path("dampers", d.name) + "." + key);
        }
        return keys;
    };
}
template <class Part>
std::function<bool(const bench::CampaignConfig&)> has_dem_damper_lacking(
    Part bench::DamperSpec::*part, std::type_identity_t<bool (*)(const Part&)> lacks) {
    return [part, lacks](const bench::CampaignConfig& c) {
        return std::any_of(c.campaign.dampers.begin(), c.campaign.dampers.end(),
                           [part, lacks](const bench::DamperSpec& d) {
                               return dem_damper_lacking(d, part, lacks);
                           });
    };
}

/// The rows on the contact law: `key` relative to the damper's contact table.
using Lacks = bool (*)(const bench::ContactSpec&);
std::function<std::vector<std::string>(bench::CampaignConfig&)> switch_contacts(
    Lacks lacks, void (*change)(bench::ContactSpec&), std::string key) {
    return switch_dampers(&bench::DamperSpec::contact, lacks, change, "contact." + key);
}
std::function<bool(const bench::CampaignConfig&)> has_dem_damper_lacking(Lacks lacks) {
    return has_dem_damper_lacking(&bench::DamperSpec::contact, lacks);
}

/// The rows on the particles: `key` relative to the damper's particles table.
using ParticlesLack = bool (*)(const dem::ParticleOptions&);
std::function<std::vector<std::string>(bench::CampaignConfig&)> switch_particles(
    ParticlesLack lacks, void (*change)(dem::ParticleOptions&), std::string key) {
    return switch_dampers(&bench::DamperSpec::particles, lacks, change, "particles." + key);
}
std::function<bool(const bench::CampaignConfig&)> has_dem_damper_lacking(ParticlesLack lacks) {
    return has_dem_damper_lacking(&bench::DamperSpec::particles, lacks);
}

bool lacks_rolling_resistance(const bench::ContactSpec& contact) {
    return contact.rolling == dem::RollingLaw::none ||
           contact.particle_particle.rolling_friction == 0.0;
}

bool lacks_velocity_dependent_restitution(const bench::ContactSpec& contact) {
    return contact.damping != dem::DampingLaw::viscoelastic &&
           contact.damping != dem::DampingLaw::none;
}

bool lacks_static_friction(const bench::ContactSpec& contact) {
    return contact.tangential == dem::TangentialLaw::directional_coulomb;
}

bool lacks_size_scatter(const dem::ParticleOptions& particles) {
    return particles.diameter_scatter == 0.0;
}

/// The first clamped support of a beam, or null.
structure::Support* first_clamp(structure::BeamSpec& beam) {
    for (auto& s : beam.supports) {
        if (s.kind == structure::SupportKind::clamped) return &s;
    }
    return nullptr;
}

/// Turns the beam's first clamp into a pin with rotational springs: about the axis the
/// driven bending turns (x × the excitation direction) a spring to be fitted, from 3000 down
/// to 3 times the beam's root bending stiffness EI/L (Euler-Bernoulli cantilever with a
/// root spring: the first mode 0.07 % to 35 % below the clamped one); about the other
/// bending axis, a spring 10^4 times EI/L, as good as rigid. Returns the fitted key.
std::string make_clamp_compliant(bench::CampaignConfig& c) {
    auto& beam = c.structure.beam;
    structure::Support* clamp = first_clamp(beam);
    const Eigen::Vector3d dir = c.structure.excitation.direction.normalized();
    // Bending in z turns about y (second moment w t^3/12), bending in y about z (t w^3/12).
    const bool about_y = std::abs(dir.z()) >= std::abs(dir.y());
    const int axis = about_y ? 1 : 2;
    const double w = beam.width_m;
    const double t = beam.thickness_m;
    const double second_moment_driven = about_y ? w * t * t * t / 12.0 : t * w * w * w / 12.0;
    const double second_moment_other = about_y ? t * w * w * w / 12.0 : w * t * t * t / 12.0;
    const double per_length = beam.youngs_modulus_pa / beam.length_m;
    const double lo = 3.0 * per_length * second_moment_driven;
    const double hi = 3000.0 * per_length * second_moment_driven;
    structure::Support spring;
    spring.name = clamp->name + kClampSpring;
    spring.x_m = clamp->x_m;
    spring.kind = structure::SupportKind::elastic;
    spring.rotational_stiffness_nm_per_rad[axis] = hi;
    spring.rotational_stiffness_nm_per_rad[3 - axis] = 1e4 * per_length * second_moment_other;
    clamp->kind = structure::SupportKind::pinned;
    beam.supports.push_back(spring);
    return "structure.beam.supports." + spring.name + ".rotational_stiffness_nm_per_rad[" +
           std::to_string(axis) + "]=" + exact_text(lo) + ":" + exact_text(hi) + ":log";
}

/// Puts an electrodynamic shaker between the amplifier and the drive point, barely on: its
/// force factor and coil resistance to be fitted (the gain Bl / R and the back-EMF's dashpot
/// Bl^2 / R, both seen in a voltage-referenced FRF), its armature and suspension as the config
/// gives them (at a single mode they only shift the frequency, as a sensor's mass does).
std::vector<std::string> switch_shaker_on(bench::CampaignConfig& c) {
    c.physics.shaker.force_factor_n_per_a = 1.0;
    return {"physics.shaker.force_factor_n_per_a=0.1:1000:log",
            "physics.shaker.coil_resistance_ohm=0.01:100:log"};
}

std::vector<CatalogueEntry> build_catalogue() {
    std::vector<CatalogueEntry> rows;
    rows.push_back(
        {"background-damping",
         "the rig's background damping",
         "Viscous damping of the bare structure and rig (material, joints, cables, air at "
         "small amplitude): the same damping ratio added at every level, dominant below the "
         "particles' lift-off.",
         {{LevelFeature::damping_ratio, ScalingShape::constant, +1}},
         [](bench::CampaignConfig&) {
             return std::vector<std::string>{"structure.damping.default_ratio"};
         },
         [](const bench::CampaignConfig& c) {
             // A lumped model with dashpots takes its damping from them, not from the ratio.
             const auto& springs = c.structure.lumped.springs;
             const bool dashpots = c.structure.kind == Kind::lumped &&
                                   std::any_of(springs.begin(), springs.end(), [](const auto& s) {
                                       return s.damping_n_s_per_m > 0.0;
                                   });
             return c.structure.damping.model == structure::DampingSpec::Model::modal &&
                    c.structure.damping.modal_ratios.empty() && !dashpots;
         },
         ""});
    rows.push_back(
        {"air-drag",
         "the beam's aerodynamic drag",
         "Quadratic drag of the air on the beam's wide face, 1/2 rho C_D b |v| v per unit "
         "length (physics.air_drag): damping that grows in proportion to the amplitude, the "
         "opposite of a particle damper's in its collisional regime.",
         {{LevelFeature::damping_ratio, ScalingShape::linear, +1}},
         [](bench::CampaignConfig&) {
             return std::vector<std::string>{"physics.air_drag.drag_coefficient"};
         },
         [](const bench::CampaignConfig& c) {
             return c.structure.kind == Kind::beam && !c.physics.air_drag.on();
         },
         ""});
    rows.push_back(
        {"joint-microslip",
         "microslip in a joint or clamp",
         "Partial slip in a bolted joint or a clamp (Iwan-type): damping that grows like a power "
         "of the amplitude below one, as a power-law dashpot at the control point "
         "(physics.microslip; a single mode's damping does not depend on where along it the "
         "dashpot sits, its coefficient absorbs the mode shape).",
         {{LevelFeature::damping_ratio, ScalingShape::power, +1}},
         [](bench::CampaignConfig& c) {
             // On from the start (its exponent applies only then), barely.
             c.physics.microslip.point = c.campaign.control_point;
             c.physics.microslip.damping_n_s_per_m = 1e-4;
             // A coefficient known within decades: searched on a log scale.
             return std::vector<std::string>{"physics.microslip.damping_n_s_per_m=0.0001:20:log",
                                             "physics.microslip.exponent"};
         },
         [](const bench::CampaignConfig& c) { return !c.physics.microslip.on(); },
         ""});
    rows.push_back(
        {"iwan-joint",
         "slip in a joint or clamp, with its softening",
         "A bolted joint or a clamp whose contact slips over more of its area at each level "
         "(Iwan; Segalman's power-law slip density): damping that grows like the amplitude^(1 "
         "+ chi) and the natural frequency falling with it, until the joint slides as a whole. "
         "An Iwan element at the control point (physics.iwan_joint): the stuck joint's "
         "stiffness and the displacement at which it slides as a whole, known within decades "
         "and searched on a log scale; the exponent of the slip density held at the config's "
         "(-0.5 by default, Segalman's lap joints).",
         {{LevelFeature::damping_ratio, ScalingShape::power, +1},
          {LevelFeature::natural_frequency, ScalingShape::power, -1}},
         [](bench::CampaignConfig& c) {
             // On from the start, barely (its other keys apply only then).
             c.physics.iwan_joint.point = c.campaign.control_point;
             c.physics.iwan_joint.stiffness_n_per_m = 0.01;
             c.physics.iwan_joint.macroslip_displacement_m = 0.01;
             // The exponent held: freed with the other two, the search settles in the valley
             // of joints that never reach macroslip (docs/diagnosis.md).
             return std::vector<std::string>{
                 "physics.iwan_joint.stiffness_n_per_m=0.01:1e6:log",
                 "physics.iwan_joint.macroslip_displacement_m=1e-6:1:log"};
         },
         [](const bench::CampaignConfig& c) { return !c.physics.iwan_joint.on(); },
         ""});
    rows.push_back(
        {"geometric-stiffening",
         "the geometric stiffening of the driven mode",
         "Large deflections stiffen the mode (mid-plane stretching, curvature): its frequency "
         "rises with the square of the amplitude, with a clean third harmonic, the damping "
         "unchanged; as a cubic spring at the control point (physics.cubic_spring).",
         {{LevelFeature::natural_frequency, ScalingShape::quadratic, +1}},
         [](bench::CampaignConfig& c) {
             c.physics.cubic_spring.point = c.campaign.control_point;
             return std::vector<std::string>{"physics.cubic_spring.stiffness_n_per_m3"};
         },
         [](const bench::CampaignConfig& c) { return !c.physics.cubic_spring.on(); },
         ""});
    rows.push_back(
        {"sensor-mass",
         "the mass of the sensor at the control point",
         "An accelerometer and its cable on the beam at the control point that the model "
         "lacks: every level's natural frequency lower by the same amount, the damping "
         "unchanged.",
         {{LevelFeature::natural_frequency, ScalingShape::constant, -1}},
         [](bench::CampaignConfig& c) {
             structure::LumpedMass m;
             m.name = kSensorMass;
             m.point = c.campaign.control_point;
             m.mass_kg = 1e-4;
             c.structure.beam.masses.push_back(m);
             return std::vector<std::string>{"structure.beam.masses[" +
                                             std::to_string(c.structure.beam.masses.size() - 1) +
                                             "].mass_kg=0.0001:0.05"};
         },
         [](const bench::CampaignConfig& c) {
             const auto& masses = c.structure.beam.masses;
             return c.structure.kind == Kind::beam &&
                    std::none_of(masses.begin(), masses.end(),
                                 [](const auto& m) { return m.name == kSensorMass; });
         },
         ""});
    rows.push_back(
        {"clamp-compliance",
         "the compliance of the clamp",
         "A clamp that lets the root turn a little (finite bolt preload, a compliant fixture): "
         "a rotational spring at the root in place of the ideal clamp, fitted from 3 to 3000 "
         "times the beam's EI/L on a log scale. Every level's natural frequency lower by the "
         "same amount, the damping unchanged; unlike a sensor's mass, the root's rotation "
         "raises the mode's shape near the root, so a force applied there drives the mode "
         "harder (Ritto et al. on matching a cantilever's clamp).",
         {{LevelFeature::natural_frequency, ScalingShape::constant, -1}},
         [](bench::CampaignConfig& c) { return std::vector<std::string>{make_clamp_compliant(c)}; },
         [](const bench::CampaignConfig& c) {
             const auto& beam = c.structure.beam;
             const bool clamped = std::any_of(
                 beam.supports.begin(), beam.supports.end(),
                 [](const auto& s) { return s.kind == structure::SupportKind::clamped; });
             return c.structure.kind == Kind::beam && clamped &&
                    std::none_of(beam.supports.begin(), beam.supports.end(), [](const auto& s) {
                        return s.name.find(kClampSpring) != std::string::npos;
                    });
         },
         ""});
    rows.push_back(
        {"electrodynamic-shaker",
         "the shaker between the amplifier's voltage and the structure",
         "A recording referenced to the amplifier's voltage, not to a force transducer: the "
         "coil's force factor Bl and resistance R turn the voltage into force, and the "
         "armature's motion through the magnet's field drives a back-EMF that takes force "
         "back, an electrical dashpot of Bl^2 / R at the drive point: the voltage-referenced "
         "FRF is more damped than the force-referenced one at every level (about four times "
         "on the RubBeR benchmark beam), its magnitude in m/s^2 per volt "
         "(physics.shaker; Varoto and de Oliveira 2002).",
         {{LevelFeature::damping_ratio, ScalingShape::constant, +1}},
         switch_shaker_on,
         [](const bench::CampaignConfig& c) {
             return c.structure.excitation.kind == structure::ExcitationSpec::Kind::force &&
                    !c.physics.shaker.on();
         },
         "voltage"});
    rows.push_back(
        {"rolling-resistance",
         "the particles' rolling resistance",
         "A torque mu_r R* F_n that resists the spheres' rolling (contact.rolling = "
         "\"constant_torque\"; Ai et al. 2011, model A): it dissipates in a dense bed at the "
         "low levels, before the particles lift off, and moves the onset of the damping; the "
         "collisional regime hardly feels it. Fitted on the coupled campaign.",
         {{LevelFeature::damping_ratio, ScalingShape::inverse, +1}},
         switch_contacts(
             lacks_rolling_resistance,
             [](bench::ContactSpec& c) { c.rolling = dem::RollingLaw::constant_torque; },
             "rolling_friction"),
         has_dem_damper_lacking(lacks_rolling_resistance),
         ""});
    rows.push_back(
        {"static-friction",
         "static friction at the particles' contacts",
         "Contacts that stick before they slide: a tangential spring with its history, capped "
         "by Coulomb (contact.tangential = \"coulomb_spring\", the linear form of "
         "Mindlin-Deresiewicz), in place of a stateless friction that only slides. It "
         "dissipates below gross sliding, at the lowest levels, with a slight softening; its "
         "value is the tangential stiffness over the normal one, searched from 0.05 to 1 on a "
         "log scale. Fitted on the coupled campaign.",
         {{LevelFeature::damping_ratio, ScalingShape::linear, +1}},
         switch_contacts(
             lacks_static_friction,
             [](bench::ContactSpec& c) { c.tangential = dem::TangentialLaw::coulomb_spring; },
             "tangential_stiffness_ratio=0.05:1:log"),
         has_dem_damper_lacking(lacks_static_friction),
         ""});
    rows.push_back(
        {"velocity-dependent-restitution",
         "a restitution that falls with the impact speed",
         "Real spheres are viscoelastic: their restitution falls with the impact speed (1 - e "
         "grows like v^(1/5)), where the model's is one number, so the bed dissipates more at "
         "the high levels than the model says and the slope of the damping curve changes. "
         "Every DEM damper with a set restitution gets Hertz contacts with the viscoelastic "
         "dashpot (Brilliantov et al. 1996), its dissipative constant searched from 1 ns to "
         "10 us on a log scale. Fitted on the coupled campaign.",
         {{LevelFeature::damping_ratio, ScalingShape::power, +1}},
         switch_contacts(
             lacks_velocity_dependent_restitution,
             [](bench::ContactSpec& c) {
                 c.normal = dem::NormalLaw::hertz;
                 c.damping = dem::DampingLaw::viscoelastic;
                 c.normal_stiffness.reset();
                 c.particle_particle.dissipative_constant_s = 1e-9;
             },
             "dissipative_constant_s=1e-9:1e-5:log"),
         has_dem_damper_lacking(lacks_velocity_dependent_restitution),
         ""});
    rows.push_back(
        {"gravity-tilt",
         "the misalignment of the mount with gravity",
         "A specimen mounted a few degrees off (a shaker or fixture not level): gravity gains "
         "a component along the motion, the bed rests against one wall and its impacts become "
         "asymmetric, with even harmonics in the response and the onset of particle motion "
         "moved. Every arrangement's arrangements.NAME.gravity_tilt_deg freed within +-10 deg "
         "(DEM dampers only: a describing function was characterised at its own gravity).",
         {{LevelFeature::h2_ratio, ScalingShape::constant, +1}},
         [](bench::CampaignConfig& c) {
             std::vector<std::string> keys;
             for (const auto& a : c.campaign.arrangements) {
                 keys.push_back(config::join_path("arrangements", a.name) + ".gravity_tilt_deg");
             }
             return keys;
         },
         [](const bench::CampaignConfig& c) {
             const auto& arrangements = c.campaign.arrangements;
             const auto& dampers = c.campaign.dampers;
             return std::any_of(dampers.begin(), dampers.end(),
                                [](const bench::DamperSpec& d) {
                                    return d.model == bench::DamperSpec::Model::dem;
                                }) &&
                    std::all_of(arrangements.begin(), arrangements.end(),
                                [](const auto& a) { return a.gravity_tilt_deg == 0.0; });
         },
         ""});
    // The scatter acts most at the low levels: a bed of equal spheres packs in ordered,
    // interlocked layers that hardly move below lift-off, a scattered one packs loosely and
    // rearranges earlier, so the onset of the damping comes sooner and smoother; in the
    // collisional regime the mean clearance rules and the mean size is kept. Hence more damping
    // measured than simulated, largest at the low levels and fading with the level: 1/A.
    rows.push_back(
        {"particle-size-scatter",
         "the scatter of the particles' sizes",
         "Spheres not all of their nominal size (tolerances, wear): the scatter of the diameters "
         "alters the packing and the effective clearance, which the damping depends on strongly "
         "(Friend and Kinra 2000), and so moves and smooths the damping's peak over the level. "
         "Every DEM damper whose spheres are all nominal gets diameters nominal (1 + s u), u "
         "uniform of unit variance (particles.diameter_scatter), its relative standard "
         "deviation s searched from 0.005 to 0.2. Fitted on the coupled campaign.",
         {{LevelFeature::damping_ratio, ScalingShape::inverse, +1}},
         switch_particles(
             lacks_size_scatter,
             // On, barely: a scatter of 0 is the model without it.
             [](dem::ParticleOptions& p) { p.diameter_scatter = 0.005; },
             "diameter_scatter=0.005:0.2"),
         has_dem_damper_lacking(lacks_size_scatter),
         ""});
    return rows;
}

/// The BIC of `shape` among a mismatch's fitted shapes (infinite when not fitted).
double bic_of(const FeatureMismatch& m, ScalingShape shape) {
    for (const auto& fit : m.scaling) {
        if (fit.shape == shape) return fit.bic;
    }
    return std::numeric_limits<double>::infinity();
}

/// The sign of the residual's mean weighted by 1/σ².
int residual_sign(const FeatureMismatch& m) {
    double sum = 0.0;
    for (const auto& r : m.residuals) sum += r.residual / (r.sigma * r.sigma);
    return sum > 0.0 ? +1 : sum < 0.0 ? -1 : 0;
}

}  // namespace

const std::vector<CatalogueEntry>& physics_catalogue() {
    static const std::vector<CatalogueEntry> rows = build_catalogue();
    return rows;
}

const CatalogueEntry& catalogue_entry(std::string_view name) {
    std::string names;
    for (const auto& e : physics_catalogue()) {
        if (e.name == name) return e;
        names += (names.empty() ? "" : ", ") + e.name;
    }
    throw std::invalid_argument("no physics '" + std::string(name) + "' in the catalogue (" +
                                names + ")");
}

std::string model_reference_quantity(const bench::CampaignConfig& config) {
    if (config.structure.excitation.kind != structure::ExcitationSpec::Kind::force) {
        return "acceleration";
    }
    return config.physics.shaker.on() ? "voltage" : "force";
}

std::vector<CandidateScore> rank_candidates(const bench::CampaignConfig& config,
                                            const std::vector<FeatureMismatch>& mismatches,
                                            const std::string& measured_reference) {
    const std::string modelled = model_reference_quantity(config);
    const bool other_reference = !measured_reference.empty() && measured_reference != modelled;
    std::vector<CandidateScore> out;
    for (const auto& entry : physics_catalogue()) {
        if (entry.applies && !entry.applies(config)) continue;
        if (!entry.makes_reference.empty() &&
            !(other_reference && entry.makes_reference == measured_reference)) {
            continue;
        }
        CandidateScore c;
        c.entry = &entry;
        std::string why;
        const auto add = [&](double points, const std::string& text) {
            c.score += points;
            why += (why.empty() ? "" : "; ") + text;
        };
        if (other_reference) {
            if (entry.makes_reference == measured_reference) {
                add(4.0, "the recording is referenced to a " + measured_reference +
                             ", the model to a " + modelled + ": it turns one into the other");
            } else {
                add(-4.0, "it cannot turn the model's " + modelled + " into the recorded " +
                              measured_reference);
            }
        }
        for (const auto& m : mismatches) {
            const std::string what = m.arrangement + " " + level_feature_name(m.feature);
            const auto expected =
                std::find_if(entry.signature.begin(), entry.signature.end(),
                             [&](const FeatureSignature& s) { return s.feature == m.feature; });
            if (expected == entry.signature.end()) {
                const bool watched = m.feature == LevelFeature::damping_ratio ||
                                     m.feature == LevelFeature::natural_frequency;
                if (watched && m.beyond_noise)
                    add(-1.0, what + " disagrees, which it leaves alone");
                continue;
            }
            if (!m.beyond_noise) {
                add(-1.0, what + " agrees, which it would move");
                continue;
            }
            if (residual_sign(m) != expected->sign) {
                add(-2.0, what + " is off the other way");
                continue;
            }
            add(2.0, what + " is off the way it moves it");
            if (!m.scaling.empty() && bic_of(m, expected->shape) <= m.scaling.front().bic + 2.0) {
                add(1.0, "and scales " + scaling_shape_name(expected->shape) + " as it does");
            }
        }
        c.reason = why.empty() ? "no feature it moves was compared" : why;
        out.push_back(c);
    }
    std::stable_sort(out.begin(), out.end(), [](const CandidateScore& a, const CandidateScore& b) {
        return a.score > b.score;
    });
    return out;
}

}  // namespace sb::correlation

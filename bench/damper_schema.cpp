// The keys of [dampers.NAME]: mounting, enclosure, particles, contact law, settling.
#include <algorithm>

#include "bench/campaign_spec.hpp"
#include "bench/describing_function.hpp"
#include "bench/schema_parts.hpp"
#include "config/builder.hpp"
#include "config/value.hpp"
#include "dem/contact_law.hpp"
#include "identification/file_error.hpp"

namespace sb::bench::schema {
namespace {

using config::Bound;
using config::TableBuilder;

std::shared_ptr<const config::Table> enclosure_table() {
    TableBuilder<dem::RodGridOptions> rods(
        "obstacle grid of thin rods (paper 002)",
        "Rods of `rod_diameter_m` along every edge of a cubic lattice of cells `cell_size_m` "
        "apart, through the whole cavity.");
    rods.boolean(
        "enabled", [](dem::RodGridOptions & r) -> auto& { return r.enabled; },
        "obstacle grid on (the other keys need it)");
    const auto on = [](const dem::RodGridOptions& r) { return r.enabled; };
    rods.number(
            "rod_diameter_m", [](dem::RodGridOptions & r) -> auto& { return r.rod_diameter_m; },
            "rod diameter")
        .unit("m")
        .bound(Bound::positive())
        .when(on, "only with enabled = true", true);
    rods.number(
            "cell_size_m", [](dem::RodGridOptions & r) -> auto& { return r.cell_size_m; },
            "edge of the cubic cells")
        .unit("m")
        .bound(Bound::positive())
        .when(on, "only with enabled = true", true);
    rods.vector3(
            "origin_m", [](dem::RodGridOptions & r) -> auto& { return r.origin_m; },
            "one lattice node, enclosure frame")
        .unit("m")
        .when(on, "only with enabled = true", true);

    TableBuilder<dem::PlateOptions> plate("partition ribs",
                                          "A solid axis-aligned plate in the enclosure frame.");
    plate
        .vector3(
            "min_corner_m", [](dem::PlateOptions & p) -> auto& { return p.min_corner_m; },
            "plate corner with the smallest coordinates")
        .unit("m")
        .required();
    plate
        .vector3(
            "max_corner_m", [](dem::PlateOptions & p) -> auto& { return p.max_corner_m; },
            "plate corner with the largest coordinates")
        .unit("m")
        .required();

    TableBuilder<dem::EnclosureOptions> t(
        "the cavity",
        "The cavity in its own frame: axis along local z, bottom at z = 0, centred on the axis.");
    t.choice(
        "shape", [](dem::EnclosureOptions & e) -> auto& { return e.shape; },
        dem::kEnclosureShapeNames, "cavity shape");
    const auto cylinder = [](const dem::EnclosureOptions& e) {
        return e.shape == dem::EnclosureShape::cylinder;
    };
    const auto box = [](const dem::EnclosureOptions& e) {
        return e.shape == dem::EnclosureShape::box;
    };
    t.number(
         "inner_diameter_m", [](dem::EnclosureOptions & e) -> auto& { return e.inner_diameter_m; },
         "cylinder inner diameter")
        .unit("m")
        .bound(Bound::positive())
        .when(cylinder, "only for shape = \"cylinder\"", true);
    t.number(
         "height_m", [](dem::EnclosureOptions & e) -> auto& { return e.height_m; },
         "inner height along the damper axis")
        .unit("m")
        .bound(Bound::positive());
    t.number(
         "length_x_m", [](dem::EnclosureOptions & e) -> auto& { return e.length_x_m; },
         "box inner size along local x")
        .unit("m")
        .bound(Bound::positive())
        .when(box, "only for shape = \"box\"", true);
    t.number(
         "length_y_m", [](dem::EnclosureOptions & e) -> auto& { return e.length_y_m; },
         "box inner size along local y")
        .unit("m")
        .bound(Bound::positive())
        .when(box, "only for shape = \"box\"", true);
    t.table(
        "rods", [](dem::EnclosureOptions & e) -> auto& { return e.rods; }, rods.build());
    t.array_of_tables(
        "plates", [](dem::EnclosureOptions & e) -> auto& { return e.plates; }, plate.build());
    return t.build();
}

std::shared_ptr<const config::Table> particles_table() {
    TableBuilder<dem::SizeFraction> size("size distribution",
                                         "One class of a discrete size distribution; the number "
                                         "fractions must sum to 1.");
    size.number(
            "diameter_m", [](dem::SizeFraction & f) -> auto& { return f.diameter_m; },
            "diameter of the class")
        .unit("m")
        .bound(Bound::positive())
        .required();
    size.number(
            "number_fraction", [](dem::SizeFraction & f) -> auto& { return f.number_fraction; },
            "share of the particle count")
        .unit("-")
        .bound(Bound::left_open(0.0, 1.0))
        .required();

    TableBuilder<dem::ParticleOptions> t("the particles");
    t.integer(
         "count", [](dem::ParticleOptions & p) -> auto& { return p.count; }, "number of spheres")
        .bound(Bound::at_least(1));
    t.number(
         "diameter_m", [](dem::ParticleOptions & p) -> auto& { return p.diameter_m; },
         "sphere diameter")
        .unit("m")
        .bound(Bound::positive())
        .when([](const dem::ParticleOptions& p) { return p.size_distribution.empty(); },
              "not used with [[sizes]]");
    t.number(
         "diameter_scatter", [](dem::ParticleOptions & p) -> auto& { return p.diameter_scatter; },
         "relative standard deviation of the sphere diameters")
        .unit("-")
        .bound(Bound::closed(0.0, dem::kMaxDiameterScatter))
        .calibrated_within(0.0, dem::kMaxDiameterScatter)
        .doc(
            "relative standard deviation s of the sphere diameters about their nominal value "
            "(`diameter_m` or the class's: a manufacturing tolerance, wear), which moves the "
            "packing and the clearance (Friend and Kinra 2000): each sphere nominal (1 + s u), u "
            "uniform in [-sqrt 3, sqrt 3] from the filling's seed; 0: every sphere its nominal "
            "size");
    t.number(
         "density_kg_m3",
         [](dem::ParticleOptions & p) -> auto& { return p.material.density_kg_m3; },
         "particle density")
        .unit("kg/m^3")
        .bound(Bound::positive())
        .leaf("material.density_kg_m3");
    t.number(
         "youngs_modulus_pa",
         [](dem::ParticleOptions & p) -> auto& { return p.material.youngs_modulus_pa; },
         "particle Young's modulus (Hertz)")
        .unit("Pa")
        .bound(Bound::positive())
        .leaf("material.youngs_modulus_pa");
    t.number(
         "poisson_ratio",
         [](dem::ParticleOptions & p) -> auto& { return p.material.poisson_ratio; },
         "particle Poisson ratio (Hertz)")
        .unit("-")
        .bound(Bound::closed(-0.999, 0.4999))
        .leaf("material.poisson_ratio");
    t.array_of_tables(
         "sizes", [](dem::ParticleOptions & p) -> auto& { return p.size_distribution; },
         size.build())
        .leaf("size_distribution");
    return t.build();
}

std::shared_ptr<const config::Table> contact_table() {
    TableBuilder<ContactSpec> t("the contact law",
                                "Normal, damping, tangential and rolling pieces with their "
                                "coefficients (see docs/dem.md).");
    t.choice(
         "normal", [](ContactSpec & c) -> auto& { return c.normal; }, dem::kNormalLawNames,
         "normal law")
        .doc(
            "normal law: `hooke`, a linear spring sized to bound the overlap (paper 000's "
            "practice), or `hertz`, F = k delta^1.5, with `stiffness_for = \"materials\"` each "
            "pair's k from the Young's moduli and Poisson ratios; the law moves paper 000's "
            "damping by up to a third at 1-2 g, docs/validation.md says where and why the "
            "default is the linear one");
    t.choice(
         "damping", [](ContactSpec & c) -> auto& { return c.damping; }, dem::kDampingLawNames,
         "normal damping")
        .doc(
            "normal dashpot from the restitution coefficient: `restitution` picks the one that "
            "matches the normal law, or name it (`linear_dashpot` with hooke, `hertz_dashpot` "
            "with hertz), or `viscoelastic` (hertz): a dissipative constant instead of a "
            "restitution, whose restitution falls with the impact speed, or `viscous`: a "
            "dashpot coefficient given directly, as a drop-bounce test measures it");
    t.choice(
         "tangential", [](ContactSpec & c) -> auto& { return c.tangential; },
         dem::kTangentialLawNames, "tangential law")
        .doc(
            "stateless directional Coulomb (papers 000, 001) or a history spring capped by "
            "Coulomb (static friction)");
    t.choice(
         "rolling", [](ContactSpec & c) -> auto& { return c.rolling; }, dem::kRollingLawNames,
         "rolling resistance")
        .doc("rolling resistance torque mu_r R* F_n");
    t.number(
         "normal_stiffness", [](ContactSpec & c) -> auto& { return c.normal_stiffness; },
         "normal stiffness")
        .unit("N/m (hooke), N/m^1.5 (hertz)")
        .bound(Bound::positive())
        .automatic(
            "chosen per sweep so that the largest overlap at the largest expected impact "
            "speed is max_overlap_fraction of the diameter");
    t.number(
         "max_overlap_fraction", [](ContactSpec & c) -> auto& { return c.max_overlap_fraction; },
         "automatic stiffness: largest overlap / diameter")
        .unit("-")
        .bound(Bound::closed(1e-6, 0.2));
    t.number(
         "time_step_fraction", [](ContactSpec & c) -> auto& { return c.time_step_fraction; },
         "DEM time step / contact time")
        .unit("-")
        .bound(Bound::closed(1e-3, 0.5))
        .automatic(
            "the largest of 1/10, 1/14, 1/20, 1/28, 1/40, 1/56 and 1/80 of the contact time "
            "of two of the smallest spheres at which single impacts (two of them head on, one "
            "onto a wall, from eight phases of the step) give the restitution of a 1/320 step "
            "within 0.5 % on average and 2 % at worst; 1/80 if none does");
    t.choice(
         "stiffness_for", [](ContactSpec & c) -> auto& { return c.stiffness_for; },
         ContactSpec::kStiffnessForNames, "what an automatic stiffness is sized for")
        .doc(
            "what an automatic stiffness is sized for: the largest level of the campaign (one "
            "stiffness and time step for every sweep, so the numerics do not change along the "
            "damping curve) or each sweep's own level (cheaper at low levels); `materials` "
            "(normal = \"hertz\"): no stiffness to size, each pair's Hertz constant 4/3 E* "
            "sqrt(R*) from the Young's moduli and Poisson ratios, the time step for the "
            "campaign's largest level");
    t.number(
         "restitution", [](ContactSpec & c) -> auto& { return c.particle_particle.restitution; },
         "particle-particle coefficient of restitution")
        .unit("-")
        .bound(Bound::left_open(0.0, 1.0))
        .calibrated_within(0.3, 0.98)
        .leaf("particle_particle.restitution");
    t.number(
         "sliding_friction",
         [](ContactSpec & c) -> auto& { return c.particle_particle.sliding_friction; },
         "particle-particle sliding friction coefficient")
        .unit("-")
        .bound(Bound::non_negative())
        .calibrated_within(0.1, 1.0)
        .leaf("particle_particle.sliding_friction");
    t.number(
         "rolling_friction",
         [](ContactSpec & c) -> auto& { return c.particle_particle.rolling_friction; },
         "particle-particle rolling friction coefficient")
        .unit("-")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 0.05)
        .leaf("particle_particle.rolling_friction");
    t.number(
         "wall_restitution", [](ContactSpec & c) -> auto& { return c.wall_restitution; },
         "particle-wall coefficient of restitution")
        .unit("-")
        .bound(Bound::left_open(0.0, 1.0))
        .follows("restitution")
        .leaf("particle_wall.restitution");
    t.number(
         "wall_sliding_friction", [](ContactSpec & c) -> auto& { return c.wall_sliding_friction; },
         "particle-wall sliding friction coefficient")
        .unit("-")
        .bound(Bound::non_negative())
        .follows("sliding_friction")
        .leaf("particle_wall.sliding_friction");
    t.number(
         "wall_rolling_friction", [](ContactSpec & c) -> auto& { return c.wall_rolling_friction; },
         "particle-wall rolling friction coefficient")
        .unit("-")
        .bound(Bound::non_negative())
        .follows("rolling_friction")
        .leaf("particle_wall.rolling_friction");
    const auto viscoelastic = [](const ContactSpec& c) {
        return c.damping == dem::DampingLaw::viscoelastic;
    };
    t.number(
         "dissipative_constant_s",
         [](ContactSpec & c) -> auto& { return c.particle_particle.dissipative_constant_s; },
         "particle-particle dissipative constant A of the viscoelastic damping")
        .unit("s")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 1e-5)
        .when(viscoelastic, "only with damping = \"viscoelastic\"")
        .leaf("particle_particle.dissipative_constant_s")
        .doc(
            "particle-particle dissipative constant A of the viscoelastic damping, F_d = 3/2 A "
            "k sqrt(delta) delta_dot: the restitution falls with the impact speed, 1 - e = "
            "1.15344 (3/2) A (k/m*)^(2/5) v^(1/5) to first order (Ramirez et al. 1999)");
    t.number(
         "wall_dissipative_constant_s",
         [](ContactSpec & c) -> auto& { return c.wall_dissipative_constant_s; },
         "particle-wall dissipative constant A of the viscoelastic damping")
        .unit("s")
        .bound(Bound::non_negative())
        .follows("dissipative_constant_s")
        .when(viscoelastic, "only with damping = \"viscoelastic\"")
        .leaf("particle_wall.dissipative_constant_s");
    const auto viscous = [](const ContactSpec& c) { return c.damping == dem::DampingLaw::viscous; };
    t.number(
         "dashpot_n_s_per_m",
         [](ContactSpec & c) -> auto& { return c.particle_particle.dashpot_n_s_per_m; },
         "particle-particle dashpot coefficient c of the viscous damping, F_d = c delta_dot")
        .unit("N s/m")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 100.0)
        .when(viscous, "only with damping = \"viscous\"")
        .leaf("particle_particle.dashpot_n_s_per_m");
    t.number(
         "wall_dashpot_n_s_per_m",
         [](ContactSpec & c) -> auto& { return c.wall_dashpot_n_s_per_m; },
         "particle-wall dashpot coefficient c of the viscous damping")
        .unit("N s/m")
        .bound(Bound::non_negative())
        .follows("dashpot_n_s_per_m")
        .when(viscous, "only with damping = \"viscous\"")
        .leaf("particle_wall.dashpot_n_s_per_m");
    t.number(
         "wall_youngs_modulus_pa",
         [](ContactSpec & c) -> auto& { return c.wall_material.youngs_modulus_pa; },
         "wall Young's modulus (Hertz)")
        .unit("Pa")
        .bound(Bound::positive())
        .leaf("wall_material.youngs_modulus_pa");
    t.number(
         "wall_poisson_ratio",
         [](ContactSpec & c) -> auto& { return c.wall_material.poisson_ratio; },
         "wall Poisson ratio (Hertz)")
        .unit("-")
        .bound(Bound::closed(-0.999, 0.4999))
        .leaf("wall_material.poisson_ratio");
    // The lateral surface may be of another material than the ends (paper 000: a PMMA tube
    // between aluminium ends).
    t.number(
         "side_restitution", [](ContactSpec & c) -> auto& { return c.side_restitution; },
         "particle-side coefficient of restitution (the lateral surface)")
        .unit("-")
        .bound(Bound::left_open(0.0, 1.0))
        .follows("wall_restitution")
        .leaf("particle_side.restitution");
    t.number(
         "side_sliding_friction", [](ContactSpec & c) -> auto& { return c.side_sliding_friction; },
         "particle-side sliding friction coefficient (the lateral surface)")
        .unit("-")
        .bound(Bound::non_negative())
        .follows("wall_sliding_friction")
        .leaf("particle_side.sliding_friction");
    t.number(
         "side_rolling_friction", [](ContactSpec & c) -> auto& { return c.side_rolling_friction; },
         "particle-side rolling friction coefficient (the lateral surface)")
        .unit("-")
        .bound(Bound::non_negative())
        .follows("wall_rolling_friction")
        .leaf("particle_side.rolling_friction");
    t.number(
         "side_youngs_modulus_pa",
         [](ContactSpec & c) -> auto& { return c.side_youngs_modulus_pa; },
         "lateral surface's Young's modulus (Hertz)")
        .unit("Pa")
        .bound(Bound::positive())
        .follows("wall_youngs_modulus_pa")
        .leaf("side_material.youngs_modulus_pa");
    t.number(
         "side_poisson_ratio", [](ContactSpec & c) -> auto& { return c.side_poisson_ratio; },
         "lateral surface's Poisson ratio (Hertz)")
        .unit("-")
        .bound(Bound::closed(-0.999, 0.4999))
        .follows("wall_poisson_ratio")
        .leaf("side_material.poisson_ratio");
    // The obstacle grid's rods (enclosure.rods) may be of another material than the walls.
    t.number(
         "rod_restitution", [](ContactSpec & c) -> auto& { return c.rod_restitution; },
         "particle-rod coefficient of restitution (obstacle grid)")
        .unit("-")
        .bound(Bound::left_open(0.0, 1.0))
        .follows("wall_restitution")
        .leaf("particle_rod.restitution");
    t.number(
         "rod_sliding_friction", [](ContactSpec & c) -> auto& { return c.rod_sliding_friction; },
         "particle-rod sliding friction coefficient (obstacle grid)")
        .unit("-")
        .bound(Bound::non_negative())
        .follows("wall_sliding_friction")
        .leaf("particle_rod.sliding_friction");
    t.number(
         "rod_rolling_friction", [](ContactSpec & c) -> auto& { return c.rod_rolling_friction; },
         "particle-rod rolling friction coefficient (obstacle grid)")
        .unit("-")
        .bound(Bound::non_negative())
        .follows("wall_rolling_friction")
        .leaf("particle_rod.rolling_friction");
    t.number(
         "rod_youngs_modulus_pa", [](ContactSpec & c) -> auto& { return c.rod_youngs_modulus_pa; },
         "rod Young's modulus (Hertz; obstacle grid)")
        .unit("Pa")
        .bound(Bound::positive())
        .follows("wall_youngs_modulus_pa")
        .leaf("rod_material.youngs_modulus_pa");
    t.number(
         "rod_poisson_ratio", [](ContactSpec & c) -> auto& { return c.rod_poisson_ratio; },
         "rod Poisson ratio (Hertz; obstacle grid)")
        .unit("-")
        .bound(Bound::closed(-0.999, 0.4999))
        .follows("wall_poisson_ratio")
        .leaf("rod_material.poisson_ratio");
    t.number(
         "tangential_stiffness_ratio",
         [](ContactSpec & c) -> auto& { return c.tangential_stiffness_ratio; },
         "coulomb_spring: tangential / normal stiffness")
        .unit("-")
        .bound(Bound::positive());
    t.number(
         "slip_regularisation_m_s",
         [](ContactSpec & c) -> auto& { return c.slip_regularisation_m_s; },
         "directional Coulomb and rolling: slip speed of full friction")
        .unit("m/s")
        .bound(Bound::positive());
    return t.build();
}

/// A describing-function damper's characterisation file: given, readable, with rows for it.
Violations check_characterization(const DamperSpec& d) {
    Violations out;
    if (d.model != DamperSpec::Model::describing_function) return out;
    const char* meaning = "characterization.csv of this damper";
    if (d.characterization_file.empty()) {
        out.push_back({"characterization_file", "",
                       "is required with model = \"describing-function\"", meaning});
        return out;
    }
    const std::string value = config::quoted(d.characterization_file.string());
    try {
        const CharacterizationTable table = read_characterization_csv(d.characterization_file);
        if (std::none_of(table.rows.begin(), table.rows.end(),
                         [&](const CharacterizationRow& r) { return r.damper == d.name; })) {
            out.push_back({"characterization_file", value,
                           "holds no rows for damper " + config::quoted(d.name), meaning});
        }
    } catch (const identification::FileError& e) {
        out.push_back(
            {"characterization_file", value, std::string("cannot be read: ") + e.what(), meaning});
    }
    return out;
}

std::shared_ptr<const config::Table> settle_table() {
    TableBuilder<DamperSpec> t(
        "settling under gravity",
        "The filling settles under the arrangement's gravity until at rest; the bed is saved in "
        "`OUT/settled/` and every sweep starts from it (see docs/dem.md).");
    t.number(
         "dt_s", [](DamperSpec & d) -> auto& { return d.settle.dt_s; },
         "largest settling time step (stiff Hooke contacts settle at a 3.5th of their contact "
         "time where that is shorter)")
        .unit("s")
        .bound(Bound::positive());
    t.number(
         "max_time_s", [](DamperSpec & d) -> auto& { return d.settle.max_time_s; },
         "give up after this simulated time")
        .unit("s")
        .bound(Bound::positive());
    t.number(
         "kinetic_threshold_j",
         [](DamperSpec & d) -> auto& { return d.settle.kinetic_threshold_j; },
         "at rest below this translational kinetic energy")
        .unit("J")
        .bound(Bound::positive());
    t.choice(
         "fill", [](DamperSpec & d) -> auto& { return d.fill; }, DamperSpec::kFillNames,
         "how the bed is filled")
        .doc(
            "`random` inserts every sphere at random into the whole cavity and then settles the "
            "bed (loose beds: random insertion jams near a solid fraction of 0.35-0.38); `pour` "
            "fills in batches, each settled under gravity before the next goes into the space "
            "above (dense beds, e.g. paper 002's 5,700 spheres in 30 x 30 x 50 mm, solid "
            "fraction 0.53)");
    return t.build();
}

}  // namespace

std::shared_ptr<const config::Table> lock_table() {
    using dem::LockOptions;
    TableBuilder<LockOptions> t(
        "particles held to the enclosure, and their release",
        "A share of the bed held to the enclosure as it settled (the lowest first, nearest a "
        "magnet under the bottom) and freed at a set time of the run (paper 004's "
        "electromagnet: every granule held, then 30, 60 or 100 % of them freed at 5 s). The "
        "clock is the damper's: it starts with the sweep (or the transient run) and goes on "
        "through its points and a resumed checkpoint, so the release comes at the same moment "
        "of a resumed run.");
    t.number(
         "fraction", [](LockOptions & l) -> auto& { return l.fraction; },
         "share of the particles held from the start, the lowest along the enclosure axis first")
        .unit("-")
        .bound(Bound::closed(0.0, 1.0));
    t.number(
         "release_time_s", [](LockOptions & l) -> auto& { return l.release_time_s; },
         "time of the run at which the release frees its share; 0: never")
        .unit("s")
        .bound(Bound::non_negative());
    t.number(
         "release_fraction", [](LockOptions & l) -> auto& { return l.release_fraction; },
         "share of all particles freed at the release, the highest held first; the rest stay "
         "held")
        .unit("-")
        .bound(Bound::closed(0.0, 1.0));
    return t.build();
}

std::shared_ptr<const config::Table> damper_table() {
    TableBuilder<DamperSpec> t(
        "a particle damper",
        "A particle damper attached to a named point. Its enclosure's own mass belongs to the "
        "structure (a `[[structure.beam.masses]]` entry); its particles are simulated (DEM) or, "
        "with `model = \"rigid\"`, replaced by an equal rigid mass at the centre of a settled "
        "bed.");
    t.string(
         "point", [](DamperSpec & d) -> auto& { return d.point; },
         "named point the damper is attached to")
        .required();
    t.vector3(
         "mount_offset_m", [](DamperSpec & d) -> auto& { return d.mount_offset_m; },
         "enclosure origin (inner bottom centre) from the point at 0 deg without a block")
        .unit("m");
    t.number(
         "bottom_thickness_m", [](DamperSpec & d) -> auto& { return d.bottom_thickness_m; },
         "the enclosure's bottom plate: the enclosure stands, and turns, on its outer face")
        .unit("m")
        .bound(Bound::non_negative());
    t.string(
         "enclosure_mass", [](DamperSpec & d) -> auto& { return d.enclosure_mass; },
         "the structure mass that is this damper's enclosure")
        .optional()
        .doc(
            "name of the `[[structure.beam.masses]]` or `[[structure.matrix.masses]]` entry at "
            "the damper's point that is this enclosure: its centre of gravity and principal "
            "inertia (given for 0 deg) move and turn with the mounting of each arrangement");
    t.boolean(
        "locked", [](DamperSpec & d) -> auto& { return d.locked; },
        "particles locked to the enclosure: a rigid bed whose load still goes through the "
        "coupling loop (a check against the linear model)");
    t.choice(
         "model", [](DamperSpec & d) -> auto& { return d.model; }, DamperSpec::kModelNames,
         "how the particles are represented")
        .doc(
            "dem: simulated particles; rigid: an equal rigid mass; describing-function: the "
            "complex apparent mass measured by `shakerbench characterize`, read from "
            "`characterization_file` and interpolated in amplitude and frequency "
            "(docs/characterisation.md)");
    const auto describing = [](const DamperSpec& d) {
        return d.model == DamperSpec::Model::describing_function;
    };
    t.file(
         "characterization_file", [](DamperSpec & d) -> auto& { return d.characterization_file; },
         "characterization.csv of this damper (relative to the config's folder)")
        .optional()
        .when(describing, "only with model = \"describing-function\"", true)
        .doc(
            "`characterization.csv` written by `shakerbench characterize` for this damper "
            "(same name) and the arrangements run, relative to the config's folder; required "
            "with model = \"describing-function\"");
    t.number(
         "characterization_scale", [](DamperSpec & d) -> auto& { return d.characterization_scale; },
         "how many times the characterised bed this damper holds (its apparent mass and bed "
         "mass multiplied by it)")
        .unit("-")
        .bound(Bound::positive())
        .when(describing, "only with model = \"describing-function\"", true)
        .doc(
            "the characterised apparent mass and bed mass multiplied by this factor: a part of "
            "a large bed characterised for the whole (a quarter of the footprint at the full "
            "height: 4), where the walls' share of the part is small enough "
            "(docs/characterisation.md); `predict --scale` sets it with `--characterization`");
    t.integer(
         "threads", [](DamperSpec & d) -> auto& { return d.threads; },
         "OpenMP threads of this damper's DEM (sweeps already run in parallel; 0: OpenMP's "
         "default)")
        .bound(Bound::non_negative())
        .leaf("solver.threads");
    t.number(
         "guard_overlap_fraction", [](DamperSpec & d) -> auto& { return d.guard_overlap_fraction; },
         "overlap / radius beyond which the run stops with an error")
        .unit("-")
        .bound(Bound::closed(1e-6, 1.0))
        .leaf("solver.max_overlap_fraction");
    t.table(
         "enclosure", [](DamperSpec & d) -> auto& { return d.enclosure; }, enclosure_table())
        .leaf("solver.enclosure");
    t.table(
         "particles", [](DamperSpec & d) -> auto& { return d.particles; }, particles_table())
        .leaf("solver.particles");
    t.table(
         "contact", [](DamperSpec & d) -> auto& { return d.contact; }, contact_table())
        .leaf("solver.contact");
    t.table(
         "settle", [](DamperSpec & d) -> auto& { return d; }, settle_table())
        .leaf("settle");
    t.table(
         "lock", [](DamperSpec & d) -> auto& { return d.lock; }, lock_table())
        .leaf("solver.lock");
    t.check([](const DamperSpec& d) { return d.validate(); });
    t.check([](const DamperSpec& d) { return check_characterization(d); });
    t.check([](const DamperSpec& d) {
        Violations out;
        if (d.contact.stiffness_for != ContactSpec::StiffnessFor::materials) return out;
        if (d.contact.normal != dem::NormalLaw::hertz) {
            out.push_back({"contact.stiffness_for", "\"materials\"",
                           "needs normal = \"hertz\": a Hooke spring's stiffness is not a "
                           "property of the materials",
                           "what an automatic stiffness is sized for"});
        }
        if (d.contact.normal_stiffness) {
            out.push_back({"contact.normal_stiffness",
                           config::number_text(*d.contact.normal_stiffness),
                           "cannot be given with stiffness_for = \"materials\", which takes it "
                           "from the Young's moduli and Poisson ratios",
                           "normal stiffness"});
        }
        return out;
    });
    t.check([](const DamperSpec& d) {
        Violations out;
        if (d.locked && d.lock.fraction > 0.0) {
            out.push_back({"lock.fraction", config::number_text(d.lock.fraction),
                           "cannot be given with locked = true, which holds every particle for "
                           "good",
                           ""});
        }
        if (d.lock.release_time_s > 0.0 && !(d.lock.fraction > 0.0)) {
            out.push_back({"lock.release_time_s", config::number_text(d.lock.release_time_s),
                           "releases nothing: lock.fraction holds no particle", ""});
        }
        return out;
    });
    return t.build();
}

}  // namespace sb::bench::schema

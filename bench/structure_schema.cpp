// The keys of [structure]: beam, lumped and imported models, damping, excitation.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "bench/schema_parts.hpp"
#include "config/builder.hpp"
#include "structure/matrix_market.hpp"
#include "structure/spec.hpp"

namespace sb::bench::schema {
namespace {

using config::Bound;
using config::Declaration;
using config::TableBuilder;
using structure::BeamSpec;
using structure::DampingSpec;
using structure::ExcitationSpec;
using structure::LumpedMass;
using structure::LumpedSpec;
using structure::MatrixSpec;
using structure::NamedPoint;
using structure::StructureSpec;
using structure::Support;
using structure::SupportKind;

std::shared_ptr<const config::Table> support_table() {
    TableBuilder<Support> t("a support",
                            "One table per support; at least one is required. Supports at the "
                            "same position act together, e.g. a `pinned` one and an `elastic` "
                            "one with rotational springs only make a spring-hinged root.");
    t.number(
         "x_m", [](Support & s) -> auto& { return s.x_m; }, "support position along the beam")
        .unit("m")
        .bound(Bound::non_negative())
        .required();
    t.choice(
         "kind", [](Support & s) -> auto& { return s.kind; }, structure::kSupportKindNames,
         "boundary condition")
        .doc(
            "clamped: all six DOFs fixed; pinned: translations and torsion fixed, bending "
            "rotations free; free: nothing fixed; elastic: the springs below (no DOF fixed)");
    const auto elastic = [](const Support& s) { return s.kind == SupportKind::elastic; };
    t.vector3(
         "translational_stiffness_n_per_m",
         [](Support & s) -> auto& { return s.translational_stiffness_n_per_m; },
         "springs along x, y, z")
        .unit("N/m")
        .bound(Bound::non_negative())
        .when(elastic, "only for kind = \"elastic\"", true);
    t.vector3(
         "rotational_stiffness_nm_per_rad",
         [](Support & s) -> auto& { return s.rotational_stiffness_nm_per_rad; },
         "springs about x, y, z")
        .unit("N m/rad")
        .bound(Bound::non_negative())
        .when(elastic, "only for kind = \"elastic\"", true);
    return t.build();
}

std::shared_ptr<const config::Table> mass_table() {
    TableBuilder<LumpedMass> t("lumped masses",
                               "A rigid lumped mass attached to the beam; repeat the table for "
                               "each mass. Give `point` or `x_m`.");
    t.string(
         "name", [](LumpedMass & m) -> auto& { return m.name; }, "label of the mass")
        .follows("point");
    t.string(
         "point", [](LumpedMass & m) -> auto& { return m.point; },
         "the named point the mass sits at (it moves with the point)")
        .optional();
    t.number(
         "x_m", [](LumpedMass & m) -> auto& { return m.x_m; }, "mass position along the beam")
        .unit("m")
        .bound(Bound::non_negative())
        .required()
        .when([](const LumpedMass& m) { return m.point.empty(); }, "only when no point is given",
              true);
    t.number(
         "mass_kg", [](LumpedMass & m) -> auto& { return m.mass_kg; }, "mass")
        .unit("kg")
        .bound(Bound::positive())
        .required();
    t.vector3(
         "inertia_kg_m2", [](LumpedMass & m) -> auto& { return m.inertia_kg_m2; },
         "rotary inertia about the mass's own centre of gravity, about x, y, z")
        .unit("kg m^2")
        .bound(Bound::non_negative());
    t.vector3(
         "offset_m", [](LumpedMass & m) -> auto& { return m.offset_m; },
         "centre of gravity offset from the beam axis")
        .unit("m");
    return t.build();
}

std::shared_ptr<const config::Table> beam_table() {
    TableBuilder<BeamSpec> t("the beam",
                             "A straight prismatic beam with a rectangular section. The structure "
                             "frame: x along the beam axis from the root, y along the section's "
                             "longer side, z along the shorter side (the weak bending direction, "
                             "which the shaker drives).");
    t.number(
         "length_m", [](BeamSpec & b) -> auto& { return b.length_m; }, "beam length")
        .unit("m")
        .bound(Bound::positive())
        .required();
    t.number(
         "width_m", [](BeamSpec & b) -> auto& { return b.width_m; },
         "section side along y, the longer one")
        .unit("m")
        .bound(Bound::positive())
        .required();
    t.number(
         "thickness_m", [](BeamSpec & b) -> auto& { return b.thickness_m; },
         "section side along z, the shorter one; drive the stiff direction with "
         "excitation.direction = [0, 1, 0]")
        .unit("m")
        .bound(Bound::positive())
        .required()
        .doc(
            "section side along z, the shorter one (at most `width_m`): z is the weak bending "
            "direction the shaker drives. A beam driven in its stiff direction keeps this frame "
            "and sets `excitation.direction = [0, 1, 0]`");
    t.number(
         "density_kg_m3", [](BeamSpec & b) -> auto& { return b.density_kg_m3; }, "beam density")
        .unit("kg/m^3")
        .bound(Bound::positive())
        .required();
    t.number(
         "youngs_modulus_pa", [](BeamSpec & b) -> auto& { return b.youngs_modulus_pa; },
         "Young's modulus")
        .unit("Pa")
        .bound(Bound::positive())
        .required();
    t.number(
         "shear_modulus_pa", [](BeamSpec & b) -> auto& { return b.shear_modulus_pa; },
         "shear modulus")
        .unit("Pa")
        .bound(Bound::positive())
        .optional()
        .doc(
            "shear modulus; given: Timoshenko elements (shear deformation, kappa = 5/6); absent: "
            "Euler-Bernoulli");
    t.integer(
         "elements", [](BeamSpec & b) -> auto& { return b.min_elements; },
         "least number of beam elements")
        .bound(Bound::at_least(1))
        .doc("least number of elements; nodes are added at every support, point and mass");
    t.named_tables(
        "supports", [](BeamSpec & b) -> auto& { return b.supports; },
        [](Support & s) -> auto& { return s.name; }, support_table());
    Declaration point;
    point.type = config::Type::number;
    point.unit = "m";
    point.bound = Bound::non_negative();
    point.meaning = "named point position along the beam";
    point.doc =
        "a named point on the beam axis (sensor, load cell, shaker, damper) in [0, length]: the "
        "mesh has a node there; outputs, loads, masses and dampers refer to it";
    t.named_numbers(
        "points", [](BeamSpec & b) -> auto& { return b.points; },
        [](NamedPoint & p) -> auto& { return p.name; },
        [](NamedPoint & p) -> auto& { return p.x_m; }, point, "named points");
    t.array_of_tables(
        "masses", [](BeamSpec & b) -> auto& { return b.masses; }, mass_table());
    return t.build();
}

std::shared_ptr<const config::Table> lumped_table() {
    TableBuilder<LumpedSpec::Mass> mass("point masses",
                                        "A mass of the chain; its name is a point.");
    mass.string(
            "name", [](LumpedSpec::Mass & m) -> auto& { return m.name; },
            "mass name (a named point)")
        .required();
    mass.number(
            "mass_kg", [](LumpedSpec::Mass & m) -> auto& { return m.mass_kg; }, "mass")
        .unit("kg")
        .bound(Bound::positive())
        .required();
    TableBuilder<LumpedSpec::Spring> spring(
        "springs between masses",
        "A spring-dashpot between two masses or a mass and \"ground\". When any dashpot is "
        "given, the dashpots form the damping matrix and [structure.damping] is not used.");
    spring
        .string(
            "from", [](LumpedSpec::Spring & s) -> auto& { return s.from; },
            "mass name or \"ground\"")
        .required();
    spring
        .string(
            "to", [](LumpedSpec::Spring & s) -> auto& { return s.to; }, "mass name or \"ground\"")
        .required();
    spring
        .number(
            "stiffness_n_per_m",
            [](LumpedSpec::Spring & s) -> auto& { return s.stiffness_n_per_m; }, "stiffness")
        .unit("N/m")
        .bound(Bound::positive())
        .required();
    spring
        .number(
            "damping_n_s_per_m",
            [](LumpedSpec::Spring & s) -> auto& { return s.damping_n_s_per_m; }, "viscous damping")
        .unit("N s/m")
        .bound(Bound::non_negative());
    TableBuilder<LumpedSpec> t("the lumped model",
                               "Point masses moving along the excitation direction (an SDOF, or a "
                               "chain like paper 004's). Named points are the masses' names.");
    t.array_of_tables(
        "masses", [](LumpedSpec & l) -> auto& { return l.masses; }, mass.build());
    t.array_of_tables(
        "springs", [](LumpedSpec & l) -> auto& { return l.springs; }, spring.build());
    return t.build();
}

/// The sizes of the Matrix Market files: readable, matching, and named rows inside them.
/// Keys are MatrixSpec's (named DOFs under "named_dofs").
Violations check_matrix_files(const MatrixSpec& spec) {
    Violations out;
    const auto size_of = [&](const char* key, const std::filesystem::path& file,
                             const char* meaning) -> std::optional<structure::MatrixMarketSize> {
        if (file.empty()) return std::nullopt;
        try {
            return structure::read_matrix_market_size(file);
        } catch (const structure::MatrixMarketError& e) {
            // The message starts with the file, which the key's value already names.
            std::string reason = e.what();
            if (const std::string prefix = file.string() + ": "; reason.rfind(prefix, 0) == 0) {
                reason = reason.substr(prefix.size());
            }
            out.push_back(
                {key, config::quoted(file.string()), "cannot be read: " + reason, meaning});
        }
        return std::nullopt;
    };
    const auto shape = [](const structure::MatrixMarketSize& s) {
        return std::to_string(s.rows) + " x " + std::to_string(s.cols);
    };
    const auto mass = size_of("mass_file", spec.mass_file, "Matrix Market mass matrix");
    const auto stiffness =
        size_of("stiffness_file", spec.stiffness_file, "Matrix Market stiffness matrix");
    const auto rigid = size_of("rigid_body_file", spec.rigid_body_file, "rigid translations");
    const auto influence = size_of("base_influence_file", spec.base_influence_file,
                                   "influence vector of the base motion");
    const auto damping = size_of("damping_file", spec.damping_file, "Matrix Market damping matrix");
    if (mass && mass->rows != mass->cols) {
        out.push_back({"mass_file", config::quoted(spec.mass_file.string()),
                       "must hold a square matrix, holds " + shape(*mass), ""});
    }
    if (mass && stiffness && (stiffness->rows != mass->rows || stiffness->cols != mass->cols)) {
        out.push_back({"stiffness_file", config::quoted(spec.stiffness_file.string()),
                       "must hold " + shape(*mass) + " like mass_file, holds " + shape(*stiffness),
                       ""});
    }
    if (mass && rigid && (rigid->rows != mass->rows || rigid->cols != 3)) {
        out.push_back({"rigid_body_file", config::quoted(spec.rigid_body_file.string()),
                       "must hold " + std::to_string(mass->rows) + " x 3, holds " + shape(*rigid),
                       ""});
    }
    if (mass && influence && (influence->rows != mass->rows || influence->cols != 1)) {
        out.push_back({"base_influence_file", config::quoted(spec.base_influence_file.string()),
                       "must hold " + std::to_string(mass->rows) +
                           " x 1 (one value per DOF), holds " + shape(*influence),
                       "influence vector of the base motion"});
    }
    if (mass && damping && (damping->rows != mass->rows || damping->cols != mass->cols)) {
        out.push_back({"damping_file", config::quoted(spec.damping_file.string()),
                       "must hold " + shape(*mass) + " like mass_file, holds " + shape(*damping),
                       ""});
    }
    if (mass) {
        for (const auto& [name, row] : spec.named_dofs) {
            if (row >= mass->rows) {
                out.push_back(
                    {"named_dofs." + name, std::to_string(row),
                     "must be < " + std::to_string(mass->rows) + ", the rows of mass_file", ""});
            }
        }
    }
    return out;
}

/// Base excitation of an imported model needs its influence vector: from the file, or the
/// rigid translation (rigid_body_file, or every row named). Keys are StructureSpec's.
Violations check_matrix_base(const StructureSpec& spec) {
    Violations out;
    const MatrixSpec& m = spec.matrix;
    if (spec.kind != StructureSpec::Kind::matrix ||
        spec.excitation.kind != ExcitationSpec::Kind::base || !m.base_influence_file.empty() ||
        !m.rigid_body_file.empty() || m.mass_file.empty()) {
        return out;
    }
    long rows = 0;
    try {
        rows = structure::read_matrix_market_size(m.mass_file).rows;
    } catch (const structure::MatrixMarketError&) {
        return out;  // reported at mass_file
    }
    std::vector<bool> named(static_cast<std::size_t>(rows), false);
    for (const auto& [name, row] : m.named_dofs) {
        if (row >= 0 && row < rows) named[static_cast<std::size_t>(row)] = true;
    }
    const auto unnamed = std::count(named.begin(), named.end(), false);
    if (unnamed > 0) {
        out.push_back({"matrix.base_influence_file", "absent",
                       "is required under base excitation: " + std::to_string(unnamed) + " of " +
                           std::to_string(rows) +
                           " rows are not named and there is no rigid_body_file, so the rigid "
                           "translation along the excitation direction is unknown",
                       "influence vector of the base motion"});
    }
    return out;
}

std::shared_ptr<const config::Table> point_mass_table() {
    TableBuilder<structure::PointMass> t(
        "masses added to the imported model",
        "A rigid mass added at a named point of the imported model (an enclosure, a sensor); "
        "repeat the table for each mass.");
    t.string(
         "name", [](structure::PointMass & m) -> auto& { return m.name; }, "label of the mass")
        .follows("point");
    t.string(
         "point", [](structure::PointMass & m) -> auto& { return m.point; },
         "the named point the mass is attached to")
        .required()
        .doc(
            "the named point (of `[structure.matrix.dofs]`) the mass is attached to: it adds to "
            "the point's translation DOFs (`p.x`, `p.y`, `p.z`, or the single DOF of a name "
            "without suffix)");
    t.number(
         "mass_kg", [](structure::PointMass & m) -> auto& { return m.mass_kg; }, "mass")
        .unit("kg")
        .bound(Bound::positive())
        .required();
    t.vector3(
         "inertia_kg_m2", [](structure::PointMass & m) -> auto& { return m.inertia_kg_m2; },
         "rotary inertia about the mass's own centre of gravity, about x, y, z")
        .unit("kg m^2")
        .bound(Bound::non_negative())
        .doc(
            "rotary inertia about the mass's own centre of gravity, about x, y, z (acts only "
            "when the point has rotation DOFs)");
    t.vector3(
         "offset_m", [](structure::PointMass & m) -> auto& { return m.offset_m; },
         "centre of gravity offset from the point")
        .unit("m")
        .doc(
            "centre of gravity offset from the point (acts only when the point has rotation DOFs)");
    return t.build();
}

std::shared_ptr<const config::Table> matrix_table() {
    TableBuilder<MatrixSpec> t(
        "imported matrices",
        "A model built elsewhere, as mass and stiffness matrices in Matrix Market coordinate "
        "format (real, general or symmetric), constraints already applied. The files are "
        "checked when the config loads (readable, sizes, named rows); their entries are read "
        "when the model is built, a bad entry reported as `FILE.mtx:LINE: message` (exit 2).");
    t.file(
         "mass_file", [](MatrixSpec & m) -> auto& { return m.mass_file; },
         "Matrix Market mass matrix")
        .required()
        .doc("mass matrix file, relative to the config's folder; symmetric positive definite");
    t.file(
         "stiffness_file", [](MatrixSpec & m) -> auto& { return m.stiffness_file; },
         "Matrix Market stiffness matrix")
        .required()
        .doc("stiffness matrix file, same size as the mass matrix, symmetric");
    t.file(
         "damping_file", [](MatrixSpec & m) -> auto& { return m.damping_file; },
         "Matrix Market damping matrix")
        .optional()
        .doc(
            "damping matrix C file, same size as the mass matrix, symmetric positive "
            "semi-definite (joints, dashpots, a damping model built with the import); it "
            "replaces `[structure.damping]`: each mode's ratio is phi^T C phi / (2 omega), the "
            "modal model keeping the diagonal of Phi^T C Phi");
    t.file(
         "rigid_body_file", [](MatrixSpec & m) -> auto& { return m.rigid_body_file; },
         "rigid translations")
        .optional()
        .doc(
            "n x 3 matrix whose column d holds every DOF's value in a unit rigid translation "
            "along x, y, z (0 for rotations); used for the effective masses and, under base "
            "excitation without `base_influence_file`, for the influence vector");
    t.file(
         "base_influence_file", [](MatrixSpec & m) -> auto& { return m.base_influence_file; },
         "influence vector of the base motion")
        .optional()
        .doc(
            "n x 1 matrix: every DOF's displacement per unit base displacement along the "
            "excitation direction (the quasi-static influence vector r of M y'' + C y' + K y = "
            "-M r a_base); absent: the rigid translation along that direction, from "
            "`rigid_body_file` or from the names when every row is named. Only for "
            "`excitation.kind = \"base\"`");
    Declaration row;
    row.type = config::Type::integer;
    row.bound = Bound::non_negative();
    row.meaning = "zero-based row of a named DOF";
    row.doc =
        "names the DOF in this zero-based row (less than the matrix size). A named point `p` is "
        "made of the DOFs named `p.x`, `p.y`, `p.z` (and `p.rx`, `p.ry`, `p.rz`), whichever "
        "exist; a name without such a suffix is a point moving along the excitation direction";
    t.named_numbers(
         "dofs", [](MatrixSpec & m) -> auto& { return m.named_dofs; },
         [](std::pair<std::string, int> & d) -> auto& { return d.first; },
         [](std::pair<std::string, int> & d) -> auto& { return d.second; }, row, "named DOFs")
        .leaf("named_dofs");
    t.array_of_tables(
        "masses", [](MatrixSpec & m) -> auto& { return m.masses; }, point_mass_table());
    t.check([](const MatrixSpec& m) { return check_matrix_files(m); });
    return t.build();
}

std::shared_ptr<const config::Table> damping_table() {
    TableBuilder<DampingSpec> t("structural damping");
    t.choice(
         "model", [](DampingSpec & d) -> auto& { return d.model; }, DampingSpec::kModelNames,
         "damping model")
        .doc("modal ratios, or C = alpha M + beta K");
    const auto modal = [](const DampingSpec& d) { return d.model == DampingSpec::Model::modal; };
    const auto rayleigh = [](const DampingSpec& d) {
        return d.model == DampingSpec::Model::rayleigh;
    };
    t.number(
         "default_ratio", [](DampingSpec & d) -> auto& { return d.default_ratio; },
         "damping ratio of every mode not in modal_ratios")
        .unit("-")
        .bound(Bound::right_open(0.0, 1.0))
        .calibrated_within(0.0, 0.05)
        .when(modal, "only for model = \"modal\"", true);
    t.numbers(
         "modal_ratios", [](DampingSpec & d) -> auto& { return d.modal_ratios; },
         "damping ratios of modes 1, 2, ...")
        .unit("-")
        .bound(Bound::right_open(0.0, 1.0))
        .when(modal, "only for model = \"modal\"", true);
    t.number(
         "alpha_per_s", [](DampingSpec & d) -> auto& { return d.alpha_per_s; },
         "Rayleigh mass-proportional coefficient (zeta = alpha/2 omega + beta omega/2)")
        .unit("1/s")
        .bound(Bound::non_negative())
        .when(rayleigh, "only for model = \"rayleigh\"", true);
    t.number(
         "beta_s", [](DampingSpec & d) -> auto& { return d.beta_s; },
         "Rayleigh stiffness-proportional coefficient")
        .unit("s")
        .bound(Bound::non_negative())
        .when(rayleigh, "only for model = \"rayleigh\"", true);
    return t.build();
}

std::shared_ptr<const config::Table> excitation_table() {
    TableBuilder<ExcitationSpec> t("how the structure is driven");
    t.choice(
         "kind", [](ExcitationSpec & e) -> auto& { return e.kind; }, ExcitationSpec::kKindNames,
         "how the structure is driven")
        .doc(
            "a force at a named point (shaker with load cell), or prescribed motion of a "
            "support or of an imported model's base (relative coordinates)");
    t.string(
         "point", [](ExcitationSpec & e) -> auto& { return e.point; },
         "the named point the shaker drives")
        .required()
        .when([](const ExcitationSpec& e) { return e.kind == ExcitationSpec::Kind::force; },
              "only for kind = \"force\"", true);
    t.string(
         "support", [](ExcitationSpec & e) -> auto& { return e.support; }, "the support that moves")
        .optional()
        .doc(
            "the support that moves: a support of `[structure.beam.supports]`, or \"ground\" for "
            "a lumped model (required for both); absent for an imported model, which has no "
            "supports (`structure.matrix.base_influence_file` or its rigid translation says how "
            "it follows the base)")
        .when([](const ExcitationSpec& e) { return e.kind == ExcitationSpec::Kind::base; },
              "only for kind = \"base\"", true);
    t.vector3(
        "direction", [](ExcitationSpec & e) -> auto& { return e.direction; },
        "direction of the force or base motion, not all 0 (normalised)");
    return t.build();
}

}  // namespace

std::shared_ptr<const config::Table> structure_table() {
    using Kind = StructureSpec::Kind;
    TableBuilder<StructureSpec> t("the structure under test");
    t.choice(
         "kind", [](StructureSpec & s) -> auto& { return s.kind; }, StructureSpec::kKindNames,
         "kind of structure model")
        .doc(
            "which model: `[structure.beam]`, `[structure.lumped]` or `[structure.matrix]` (only "
            "the one of this kind may be present)");
    t.integer(
         "modes", [](StructureSpec & s) -> auto& { return s.modes; },
         "modes kept in the reduced modal model")
        .bound(Bound::at_least(1))
        .doc("modes kept in the reduced modal model and printed by `modes`");
    t.vector3(
         "gravity_m_s2", [](StructureSpec & s) -> auto& { return s.gravity_m_s2; },
         "gravity: its magnitude is what every arrangement turns to its own direction "
         "(horizontal oscillation: -y, vertical: -z, tilted by gravity_tilt_deg); it acts on "
         "the particles, not on the linear structure; [0, 0, 0]: weightless (a damper in "
         "orbit, an impact-damper model without gravity)")
        .unit("m/s^2");
    t.table(
         "beam", [](StructureSpec & s) -> auto& { return s.beam; }, beam_table())
        .meaning("the beam of a structure of kind \"beam\"")
        .required()
        .when([](const StructureSpec& s) { return s.kind == Kind::beam; },
              "only for kind = \"beam\"", true);
    t.table(
         "lumped", [](StructureSpec & s) -> auto& { return s.lumped; }, lumped_table())
        .meaning("the lumped model of a structure of kind \"lumped\"")
        .required()
        .when([](const StructureSpec& s) { return s.kind == Kind::lumped; },
              "only for kind = \"lumped\"", true);
    t.table(
         "matrix", [](StructureSpec & s) -> auto& { return s.matrix; }, matrix_table())
        .meaning("the matrices of a structure of kind \"matrix\"")
        .required()
        .when([](const StructureSpec& s) { return s.kind == Kind::matrix; },
              "only for kind = \"matrix\"", true);
    t.table(
        "damping", [](StructureSpec & s) -> auto& { return s.damping; }, damping_table());
    t.table(
        "excitation", [](StructureSpec & s) -> auto& { return s.excitation; }, excitation_table());
    t.check([](const StructureSpec& s) {
        Violations out = s.validate();
        const Violations base = check_matrix_base(s);
        out.insert(out.end(), base.begin(), base.end());
        return out;
    });
    return t.build();
}

}  // namespace sb::bench::schema

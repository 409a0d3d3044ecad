// Reading the [structure] section of a campaign config.
#include "bench/structure_config.hpp"

#include <map>

namespace sb::bench {
namespace {

using structure::BeamSpec;
using structure::DampingSpec;
using structure::ExcitationSpec;
using structure::LumpedSpec;
using structure::MatrixSpec;
using structure::StructureSpec;
using structure::SupportKind;

SupportKind support_kind(const std::string& text) {
    if (text == "pinned") return SupportKind::pinned;
    if (text == "free") return SupportKind::free;
    if (text == "elastic") return SupportKind::elastic;
    return SupportKind::clamped;
}

BeamSpec read_beam(Section beam) {
    BeamSpec spec;
    spec.length_m = beam.required_number("length_m", "beam length [m]");
    spec.width_m = beam.required_number("width_m", "section side along y, the longer one [m]");
    spec.thickness_m =
        beam.required_number("thickness_m", "section side along z, the shaker direction [m]");
    spec.density_kg_m3 = beam.required_number("density_kg_m3", "beam density [kg/m^3]");
    spec.youngs_modulus_pa = beam.required_number("youngs_modulus_pa", "Young's modulus [Pa]");
    spec.shear_modulus_pa =
        beam.optional_number("shear_modulus_pa", "shear modulus [Pa]; given: Timoshenko beam");
    spec.min_elements = beam.integer("elements", spec.min_elements, "least number of elements");

    Section supports = beam.table("supports", "boundary conditions");
    for (auto& [name, support] : supports.named_tables("a support")) {
        structure::Support s;
        s.name = name;
        s.x_m = support.required_number("x_m", "support position along the beam [m]");
        s.kind = support_kind(support.choice(
            "kind", "clamped", {"clamped", "pinned", "free", "elastic"}, "boundary condition"));
        s.translational_stiffness_n_per_m =
            support.vector3("translational_stiffness_n_per_m", Eigen::Vector3d::Zero(),
                            "elastic support: springs along x, y, z [N/m]");
        s.rotational_stiffness_nm_per_rad =
            support.vector3("rotational_stiffness_nm_per_rad", Eigen::Vector3d::Zero(),
                            "elastic support: springs about x, y, z [N m/rad]");
        if (s.kind != SupportKind::elastic && (support.has("translational_stiffness_n_per_m") ||
                                               support.has("rotational_stiffness_nm_per_rad"))) {
            support.error("kind", "\"" + support.string("kind", "clamped", "") + "\"",
                          "must be \"elastic\" when spring constants are given",
                          "boundary condition");
        }
        support.finish();
        spec.supports.push_back(std::move(s));
    }
    supports.finish();

    Section points = beam.table("points", "named points: name = position along the beam [m]");
    std::map<std::string, double, std::less<>> point_x;
    for (const auto& [name, x] : points.named_numbers("named point position along the beam [m]")) {
        spec.points.push_back({name, x});
        point_x[name] = x;
    }
    points.finish();

    for (Section mass : beam.array_of_tables("masses", "lumped masses")) {
        structure::LumpedMass m;
        m.name = mass.string("name", "", "label of the mass");
        const bool has_point = mass.has("point");
        const bool has_x = mass.has("x_m");
        if (has_point == has_x) {
            mass.error(has_point ? "x_m" : "point", "", "give exactly one of point and x_m",
                       "where the mass is attached");
        }
        if (has_point) {
            const std::string point = mass.string("point", "", "named point the mass sits at");
            const auto it = point_x.find(point);
            if (it == point_x.end()) {
                mass.error("point", "\"" + point + "\"",
                           "must name a point of [structure.beam.points]",
                           "named point the mass sits at");
            } else {
                m.x_m = it->second;
            }
            if (m.name.empty()) {
                m.name = point;
            }
        } else {
            m.x_m = mass.number("x_m", 0.0, "mass position along the beam [m]");
        }
        m.mass_kg = mass.required_number("mass_kg", "mass [kg]");
        m.inertia_kg_m2 =
            mass.vector3("inertia_kg_m2", Eigen::Vector3d::Zero(),
                         "rotary inertia about the mass's own centre, x y z [kg m^2]");
        m.offset_m = mass.vector3("offset_m", Eigen::Vector3d::Zero(),
                                  "centre of gravity offset from the beam axis [m]");
        mass.finish();
        spec.masses.push_back(std::move(m));
    }
    beam.finish();
    return spec;
}

LumpedSpec read_lumped(Section lumped) {
    LumpedSpec spec;
    for (Section mass : lumped.array_of_tables("masses", "point masses")) {
        spec.masses.push_back({mass.required_string("name", "mass name (a named point)"),
                               mass.required_number("mass_kg", "mass [kg]")});
        mass.finish();
    }
    for (Section spring : lumped.array_of_tables("springs", "springs between masses")) {
        LumpedSpec::Spring s;
        s.from = spring.required_string("from", "mass name or \"ground\"");
        s.to = spring.required_string("to", "mass name or \"ground\"");
        s.stiffness_n_per_m = spring.required_number("stiffness_n_per_m", "stiffness [N/m]");
        s.damping_n_s_per_m = spring.number("damping_n_s_per_m", 0.0, "viscous damping [N s/m]");
        spring.finish();
        spec.springs.push_back(std::move(s));
    }
    lumped.finish();
    return spec;
}

MatrixSpec read_matrix(Section matrix, const std::filesystem::path& base_dir) {
    MatrixSpec spec;
    const auto resolve = [&](const std::string& name) {
        const std::filesystem::path p(name);
        return p.is_absolute() || name.empty() ? p : base_dir / p;
    };
    spec.mass_file = resolve(matrix.required_string("mass_file", "Matrix Market mass matrix"));
    spec.stiffness_file =
        resolve(matrix.required_string("stiffness_file", "Matrix Market stiffness matrix"));
    Section dofs = matrix.table("dofs", "named DOFs: name = zero-based row");
    for (const auto& [name, row] : dofs.named_numbers("zero-based row of a named DOF")) {
        if (row < 0 || row != static_cast<double>(static_cast<long>(row))) {
            dofs.error(name, format_value(row), "must be a whole number >= 0",
                       "zero-based row of a named DOF");
            continue;
        }
        spec.named_dofs.emplace_back(name, static_cast<int>(row));
    }
    dofs.finish();
    matrix.finish();
    return spec;
}

DampingSpec read_damping(Section damping) {
    DampingSpec spec;
    const std::string model =
        damping.choice("model", "modal", {"modal", "rayleigh"}, "damping model");
    spec.model = model == "rayleigh" ? DampingSpec::Model::rayleigh : DampingSpec::Model::modal;
    spec.default_ratio =
        damping.number("default_ratio", spec.default_ratio, "ratio of modes not listed [-]");
    spec.modal_ratios = damping.numbers("modal_ratios", "ratios of modes 1, 2, ... [-]");
    spec.alpha_per_s = damping.number("alpha_per_s", 0.0, "Rayleigh mass coefficient [1/s]");
    spec.beta_s = damping.number("beta_s", 0.0, "Rayleigh stiffness coefficient [s]");
    damping.finish();
    return spec;
}

ExcitationSpec read_excitation(Section excitation) {
    ExcitationSpec spec;
    const std::string kind =
        excitation.choice("kind", "force", {"force", "base"}, "how the structure is driven");
    spec.kind = kind == "base" ? ExcitationSpec::Kind::base : ExcitationSpec::Kind::force;
    spec.point = excitation.string("point", "", "force: named point the shaker drives");
    spec.support = excitation.string("support", "", "base: the support that moves");
    spec.direction = excitation.vector3("direction", Eigen::Vector3d::UnitZ(),
                                        "direction of the force or base motion");
    excitation.finish();
    return spec;
}

}  // namespace

StructureSpec read_structure(Section section, const std::filesystem::path& base_dir) {
    StructureSpec spec;
    if (!section.present()) {
        section.error("", "", "is required", "the structure under test");
        return spec;
    }
    const std::string kind =
        section.choice("kind", "beam", {"beam", "lumped", "matrix"}, "kind of structure model");
    spec.kind = kind == "lumped"   ? StructureSpec::Kind::lumped
                : kind == "matrix" ? StructureSpec::Kind::matrix
                                   : StructureSpec::Kind::beam;
    spec.modes = section.integer("modes", spec.modes, "modes kept in the reduced modal model");
    spec.gravity_m_s2 = section.vector3("gravity_m_s2", spec.gravity_m_s2,
                                        "gravity in the structure frame [m/s^2]");

    const std::vector<std::pair<const char*, StructureSpec::Kind>> model_sections{
        {"beam", StructureSpec::Kind::beam},
        {"lumped", StructureSpec::Kind::lumped},
        {"matrix", StructureSpec::Kind::matrix}};
    for (const auto& [name, k] : model_sections) {
        if (k != spec.kind && section.has(name)) {
            section.error(name, "{...}", "does not belong to a structure of kind \"" + kind + "\"",
                          "model section of another kind");
        }
    }
    switch (spec.kind) {
        case StructureSpec::Kind::beam:
            if (!section.has("beam")) {
                section.error("beam", "", "is required",
                              "the beam of a structure of kind \"beam\"");
                return spec;
            }
            spec.beam = read_beam(section.table("beam", "the beam"));
            break;
        case StructureSpec::Kind::lumped:
            spec.lumped = read_lumped(section.table("lumped", "the lumped model"));
            break;
        case StructureSpec::Kind::matrix:
            if (!section.has("matrix")) {
                section.error("matrix", "", "is required",
                              "the matrices of a structure of kind \"matrix\"");
                return spec;
            }
            spec.matrix = read_matrix(section.table("matrix", "imported matrices"), base_dir);
            break;
    }
    spec.damping = read_damping(section.table("damping", "structural damping"));
    spec.excitation = read_excitation(section.table("excitation", "how the structure is driven"));
    section.finish();
    section.report(spec.validate());
    return spec;
}

}  // namespace sb::bench

// Reading the [structure] section of a campaign config.
#include "bench/structure_config.hpp"

#include <cmath>
#include <map>
#include <optional>
#include <string_view>

#include "structure/matrix_market.hpp"

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

/// Size of the Matrix Market file the config names at `key` (already resolved to `file`), or
/// nothing, with the error reported, when it cannot be read: a missing or broken file named
/// by a config is a config error.
std::optional<structure::MatrixMarketSize> matrix_size(Section& matrix, std::string_view key,
                                                       const std::string& written,
                                                       const std::filesystem::path& file,
                                                       std::string_view meaning) {
    if (file.empty()) return std::nullopt;
    try {
        return structure::read_matrix_market_size(file);
    } catch (const structure::MatrixMarketError& e) {
        matrix.error(key, "\"" + written + "\"", std::string("cannot be read: ") + e.what(),
                     std::string(meaning));
    }
    return std::nullopt;
}

std::string shape_text(const structure::MatrixMarketSize& size) {
    return std::to_string(size.rows) + " x " + std::to_string(size.cols);
}

MatrixSpec read_matrix(Section matrix, const std::filesystem::path& base_dir) {
    MatrixSpec spec;
    const auto resolve = [&](const std::string& name) {
        const std::filesystem::path p(name);
        // Absolute, so that the model builder does not prefix a relative config folder again.
        return p.is_absolute() || name.empty() ? p : std::filesystem::absolute(base_dir / p);
    };
    constexpr std::string_view kMassMeaning = "Matrix Market mass matrix";
    constexpr std::string_view kStiffnessMeaning = "Matrix Market stiffness matrix";
    constexpr std::string_view kRigidMeaning =
        "Matrix Market n x 3: DOF values of unit rigid translations along x, y, z";
    const std::string mass_name = matrix.required_string("mass_file", kMassMeaning);
    const std::string stiffness_name = matrix.required_string("stiffness_file", kStiffnessMeaning);
    const std::string rigid_name = matrix.string("rigid_body_file", "", kRigidMeaning);
    spec.mass_file = resolve(mass_name);
    spec.stiffness_file = resolve(stiffness_name);
    spec.rigid_body_file = resolve(rigid_name);
    const auto mass = matrix_size(matrix, "mass_file", mass_name, spec.mass_file, kMassMeaning);
    const auto stiffness = matrix_size(matrix, "stiffness_file", stiffness_name,
                                       spec.stiffness_file, kStiffnessMeaning);
    const auto rigid =
        matrix_size(matrix, "rigid_body_file", rigid_name, spec.rigid_body_file, kRigidMeaning);
    if (mass && mass->rows != mass->cols) {
        matrix.error("mass_file", "\"" + mass_name + "\"",
                     "must hold a square matrix, holds " + shape_text(*mass),
                     std::string(kMassMeaning));
    }
    if (mass && stiffness && (stiffness->rows != mass->rows || stiffness->cols != mass->cols)) {
        matrix.error(
            "stiffness_file", "\"" + stiffness_name + "\"",
            "must hold " + shape_text(*mass) + " like mass_file, holds " + shape_text(*stiffness),
            std::string(kStiffnessMeaning));
    }
    if (mass && rigid && (rigid->rows != mass->rows || rigid->cols != 3)) {
        matrix.error(
            "rigid_body_file", "\"" + rigid_name + "\"",
            "must hold " + std::to_string(mass->rows) + " x 3, holds " + shape_text(*rigid),
            std::string(kRigidMeaning));
    }
    Section dofs = matrix.table("dofs", "named DOFs: name = zero-based row");
    for (const auto& [name, row] : dofs.named_numbers("zero-based row of a named DOF")) {
        constexpr double kLargestRow = 1e9;  // keeps the conversion to int defined
        if (!(row >= 0.0 && row <= kLargestRow && row == std::floor(row))) {
            dofs.error(name, format_value(row), "must be a whole number >= 0",
                       "zero-based row of a named DOF");
            continue;
        }
        if (mass && row >= static_cast<double>(mass->rows)) {
            // Reported here, where the line is known; the DOF is kept so that its point
            // exists and the excitation naming it is not blamed as well.
            dofs.error(name, format_value(row),
                       "must be < " + std::to_string(mass->rows) + ", the rows of mass_file",
                       "zero-based row of a named DOF");
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
    // A missing model section is reported, and everything else of [structure] is still read
    // and checked; only the checks that need the model are left out.
    const char* model_key = kind == "lumped" ? "lumped" : kind == "matrix" ? "matrix" : "beam";
    const bool model_present = section.has(model_key);
    if (!model_present) {
        const char* what = spec.kind == StructureSpec::Kind::beam     ? "the beam"
                           : spec.kind == StructureSpec::Kind::lumped ? "the lumped model"
                                                                      : "the matrices";
        section.error(model_key, "", "is required",
                      std::string(what) + " of a structure of kind \"" + kind + "\"");
    } else {
        switch (spec.kind) {
            case StructureSpec::Kind::beam:
                spec.beam = read_beam(section.table("beam", "the beam"));
                break;
            case StructureSpec::Kind::lumped:
                spec.lumped = read_lumped(section.table("lumped", "the lumped model"));
                break;
            case StructureSpec::Kind::matrix:
                spec.matrix = read_matrix(section.table("matrix", "imported matrices"), base_dir);
                break;
        }
    }
    spec.damping = read_damping(section.table("damping", "structural damping"));
    spec.excitation = read_excitation(section.table("excitation", "how the structure is driven"));
    section.finish();
    Violations violations = spec.validate();
    if (!model_present) {
        // Without the model, its own checks and the names that refer into it mean nothing.
        std::erase_if(violations, [&](const Violation& v) {
            return v.key.starts_with(std::string(model_key) + ".") || v.key == "excitation.point" ||
                   v.key == "excitation.support";
        });
    }
    section.report(violations);
    return spec;
}

}  // namespace sb::bench

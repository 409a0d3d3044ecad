// Validation of the structure description (every violation collected, none thrown).
#include "structure/spec.hpp"

#include <cmath>
#include <set>
#include <string>

namespace sb::structure {
namespace {

void require_at_least(Violations& out, std::string_view key, int value, int lo,
                      std::string_view meaning) {
    if (value < lo) {
        out.push_back({std::string(key), std::to_string(value), "must be >= " + std::to_string(lo),
                       std::string(meaning)});
    }
}

void require_unique(Violations& out, std::set<std::string>& seen, const std::string& key,
                    const std::string& name, std::string_view meaning) {
    if (name.empty()) {
        out.push_back({key, "\"\"", "must not be empty", std::string(meaning)});
    } else if (!seen.insert(name).second) {
        out.push_back({key, name, "must be unique", std::string(meaning)});
    }
}

void require_non_negative_vector(Violations& out, const std::string& key, const Eigen::Vector3d& v,
                                 std::string_view meaning) {
    for (int i = 0; i < 3; ++i) {
        require_non_negative(out, key + "[" + std::to_string(i) + "]", v[i], meaning);
    }
}

}  // namespace

Violations BeamSpec::validate() const {
    Violations out;
    require_positive(out, "length_m", length_m, "beam length [m]");
    require_positive(out, "width_m", width_m, "section side along y [m]");
    require_positive(out, "thickness_m", thickness_m, "section side along z [m]");
    require_positive(out, "density_kg_m3", density_kg_m3, "beam density [kg/m^3]");
    require_positive(out, "youngs_modulus_pa", youngs_modulus_pa, "Young's modulus [Pa]");
    if (shear_modulus_pa) {
        require_positive(out, "shear_modulus_pa", *shear_modulus_pa, "shear modulus [Pa]");
    }
    // The frame puts y along the longer side, so z (thickness) is the weak bending direction
    // the shaker drives; a beam driven in its stiff direction keeps this frame and sets
    // excitation.direction = [0, 1, 0].
    if (std::isfinite(width_m) && std::isfinite(thickness_m) && width_m > 0.0 &&
        thickness_m > width_m) {
        out.push_back({"thickness_m", format_value(thickness_m),
                       "must be <= width_m = " + format_value(width_m),
                       "section side along z, the shorter one; drive the stiff direction with "
                       "excitation.direction = [0, 1, 0]"});
    }
    require_at_least(out, "elements", min_elements, 1, "minimum number of beam elements");
    // Positions are checked against the length only when the length itself is usable;
    // otherwise only their sign, so that one bad length does not condemn every position.
    const bool length_usable = std::isfinite(length_m) && length_m > 0.0;
    const auto require_on_beam = [&](const std::string& key, double x, std::string_view meaning) {
        if (length_usable) {
            require_in_range(out, key, x, 0.0, length_m, meaning);
        } else {
            require_non_negative(out, key, x, meaning);
        }
    };

    if (supports.empty()) {
        out.push_back({"supports", "(none)", "must have at least one support",
                       "boundary conditions of the beam"});
    }
    std::set<std::string> support_names;
    for (const auto& s : supports) {
        const std::string key = "supports." + s.name;
        require_unique(out, support_names, key, s.name, "support name");
        require_on_beam(key + ".x_m", s.x_m, "support position along the beam [m]");
        if (s.kind == SupportKind::elastic) {
            require_non_negative_vector(out, key + ".translational_stiffness_n_per_m",
                                        s.translational_stiffness_n_per_m,
                                        "support translational stiffness [N/m]");
            require_non_negative_vector(out, key + ".rotational_stiffness_nm_per_rad",
                                        s.rotational_stiffness_nm_per_rad,
                                        "support rotational stiffness [N m/rad]");
        }
    }
    std::set<std::string> point_names;
    for (const auto& p : points) {
        const std::string key = "points." + p.name;
        require_unique(out, point_names, key, p.name, "point name");
        require_on_beam(key, p.x_m, "point position along the beam [m]");
    }
    std::set<std::string> mass_names;
    for (std::size_t i = 0; i < masses.size(); ++i) {
        const auto& m = masses[i];
        const std::string key = "masses[" + std::to_string(i) + "]";
        const std::string& label = m.name.empty() ? m.point : m.name;
        if (!label.empty() && !mass_names.insert(label).second) {
            out.push_back({key + ".name", label, "must be unique", "lumped mass name"});
        }
        if (m.point.empty()) {
            require_on_beam(key + ".x_m", m.x_m, "mass position along the beam [m]");
        } else if (!point_names.contains(m.point)) {
            out.push_back({key + ".point", "\"" + m.point + "\"",
                           "must name a point of [structure.beam.points]",
                           "named point the mass sits at"});
        }
        require_positive(out, key + ".mass_kg", m.mass_kg, "lumped mass [kg]");
        require_non_negative_vector(out, key + ".inertia_kg_m2", m.inertia_kg_m2,
                                    "rotary inertia about the mass's centre of gravity [kg m^2]");
        for (int d = 0; d < 3; ++d) {
            if (!std::isfinite(m.offset_m[d])) {
                out.push_back({key + ".offset_m[" + std::to_string(d) + "]",
                               format_value(m.offset_m[d]), "must be finite",
                               "centre of gravity offset from the beam axis [m]"});
            }
        }
    }
    return out;
}

BeamSpec BeamSpec::resolved() const {
    BeamSpec out = *this;
    for (auto& m : out.masses) {
        if (m.point.empty()) continue;
        for (const auto& p : points) {
            if (p.name == m.point) m.x_m = p.x_m;
        }
        if (m.name.empty()) m.name = m.point;
    }
    return out;
}

Violations LumpedSpec::validate() const {
    Violations out;
    if (masses.empty()) {
        out.push_back({"masses", "(none)", "must have at least one mass", "lumped masses"});
    }
    std::set<std::string> names;
    for (std::size_t i = 0; i < masses.size(); ++i) {
        const std::string key = "masses[" + std::to_string(i) + "]";
        if (masses[i].name == "ground") {
            out.push_back(
                {key + ".name", "ground", "must not be \"ground\" (reserved)", "lumped mass name"});
        }
        require_unique(out, names, key + ".name", masses[i].name, "lumped mass name");
        require_positive(out, key + ".mass_kg", masses[i].mass_kg, "lumped mass [kg]");
    }
    for (std::size_t i = 0; i < springs.size(); ++i) {
        const auto& s = springs[i];
        const std::string key = "springs[" + std::to_string(i) + "]";
        for (const auto& [end, field] : {std::pair{s.from, "from"}, std::pair{s.to, "to"}}) {
            if (end != "ground" && !names.contains(end)) {
                out.push_back(
                    {key + "." + field, end, "must name a mass or \"ground\"", "spring end"});
            }
        }
        if (s.from == s.to) {
            out.push_back({key + ".to", s.to, "must differ from 'from'", "spring end"});
        }
        require_positive(out, key + ".stiffness_n_per_m", s.stiffness_n_per_m,
                         "spring stiffness [N/m]");
        require_non_negative(out, key + ".damping_n_s_per_m", s.damping_n_s_per_m,
                             "dashpot coefficient [N s/m]");
    }
    return out;
}

Violations MatrixSpec::validate() const {
    Violations out;
    if (mass_file.empty()) {
        out.push_back({"mass_file", "\"\"", "must name a file", "Matrix Market mass matrix"});
    }
    if (stiffness_file.empty()) {
        out.push_back(
            {"stiffness_file", "\"\"", "must name a file", "Matrix Market stiffness matrix"});
    }
    std::set<std::string> names;
    std::set<std::string> points;
    for (const auto& [name, index] : named_dofs) {
        const std::string key = "named_dofs." + name;
        require_unique(out, names, key, name, "named DOF");
        require_at_least(out, key, index, 0, "zero-based row of the named DOF");
        points.insert(point_of(name));
    }
    for (std::size_t i = 0; i < masses.size(); ++i) {
        const auto& m = masses[i];
        const std::string key = "masses[" + std::to_string(i) + "]";
        if (!points.contains(m.point)) {
            out.push_back({key + ".point", "\"" + m.point + "\"",
                           "must name a point of [structure.matrix.dofs]",
                           "named point the mass is attached to"});
        }
        require_positive(out, key + ".mass_kg", m.mass_kg, "added mass [kg]");
    }
    return out;
}

std::string MatrixSpec::point_of(const std::string& dof) {
    const auto dot = dof.rfind('.');
    if (dot == std::string::npos) return dof;
    const std::string suffix = dof.substr(dot + 1);
    for (const char* c : {"x", "y", "z", "rx", "ry", "rz"}) {
        if (suffix == c) return dof.substr(0, dot);
    }
    return dof;
}

Violations DampingSpec::validate() const {
    Violations out;
    if (model == Model::modal) {
        const auto require_ratio = [&](const std::string& key, double ratio,
                                       const std::string& meaning) {
            if (!(std::isfinite(ratio) && ratio >= 0.0 && ratio < 1.0)) {
                out.push_back({key, format_value(ratio), "must be in [0, 1)", meaning});
            }
        };
        require_ratio("default_ratio", default_ratio, "damping ratio of modes not listed [-]");
        for (std::size_t i = 0; i < modal_ratios.size(); ++i) {
            require_ratio("modal_ratios[" + std::to_string(i) + "]", modal_ratios[i],
                          "damping ratio of mode " + std::to_string(i + 1));
        }
    } else {
        require_non_negative(out, "alpha_per_s", alpha_per_s,
                             "Rayleigh mass-proportional coefficient [1/s]");
        require_non_negative(out, "beta_s", beta_s,
                             "Rayleigh stiffness-proportional coefficient [s]");
    }
    return out;
}

double DampingSpec::ratio(int mode, double omega_rad_s) const {
    if (model == Model::rayleigh) {
        // Rayleigh damping C = alpha M + beta K: zeta = alpha/(2 omega) + beta omega/2
        // (Clough & Penzien, Dynamics of Structures, eq. 12-34).
        return alpha_per_s / (2.0 * omega_rad_s) + 0.5 * beta_s * omega_rad_s;
    }
    if (mode >= 1 && static_cast<std::size_t>(mode) <= modal_ratios.size()) {
        return modal_ratios[static_cast<std::size_t>(mode - 1)];
    }
    return default_ratio;
}

Violations ExcitationSpec::validate() const {
    Violations out;
    if (!(direction.allFinite() && direction.norm() > 0.0)) {
        out.push_back({"direction",
                       format_value(direction.x()) + ", " + format_value(direction.y()) + ", " +
                           format_value(direction.z()),
                       "must be a finite non-zero vector", "excitation direction"});
    }
    if (kind == Kind::force && point.empty()) {
        out.push_back({"point", "\"\"", "must name a point", "where the force acts"});
    }
    return out;
}

Violations StructureSpec::validate() const {
    Violations out;
    std::set<std::string> point_names;
    std::set<std::string> support_names;
    switch (kind) {
        case Kind::beam:
            append_prefixed(out, "beam", beam.validate());
            for (const auto& p : beam.points) point_names.insert(p.name);
            for (const auto& m : beam.resolved().masses) {
                if (!m.name.empty()) point_names.insert(m.name);
            }
            for (const auto& s : beam.supports) {
                point_names.insert(s.name);
                support_names.insert(s.name);
            }
            break;
        case Kind::lumped:
            append_prefixed(out, "lumped", lumped.validate());
            for (const auto& m : lumped.masses) point_names.insert(m.name);
            support_names.insert("ground");
            break;
        case Kind::matrix:
            append_prefixed(out, "matrix", matrix.validate());
            for (const auto& [name, index] : matrix.named_dofs) {
                point_names.insert(MatrixSpec::point_of(name));
            }
            break;
    }
    append_prefixed(out, "damping", damping.validate());
    append_prefixed(out, "excitation", excitation.validate());
    if (excitation.kind == ExcitationSpec::Kind::force && !excitation.point.empty() &&
        !point_names.contains(excitation.point)) {
        out.push_back({"excitation.point", excitation.point, "must name a point of the structure",
                       "where the force acts"});
    }
    const bool base = excitation.kind == ExcitationSpec::Kind::base;
    if (base && kind == Kind::matrix) {
        // An imported model has no supports: its base DOFs were constrained out of the
        // matrices, and the influence vector r says how the free DOFs follow the base.
        if (!excitation.support.empty()) {
            out.push_back({"excitation.support", excitation.support,
                           "must be absent for an imported model (kind = \"matrix\"): "
                           "structure.matrix.base_influence_file or the rigid translation "
                           "gives how it follows the base",
                           "the support that moves"});
        }
    } else if (base && !support_names.contains(excitation.support)) {
        out.push_back({"excitation.support", "\"" + excitation.support + "\"",
                       kind == Kind::lumped ? "must be \"ground\"" : "must name a support",
                       "the support that moves"});
    }
    if (kind == Kind::matrix && !base && !matrix.base_influence_file.empty()) {
        out.push_back({"matrix.base_influence_file", matrix.base_influence_file.string(),
                       "applies only to structure.excitation.kind = \"base\"",
                       "influence vector of the base motion"});
    }
    if (modes < 1) {
        out.push_back({"modes", std::to_string(modes), "must be >= 1",
                       "modes kept in the reduced modal model"});
    }
    if (!gravity_m_s2.allFinite()) {
        out.push_back({"gravity_m_s2", "non-finite", "must be finite", "gravity [m/s^2]"});
    }
    return out;
}

}  // namespace sb::structure

// Assembly of a beam spec into a LinearModel (elements, lumped masses, supports).
#include "structure/beam_model.hpp"

#include <Eigen/Cholesky>
#include <array>
#include <map>
#include <stdexcept>

#include "structure/beam_element.hpp"
#include "structure/beam_mesh.hpp"
#include "structure/rigid_mass.hpp"

namespace sb::structure {
namespace {

constexpr int kNodeDofs = 6;

/// Which of the six node DOFs a support fixes.
std::array<bool, 6> fixed_dofs(SupportKind kind) {
    switch (kind) {
        case SupportKind::clamped:
            return {true, true, true, true, true, true};
        case SupportKind::pinned:
            return {true, true, true, true, false, false};
        case SupportKind::free:
        case SupportKind::elastic:
            break;
    }
    return {false, false, false, false, false, false};
}

}  // namespace

LinearModel build_beam_model(const BeamSpec& spec, const ExcitationSpec& excitation) {
    const BeamSpec beam = spec.resolved();  // masses at named points placed there
    const std::vector<double> nodes = beam_mesh_nodes(beam);
    const int node_count = static_cast<int>(nodes.size());
    const int full = kNodeDofs * node_count;

    BeamElementProperties props;
    props.section = rectangular_section(beam.width_m, beam.thickness_m);
    props.density_kg_m3 = beam.density_kg_m3;
    props.youngs_modulus_pa = beam.youngs_modulus_pa;
    props.timoshenko = beam.shear_modulus_pa.has_value();
    props.shear_modulus_pa = beam.shear_modulus_pa.value_or(beam.youngs_modulus_pa /
                                                            (2.0 * (1.0 + kDefaultPoissonRatio)));

    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(full, full);
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(full, full);
    for (int e = 0; e + 1 < node_count; ++e) {
        const double length =
            nodes[static_cast<std::size_t>(e + 1)] - nodes[static_cast<std::size_t>(e)];
        const int first = kNodeDofs * e;
        k.block<12, 12>(first, first) += beam_element_stiffness(props, length);
        m.block<12, 12>(first, first) += beam_element_mass(props, length);
    }
    for (const auto& lumped : beam.masses) {
        const int first = kNodeDofs * nearest_node(nodes, lumped.x_m);
        m.block<6, 6>(first, first) +=
            rigid_body_mass(lumped.mass_kg, lumped.inertia_kg_m2, lumped.offset_m);
    }

    // Supports: fixed DOFs, and springs to ground for elastic ones.
    std::vector<bool> fixed(static_cast<std::size_t>(full), false);
    for (const auto& s : beam.supports) {
        const int first = kNodeDofs * nearest_node(nodes, s.x_m);
        const auto mask = fixed_dofs(s.kind);
        for (int d = 0; d < kNodeDofs; ++d) {
            if (mask[static_cast<std::size_t>(d)])
                fixed[static_cast<std::size_t>(first + d)] = true;
        }
        if (s.kind == SupportKind::elastic) {
            for (int d = 0; d < 3; ++d) {
                k(first + d, first + d) += s.translational_stiffness_n_per_m[d];
                k(first + 3 + d, first + 3 + d) += s.rotational_stiffness_nm_per_rad[d];
            }
        }
    }
    std::vector<int> free_index(static_cast<std::size_t>(full), -1);
    std::vector<int> free_dofs;
    for (int i = 0; i < full; ++i) {
        if (!fixed[static_cast<std::size_t>(i)]) {
            free_index[static_cast<std::size_t>(i)] = static_cast<int>(free_dofs.size());
            free_dofs.push_back(i);
        }
    }
    const int n = static_cast<int>(free_dofs.size());
    if (n == 0) throw std::invalid_argument("beam: every DOF is fixed");
    Eigen::MatrixXd kff(n, n);
    Eigen::MatrixXd mff(n, n);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            kff(i, j) =
                k(free_dofs[static_cast<std::size_t>(i)], free_dofs[static_cast<std::size_t>(j)]);
            mff(i, j) =
                m(free_dofs[static_cast<std::size_t>(i)], free_dofs[static_cast<std::size_t>(j)]);
        }
    }
    LinearModel model(mff, kff);
    model.set_excitation_direction(excitation.direction);

    // Selection of a node's six DOFs from the free vector (fixed DOFs give zero columns).
    const auto node_op = [&](int node) {
        Eigen::Matrix<double, 6, Eigen::Dynamic> op = Eigen::MatrixXd::Zero(6, n);
        for (int d = 0; d < kNodeDofs; ++d) {
            const int f = free_index[static_cast<std::size_t>(kNodeDofs * node + d)];
            if (f >= 0) op(d, f) = 1.0;
        }
        return op;
    };
    // Node of every point; a later point of the same name replaces an earlier one, as in
    // LinearModel::add_point.
    std::map<std::string, int> point_nodes;
    for (const auto& s : beam.supports) {
        const int node = nearest_node(nodes, s.x_m);
        model.add_point({s.name, node_op(node), {s.x_m, 0.0, 0.0}});
        point_nodes[s.name] = node;
    }
    for (const auto& lumped : beam.masses) {
        if (lumped.name.empty()) continue;
        // Centre of gravity moves with u + theta x r = u - [r]x theta (small rotations).
        const int node = nearest_node(nodes, lumped.x_m);
        Eigen::Matrix<double, 6, Eigen::Dynamic> op = node_op(node);
        op.topRows<3>() -= skew(lumped.offset_m) * op.bottomRows<3>();
        model.add_point({lumped.name, op, Eigen::Vector3d(lumped.x_m, 0.0, 0.0) + lumped.offset_m});
        point_nodes[lumped.name] = node;
    }
    for (const auto& p : beam.points) {
        const int node = nearest_node(nodes, p.x_m);
        model.add_point({p.name, node_op(node), {p.x_m, 0.0, 0.0}});
        point_nodes[p.name] = node;
    }

    // Sample translations: every node, then every lumped mass centre of gravity.
    const int samples = node_count + static_cast<int>(beam.masses.size());
    Eigen::MatrixXd sample = Eigen::MatrixXd::Zero(3 * samples, n);
    for (int node = 0; node < node_count; ++node) {
        sample.middleRows(3 * node, 3) = node_op(node).topRows<3>();
    }
    for (std::size_t i = 0; i < beam.masses.size(); ++i) {
        const auto op = node_op(nearest_node(nodes, beam.masses[i].x_m));
        sample.middleRows(3 * (node_count + static_cast<int>(i)), 3) =
            op.topRows<3>() - skew(beam.masses[i].offset_m) * op.bottomRows<3>();
    }
    model.set_sample_translation(sample);

    Eigen::MatrixXd rigid = Eigen::MatrixXd::Zero(n, 3);
    for (int node = 0; node < node_count; ++node) {
        for (int d = 0; d < 3; ++d) {
            const int f = free_index[static_cast<std::size_t>(kNodeDofs * node + d)];
            if (f >= 0) rigid(f, d) = 1.0;
        }
    }
    model.set_rigid_translation(rigid);

    if (excitation.kind == ExcitationSpec::Kind::base) {
        const Support* moving = nullptr;
        for (const auto& s : beam.supports) {
            if (s.name == excitation.support) moving = &s;
        }
        if (moving == nullptr) {
            throw std::invalid_argument("beam: unknown base support '" + excitation.support + "'");
        }
        if (moving->kind == SupportKind::free) {
            throw std::invalid_argument("beam: base support '" + moving->name +
                                        "' is free and cannot drive the structure");
        }
        // Quasi-static influence: K_ff r = -K_fb u_b + K_spring u_b (Clough & Penzien,
        // Dynamics of Structures, sec. 26-5, multiple-support excitation).
        const Eigen::Vector3d dir = excitation.direction.normalized();
        const int first = kNodeDofs * nearest_node(nodes, moving->x_m);
        Eigen::VectorXd ub = Eigen::VectorXd::Zero(full);
        ub.segment<3>(first) = dir;
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < 3; ++j) {
                if (fixed[static_cast<std::size_t>(first + j)]) {
                    rhs(i) -= k(free_dofs[static_cast<std::size_t>(i)], first + j) * ub(first + j);
                }
            }
        }
        if (moving->kind == SupportKind::elastic) {
            for (int d = 0; d < 3; ++d) {
                const int f = free_index[static_cast<std::size_t>(first + d)];
                if (f >= 0) rhs(f) += moving->translational_stiffness_n_per_m[d] * dir[d];
            }
        }
        const Eigen::LDLT<Eigen::MatrixXd> solver(kff);
        if (solver.info() != Eigen::Success || !(solver.vectorD().array() > 0.0).all()) {
            throw std::invalid_argument(
                "beam: the structure is not held statically, so the "
                "base influence vector is undefined");
        }
        model.set_base_influence(solver.solve(rhs));
        // Points on the moving node also move through its fixed DOFs, which have no column
        // in their operators: add u_b dir on those (a lumped mass there moves rigidly with
        // its node, the prescribed rotations being zero).
        const int moving_node = nearest_node(nodes, moving->x_m);
        Eigen::Matrix<double, 6, 1> prescribed = Eigen::Matrix<double, 6, 1>::Zero();
        for (int d = 0; d < 3; ++d) {
            if (fixed[static_cast<std::size_t>(first + d)]) prescribed(d) = dir(d);
        }
        for (const auto& [name, node] : point_nodes) {
            if (node == moving_node) model.add_prescribed_base_motion(name, prescribed);
        }
    }
    return model;
}

}  // namespace sb::structure

// Chains and networks of point masses with springs and dashpots along the excitation direction.
#include "structure/lumped_model.hpp"

#include <Eigen/Cholesky>
#include <stdexcept>

namespace sb::structure {

LinearModel build_lumped_model(const LumpedSpec& lumped, const ExcitationSpec& excitation) {
    const int n = static_cast<int>(lumped.masses.size());
    const auto index_of = [&](const std::string& name) {
        for (int i = 0; i < n; ++i) {
            if (lumped.masses[static_cast<std::size_t>(i)].name == name) return i;
        }
        return -1;  // ground
    };
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd ground_stiffness = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) m(i, i) = lumped.masses[static_cast<std::size_t>(i)].mass_kg;
    bool any_dashpot = false;
    for (const auto& s : lumped.springs) {
        const int a = index_of(s.from);
        const int b = index_of(s.to);
        // Element matrix k [1 -1; -1 1] between a and b; a ground end drops its row/column.
        const auto add = [&](Eigen::MatrixXd& target, double value) {
            if (a >= 0) target(a, a) += value;
            if (b >= 0) target(b, b) += value;
            if (a >= 0 && b >= 0) {
                target(a, b) -= value;
                target(b, a) -= value;
            }
        };
        add(k, s.stiffness_n_per_m);
        add(c, s.damping_n_s_per_m);
        if (s.damping_n_s_per_m != 0.0) any_dashpot = true;
        if (a < 0 && b >= 0) ground_stiffness(b) += s.stiffness_n_per_m;
        if (b < 0 && a >= 0) ground_stiffness(a) += s.stiffness_n_per_m;
    }
    LinearModel model(m, k);
    if (any_dashpot) model.set_damping(c);
    model.set_excitation_direction(excitation.direction);
    const Eigen::Vector3d dir = model.excitation_direction();

    Eigen::MatrixXd sample = Eigen::MatrixXd::Zero(3 * n, n);
    for (int i = 0; i < n; ++i) {
        PointMap p;
        p.name = lumped.masses[static_cast<std::size_t>(i)].name;
        p.op = Eigen::MatrixXd::Zero(6, n);
        p.op.col(i).head<3>() = dir;
        sample.block(3 * i, i, 3, 1) = dir;
        model.add_point(std::move(p));
    }
    model.set_sample_translation(sample);
    model.set_rigid_translation(Eigen::VectorXd::Ones(n) * dir.transpose());

    if (excitation.kind == ExcitationSpec::Kind::base) {
        const Eigen::LDLT<Eigen::MatrixXd> solver(k);
        if (solver.info() != Eigen::Success || !(solver.vectorD().array() > 0.0).all()) {
            throw std::invalid_argument("lumped: the masses are not held by springs to ground");
        }
        model.set_base_influence(solver.solve(ground_stiffness));
    }
    return model;
}

}  // namespace sb::structure

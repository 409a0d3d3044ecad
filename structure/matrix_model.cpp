// A structure imported as Matrix Market mass and stiffness matrices with named DOFs.
#include "structure/matrix_model.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>

#include "structure/matrix_market.hpp"
#include "structure/rigid_mass.hpp"

namespace sb::structure {

LinearModel build_matrix_model(const MatrixSpec& matrix, const ExcitationSpec& excitation,
                               const std::filesystem::path& base_dir) {
    const auto resolve = [&](const std::filesystem::path& p) {
        return p.is_absolute() ? p : base_dir / p;
    };
    const std::string mass_name = resolve(matrix.mass_file).string();
    Eigen::MatrixXd m = read_matrix_market_dense(resolve(matrix.mass_file));
    Eigen::MatrixXd k = read_matrix_market_dense(resolve(matrix.stiffness_file));
    if (m.rows() != m.cols() || k.rows() != k.cols() || m.rows() != k.rows()) {
        throw std::invalid_argument(mass_name + ": mass " + std::to_string(m.rows()) + "x" +
                                    std::to_string(m.cols()) + " and stiffness " +
                                    std::to_string(k.rows()) + "x" + std::to_string(k.cols()) +
                                    " must be square and equal");
    }
    // The eigensolver needs M symmetric positive definite and K symmetric; an import that is
    // not is bad input, reported here with the file rather than as a solver failure later.
    constexpr double kSymmetryRoundOff = 1e-9;  // relative: files written with ~12 digits
    const auto require_symmetric = [&](const Eigen::MatrixXd& a, const std::filesystem::path& f) {
        if ((a - a.transpose()).cwiseAbs().maxCoeff() >
            kSymmetryRoundOff * a.cwiseAbs().maxCoeff()) {
            throw std::invalid_argument(resolve(f).string() + ": the matrix must be symmetric");
        }
    };
    require_symmetric(m, matrix.mass_file);
    require_symmetric(k, matrix.stiffness_file);
    std::optional<Eigen::MatrixXd> c;
    if (!matrix.damping_file.empty()) {
        c = read_matrix_market_dense(resolve(matrix.damping_file));
        if (c->rows() != m.rows() || c->cols() != m.cols()) {
            throw std::invalid_argument(
                resolve(matrix.damping_file).string() + ": " + std::to_string(c->rows()) + "x" +
                std::to_string(c->cols()) + ", expected " + std::to_string(m.rows()) + "x" +
                std::to_string(m.cols()) + " like the mass matrix");
        }
        require_symmetric(*c, matrix.damping_file);
        // A damping matrix that feeds energy in (a negative eigenvalue beyond round-off) is
        // bad input: the response would grow without bound.
        const Eigen::VectorXd lambda =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(*c, Eigen::EigenvaluesOnly)
                .eigenvalues();
        if (lambda.size() > 0 &&
            lambda.minCoeff() < -kSymmetryRoundOff * lambda.cwiseAbs().maxCoeff()) {
            throw std::invalid_argument(resolve(matrix.damping_file).string() +
                                        ": the damping matrix must be positive semi-definite");
        }
    }
    if (Eigen::LLT<Eigen::MatrixXd>(m).info() != Eigen::Success) {
        throw std::invalid_argument(mass_name + ": the mass matrix must be positive definite");
    }
    const int n = static_cast<int>(m.rows());
    const Eigen::Vector3d dir = excitation.direction.normalized();
    const std::map<std::string, int> components{{"x", 0},  {"y", 1},  {"z", 2},
                                                {"rx", 3}, {"ry", 4}, {"rz", 5}};
    std::map<std::string, Eigen::Matrix<double, 6, Eigen::Dynamic>> ops;
    std::vector<std::string> order;
    Eigen::MatrixXd rigid = Eigen::MatrixXd::Zero(n, 3);
    std::vector<bool> named(static_cast<std::size_t>(n), false);
    for (const auto& [name, row] : matrix.named_dofs) {
        if (row < 0 || row >= n) {
            throw std::invalid_argument("matrix model: DOF '" + name + "' row " +
                                        std::to_string(row) + " outside " + std::to_string(n));
        }
        named[static_cast<std::size_t>(row)] = true;
        const std::string point = MatrixSpec::point_of(name);
        const auto comp =
            point == name ? components.end() : components.find(name.substr(point.size() + 1));
        auto [it, inserted] = ops.try_emplace(point, Eigen::MatrixXd::Zero(6, n));
        if (inserted) order.push_back(point);
        if (comp == components.end()) {
            // A DOF moving along the excitation direction n: a rigid translation e_d moves it
            // by n_d.
            it->second.col(row).head<3>() += dir;
            rigid.row(row) = dir.transpose();
        } else {
            it->second(comp->second, row) = 1.0;
            if (comp->second < 3) rigid(row, comp->second) = 1.0;  // rotations stay 0
        }
    }
    bool rigid_known = true;
    if (!matrix.rigid_body_file.empty()) {
        Eigen::MatrixXd given = read_matrix_market_dense(resolve(matrix.rigid_body_file));
        if (given.rows() != n || given.cols() != 3) {
            throw std::invalid_argument(resolve(matrix.rigid_body_file).string() + ": " +
                                        std::to_string(given.rows()) + "x" +
                                        std::to_string(given.cols()) + ", expected " +
                                        std::to_string(n) + "x3 (rigid translations x, y, z)");
        }
        rigid = std::move(given);
    } else {
        // Unnamed rows may be translations or rotations: their share is unknown.
        rigid_known = std::all_of(named.begin(), named.end(), [](bool b) { return b; });
    }

    // Added masses: a rigid body of 6 x 6 mass B at a point whose motion is op x adds
    // op^T B op (kinetic energy 1/2 x'^T op^T B op x'). Without rotation DOFs only the m I
    // block survives: m on each translation DOF of the point (m n n^T = m for a DOF moving
    // along n). Its share of a rigid translation e_d is then op r_d, which must be the
    // point's own motion op op^T [e_d; 0] for its effective masses to add up to m.
    for (const auto& added : matrix.masses) {
        const std::string label = added.name.empty() ? added.point : added.name;
        const auto op = ops.find(added.point);
        if (op == ops.end()) {
            throw std::invalid_argument("matrix model: mass '" + label + "' at unknown point '" +
                                        added.point + "'");
        }
        const Eigen::Matrix<double, 6, 6> body =
            rigid_body_mass(added.mass_kg, added.inertia_kg_m2, added.offset_m);
        m += op->second.transpose() * body * op->second;
        if (!rigid_known) continue;
        for (int d = 0; d < 3; ++d) {
            Eigen::Matrix<double, 6, 1> unit = Eigen::Matrix<double, 6, 1>::Zero();
            unit(d) = 1.0;
            const Eigen::Matrix<double, 6, 1> own = op->second * (op->second.transpose() * unit);
            if ((op->second * rigid.col(d) - own).norm() > 1e-9) {
                const std::string source = matrix.rigid_body_file.empty()
                                               ? std::string("structure.matrix.dofs")
                                               : resolve(matrix.rigid_body_file).string();
                throw std::invalid_argument(
                    source + ": the rigid translation along " +
                    std::string(1, static_cast<char>('x' + d)) + " does not move point '" +
                    added.point + "' by 1 along its DOFs, so the mass added there (" + label +
                    ") would not count fully in the effective masses");
            }
        }
    }

    LinearModel model(m, k);
    if (c) model.set_damping(std::move(*c));
    model.set_excitation_direction(dir);
    Eigen::MatrixXd sample(3 * static_cast<int>(order.size()), n);
    for (std::size_t i = 0; i < order.size(); ++i) {
        sample.middleRows(3 * static_cast<int>(i), 3) = ops[order[i]].topRows<3>();
        model.add_point({order[i], ops[order[i]], Eigen::Vector3d::Zero()});
    }
    model.set_sample_translation(sample);
    model.set_rigid_translation(rigid, rigid_known);

    if (excitation.kind == ExcitationSpec::Kind::base) {
        // The base DOFs were constrained out of the matrices. With y = x - r u_b relative to
        // the quasi-static motion r u_b, M y'' + C y' + K y = -M r a_b: r = -K_ff^-1 K_fb u_b
        // for a unit base motion, which for a base moving as one rigid body is the free DOFs'
        // rigid translation along the direction, R n (K_full [R n; n_b] = 0). A base of
        // several parts moving differently needs r from a file.
        Eigen::VectorXd r;
        if (!matrix.base_influence_file.empty()) {
            const std::string file = resolve(matrix.base_influence_file).string();
            Eigen::MatrixXd given = read_matrix_market_dense(resolve(matrix.base_influence_file));
            if (given.rows() != n || given.cols() != 1) {
                throw std::invalid_argument(
                    file + ": " + std::to_string(given.rows()) + "x" +
                    std::to_string(given.cols()) + ", expected " + std::to_string(n) +
                    "x1 (structure.matrix.base_influence_file: each DOF's displacement per unit "
                    "base displacement)");
            }
            r = given.col(0);
        } else if (rigid_known) {
            r = rigid * dir;
        } else {
            throw std::invalid_argument(
                "structure.matrix.base_influence_file is required for base excitation: rows of " +
                mass_name +
                " are not all named and there is no rigid_body_file, so the rigid translation "
                "along the excitation direction is unknown");
        }
        model.set_base_influence(std::move(r));
    }
    return model;
}

}  // namespace sb::structure

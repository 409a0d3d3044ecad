// A structure imported as Matrix Market mass and stiffness matrices with named DOFs.
#include "structure/matrix_model.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <map>
#include <stdexcept>

#include "structure/matrix_market.hpp"

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
    if (Eigen::LLT<Eigen::MatrixXd>(m).info() != Eigen::Success) {
        throw std::invalid_argument(mass_name + ": the mass matrix must be positive definite");
    }
    if (excitation.kind == ExcitationSpec::Kind::base) {
        throw std::invalid_argument("matrix model: base excitation is not supported");
    }
    const int n = static_cast<int>(m.rows());
    LinearModel model(m, k);
    model.set_excitation_direction(excitation.direction);
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
        const auto dot = name.rfind('.');
        const std::string suffix = dot == std::string::npos ? "" : name.substr(dot + 1);
        const auto comp = components.find(suffix);
        const std::string point = comp == components.end() ? name : name.substr(0, dot);
        auto [it, inserted] = ops.try_emplace(point, Eigen::MatrixXd::Zero(6, n));
        if (inserted) order.push_back(point);
        if (comp == components.end()) {
            // A DOF moving along the excitation direction n: a rigid translation e_d moves it
            // by n_d.
            it->second.col(row).head<3>() += model.excitation_direction();
            rigid.row(row) = model.excitation_direction().transpose();
        } else {
            it->second(comp->second, row) = 1.0;
            if (comp->second < 3) rigid(row, comp->second) = 1.0;  // rotations stay 0
        }
    }
    Eigen::MatrixXd sample(3 * static_cast<int>(order.size()), n);
    for (std::size_t i = 0; i < order.size(); ++i) {
        sample.middleRows(3 * static_cast<int>(i), 3) = ops[order[i]].topRows<3>();
        model.add_point({order[i], ops[order[i]], Eigen::Vector3d::Zero()});
    }
    model.set_sample_translation(sample);
    if (!matrix.rigid_body_file.empty()) {
        Eigen::MatrixXd given = read_matrix_market_dense(resolve(matrix.rigid_body_file));
        if (given.rows() != n || given.cols() != 3) {
            throw std::invalid_argument(resolve(matrix.rigid_body_file).string() + ": " +
                                        std::to_string(given.rows()) + "x" +
                                        std::to_string(given.cols()) + ", expected " +
                                        std::to_string(n) + "x3 (rigid translations x, y, z)");
        }
        model.set_rigid_translation(std::move(given));
    } else {
        // Unnamed rows may be translations or rotations: their share is unknown.
        const bool every_row_named =
            std::all_of(named.begin(), named.end(), [](bool b) { return b; });
        model.set_rigid_translation(rigid, every_row_named);
    }
    return model;
}

}  // namespace sb::structure

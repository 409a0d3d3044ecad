// A structure imported as Matrix Market mass and stiffness matrices with named DOFs.
#include "structure/matrix_model.hpp"

#include <map>
#include <stdexcept>

#include "structure/matrix_market.hpp"

namespace sb::structure {

LinearModel build_matrix_model(const MatrixSpec& matrix, const ExcitationSpec& excitation,
                               const std::filesystem::path& base_dir) {
    const auto resolve = [&](const std::filesystem::path& p) {
        return p.is_absolute() ? p : base_dir / p;
    };
    Eigen::MatrixXd m = read_matrix_market_dense(resolve(matrix.mass_file));
    Eigen::MatrixXd k = read_matrix_market_dense(resolve(matrix.stiffness_file));
    if (m.rows() != m.cols() || k.rows() != k.cols() || m.rows() != k.rows()) {
        throw std::runtime_error(resolve(matrix.mass_file).string() + ": mass " +
                                 std::to_string(m.rows()) + "x" + std::to_string(m.cols()) +
                                 " and stiffness " + std::to_string(k.rows()) + "x" +
                                 std::to_string(k.cols()) + " must be square and equal");
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
    for (const auto& [name, row] : matrix.named_dofs) {
        if (row >= n) {
            throw std::invalid_argument("matrix model: DOF '" + name + "' row " +
                                        std::to_string(row) + " outside " + std::to_string(n));
        }
        const auto dot = name.rfind('.');
        const std::string suffix = dot == std::string::npos ? "" : name.substr(dot + 1);
        const auto comp = components.find(suffix);
        const std::string point = comp == components.end() ? name : name.substr(0, dot);
        auto [it, inserted] = ops.try_emplace(point, Eigen::MatrixXd::Zero(6, n));
        if (inserted) order.push_back(point);
        if (comp == components.end()) {
            it->second.col(row).head<3>() += model.excitation_direction();
        } else {
            it->second(comp->second, row) = 1.0;
            if (comp->second < 3) rigid(row, comp->second) = 1.0;
        }
    }
    Eigen::MatrixXd sample(3 * static_cast<int>(order.size()), n);
    for (std::size_t i = 0; i < order.size(); ++i) {
        sample.middleRows(3 * static_cast<int>(i), 3) = ops[order[i]].topRows<3>();
        model.add_point({order[i], ops[order[i]], Eigen::Vector3d::Zero()});
    }
    model.set_sample_translation(sample);
    model.set_rigid_translation(rigid);
    return model;
}

}  // namespace sb::structure

// An assembled linear structure on its free DOFs, and the factory that dispatches on the kind.
#include "structure/linear_model.hpp"

#include <stdexcept>

#include "structure/beam_model.hpp"
#include "structure/lumped_model.hpp"
#include "structure/matrix_model.hpp"

namespace sb::structure {

LinearModel::LinearModel(Eigen::MatrixXd mass, Eigen::MatrixXd stiffness)
    : mass_(std::move(mass)), stiffness_(std::move(stiffness)) {
    if (mass_.rows() != mass_.cols() || stiffness_.rows() != stiffness_.cols() ||
        mass_.rows() != stiffness_.rows()) {
        throw std::invalid_argument("LinearModel: mass and stiffness must be square, same size");
    }
    rigid_translation_ = Eigen::MatrixXd::Zero(mass_.rows(), 3);
    sample_translation_ = Eigen::MatrixXd::Zero(0, mass_.rows());
}

const PointMap& LinearModel::point(std::string_view name) const {
    for (const auto& p : points_) {
        if (p.name == name) return p;
    }
    throw std::out_of_range("unknown point '" + std::string(name) + "'");
}

bool LinearModel::has_point(std::string_view name) const {
    for (const auto& p : points_) {
        if (p.name == name) return true;
    }
    return false;
}

std::vector<std::string> LinearModel::point_names() const {
    std::vector<std::string> names;
    names.reserve(points_.size());
    for (const auto& p : points_) names.push_back(p.name);
    return names;
}

Eigen::VectorXd LinearModel::point_load(std::string_view name, const Eigen::Vector3d& force_n,
                                        const Eigen::Vector3d& moment_nm) const {
    Eigen::Matrix<double, 6, 1> load;
    load << force_n, moment_nm;
    // Virtual work: f^T delta x = [F; M]^T op delta x, so the generalised load is op^T [F; M].
    return point(name).op.transpose() * load;
}

void LinearModel::set_base_influence(Eigen::VectorXd r) {
    base_influence_ = std::move(r);
    for (auto& p : points_) p.base_motion = p.op * *base_influence_;
}

void LinearModel::add_prescribed_base_motion(std::string_view point,
                                             const Eigen::Matrix<double, 6, 1>& m) {
    for (auto& p : points_) {
        if (p.name == point) {
            p.base_motion += m;
            return;
        }
    }
    throw std::out_of_range("unknown point '" + std::string(point) + "'");
}

void LinearModel::add_rigid_body(std::string_view name, const Eigen::Matrix<double, 6, 6>& body) {
    const auto& op = point(name).op;
    mass_ += op.transpose() * body * op;
}

void LinearModel::add_point(PointMap point) {
    for (auto& p : points_) {
        if (p.name == point.name) {
            p = std::move(point);
            return;
        }
    }
    points_.push_back(std::move(point));
}

LinearModel build_linear_model(const StructureSpec& spec, const std::filesystem::path& base_dir) {
    const Violations violations = spec.validate();
    if (!violations.empty()) {
        const auto& v = violations.front();
        throw std::invalid_argument("invalid structure spec: " + v.key + " = " + v.value + " " +
                                    v.constraint + " (" + v.meaning + ")");
    }
    switch (spec.kind) {
        case StructureSpec::Kind::beam:
            return build_beam_model(spec.beam, spec.excitation);
        case StructureSpec::Kind::lumped:
            return build_lumped_model(spec.lumped, spec.excitation);
        case StructureSpec::Kind::matrix:
            return build_matrix_model(spec.matrix, spec.excitation, base_dir);
    }
    throw std::invalid_argument("unknown structure kind");
}

}  // namespace sb::structure

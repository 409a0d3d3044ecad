// An assembled linear structure on its free DOFs: mass, stiffness, damping and named points.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "structure/spec.hpp"

namespace sb::structure {

/// Kinematics of a named point as a linear map of the free-DOF vector.
struct PointMap {
    std::string name;
    /// 6 x n operator: rows 0-2 translation x, y, z [m per DOF unit], rows 3-5 rotation about
    /// x, y, z [rad per DOF unit], structure frame.
    Eigen::Matrix<double, 6, Eigen::Dynamic> op;
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< undeformed position [m]
    /// Base excitation only: quasi-static motion of the point per unit base displacement
    /// along the excitation direction [m/m, rad/m]: op r, plus the prescribed motion of the
    /// point's fixed DOFs when it sits on the moving support (which op cannot see).
    Eigen::Matrix<double, 6, 1> base_motion = Eigen::Matrix<double, 6, 1>::Zero();
};

/// Linear structure M x'' + C x' + K x = f on the free (unconstrained) DOFs.
class LinearModel {
  public:
    LinearModel() = default;
    LinearModel(Eigen::MatrixXd mass, Eigen::MatrixXd stiffness);

    /// Number of free DOFs.
    [[nodiscard]] int dofs() const { return static_cast<int>(mass_.rows()); }
    /// Mass matrix on the free DOFs [kg, kg m, kg m^2].
    [[nodiscard]] const Eigen::MatrixXd& mass() const { return mass_; }
    /// Stiffness matrix on the free DOFs [N/m, N, N m].
    [[nodiscard]] const Eigen::MatrixXd& stiffness() const { return stiffness_; }
    /// Physical damping matrix [N s/m, ...] if the model has one (lumped dashpots).
    [[nodiscard]] const std::optional<Eigen::MatrixXd>& damping() const { return damping_; }

    /// The named point; throws std::out_of_range("unknown point 'x'").
    [[nodiscard]] const PointMap& point(std::string_view name) const;
    [[nodiscard]] bool has_point(std::string_view name) const;
    /// Names of all points, in definition order.
    [[nodiscard]] std::vector<std::string> point_names() const;
    /// Generalised load op^T [F; M] of a force [N] and moment [N m] at a named point.
    [[nodiscard]] Eigen::VectorXd point_load(std::string_view name, const Eigen::Vector3d& force_n,
                                             const Eigen::Vector3d& moment_nm) const;

    /// n x 3 rigid-body translation vectors: column d holds the free-DOF values of a unit
    /// rigid translation along axis d (used for effective masses).
    [[nodiscard]] const Eigen::MatrixXd& rigid_translation() const { return rigid_translation_; }
    /// False when the model cannot know every DOF's share of a rigid translation (a matrix
    /// import with unnamed rows and no rigid-body file): effective masses are then unknown.
    [[nodiscard]] bool rigid_translation_known() const { return rigid_translation_known_; }
    /// 3k x n map from free DOFs to the translations of k sample locations (all nodes, masses
    /// and points): rows 3j..3j+2 are x, y, z of location j (used to scale mode shapes).
    [[nodiscard]] const Eigen::MatrixXd& sample_translation() const { return sample_translation_; }
    /// Quasi-static influence vector r [m/m]: free-DOF displacement for a unit displacement of
    /// the moving base along the excitation direction (absent unless excitation is "base").
    [[nodiscard]] const std::optional<Eigen::VectorXd>& base_influence() const {
        return base_influence_;
    }
    /// Unit excitation direction in the structure frame.
    [[nodiscard]] const Eigen::Vector3d& excitation_direction() const { return direction_; }

    // Set-up, used by the model builders.
    void set_damping(Eigen::MatrixXd damping) { damping_ = std::move(damping); }
    void add_point(PointMap point);
    void set_rigid_translation(Eigen::MatrixXd r, bool known = true) {
        rigid_translation_ = std::move(r);
        rigid_translation_known_ = known;
    }
    void set_sample_translation(Eigen::MatrixXd t) { sample_translation_ = std::move(t); }
    /// Sets r and every point's base_motion to op r.
    void set_base_influence(Eigen::VectorXd r);
    /// Adds the prescribed motion of fixed DOFs to a point's base_motion (after
    /// set_base_influence).
    void add_prescribed_base_motion(std::string_view point, const Eigen::Matrix<double, 6, 1>& m);
    void set_excitation_direction(const Eigen::Vector3d& d) { direction_ = d.normalized(); }
    /// Adds a rigid body of 6 x 6 mass `body` (structure/rigid_mass.hpp) moving with a named
    /// point: op^T body op, from its kinetic energy 1/2 x'^T op^T body op x'.
    void add_rigid_body(std::string_view point, const Eigen::Matrix<double, 6, 6>& body);

  private:
    Eigen::MatrixXd mass_;
    Eigen::MatrixXd stiffness_;
    std::optional<Eigen::MatrixXd> damping_;
    std::vector<PointMap> points_;
    Eigen::MatrixXd rigid_translation_;
    bool rigid_translation_known_ = true;
    Eigen::MatrixXd sample_translation_;
    std::optional<Eigen::VectorXd> base_influence_;
    Eigen::Vector3d direction_ = Eigen::Vector3d::UnitZ();
};

/// Builds the model a spec describes (beam, lumped or matrix). base_dir resolves relative
/// matrix file paths. The spec must be valid (validate() empty); throws std::invalid_argument
/// otherwise, std::runtime_error on unreadable matrix files.
LinearModel build_linear_model(const StructureSpec& spec, const std::filesystem::path& base_dir);

}  // namespace sb::structure

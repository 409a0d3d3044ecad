// Implicit Newmark (average acceleration) integration of the full finite element model.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <string_view>

#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"
#include "structure/spec.hpp"

namespace sb::structure {

/// Damping matrix of a model: the model's physical one if it has one; Rayleigh alpha M +
/// beta K; or modal C = M Phi diag(2 zeta_r w_r) Phi^T M over the modes of the mass-normalised
/// basis (Clough & Penzien, Dynamics of Structures, eq. 12-42); modes outside it are undamped.
Eigen::MatrixXd damping_matrix(const LinearModel& model, const ModalBasis& basis,
                               const DampingSpec& damping);

/// M x'' + C x' + K x = f on all free DOFs, Newmark beta = 1/4, gamma = 1/2 (trapezoidal:
/// unconditionally stable, no numerical damping, period error ~ (w dt)^2 / 12; Newmark, ASCE
/// J. Eng. Mech. 85 (1959) 67). A reference for the reduced model; same load and output
/// conventions as ReducedModalModel (loads are end-of-step values, relative coordinates under
/// base excitation, outputs add P r u_b).
class NewmarkIntegrator {
  public:
    NewmarkIntegrator(const LinearModel& model, const ModalBasis& basis, const DampingSpec& damping,
                      double dt_s);

    [[nodiscard]] double dt_s() const { return dt_; }
    [[nodiscard]] double time_s() const { return time_; }

    /// Removes every point load and the base acceleration.
    void clear_loads();
    /// Force [N] and moment [N m] at a named point (replaces that point's previous load).
    void set_point_load(std::string_view point, const Eigen::Vector3d& force_n,
                        const Eigen::Vector3d& moment_nm);
    /// Base acceleration along the excitation direction [m/s^2] (relative outputs for
    /// displacement and velocity, absolute acceleration).
    void set_base_acceleration(double acceleration_m_s2);
    /// Base displacement [m], velocity [m/s] and acceleration [m/s^2]: every output absolute.
    void set_base_motion(double displacement_m, double velocity_m_s, double acceleration_m_s2);
    void step();

    /// Outputs at a named point; under base excitation they add PointMap::base_motion times
    /// the base motion set (as ReducedModalModel does).
    [[nodiscard]] Eigen::Vector3d displacement(std::string_view point) const;
    [[nodiscard]] Eigen::Vector3d velocity(std::string_view point) const;
    [[nodiscard]] Eigen::Vector3d acceleration(std::string_view point) const;
    [[nodiscard]] Eigen::Vector3d rotation(std::string_view point) const;
    [[nodiscard]] Eigen::Vector3d angular_velocity(std::string_view point) const;

    /// Steady state of the continuous system under F sin(2 pi f t) along `direction` at a
    /// point, at time_s; sets that point load to its value at time_s.
    void set_harmonic_steady_state(std::string_view point, const Eigen::Vector3d& direction,
                                   double force_amplitude_n, double frequency_hz, double time_s);

    /// Full state [m, m/s, m/s^2] on the free DOFs.
    [[nodiscard]] const Eigen::VectorXd& x() const { return x_; }

  private:
    [[nodiscard]] Eigen::VectorXd current_load() const;
    /// PointMap::base_motion: 6 motions per unit base displacement (zero without a base).
    [[nodiscard]] Eigen::Matrix<double, 6, 1> base_motion_of(std::string_view point) const;

    const LinearModel* model_;
    double dt_;
    double time_ = 0.0;
    Eigen::MatrixXd c_;
    Eigen::LDLT<Eigen::MatrixXd> effective_;
    Eigen::VectorXd point_load_sum_;
    std::vector<std::pair<std::string, Eigen::VectorXd>> point_loads_;
    double base_displacement_ = 0.0;
    double base_velocity_ = 0.0;
    double base_acceleration_ = 0.0;
    Eigen::VectorXd x_, v_, a_;
};

}  // namespace sb::structure

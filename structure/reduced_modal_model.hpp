// Time stepping of the first modes with an exact discretisation, O(modes) per step.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <string_view>
#include <vector>

#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"
#include "structure/modal_oscillator.hpp"

namespace sb::structure {

/// Modal coordinates q of x = Phi q (relative to the moving base under base excitation), each
/// obeying q'' + 2 zeta w q' + w^2 q = phi^T f, stepped exactly for loads varying linearly over
/// a step (modal_oscillator.hpp): unconditionally stable, exact at any dt for such loads.
///
/// Loads: whatever is set (point loads, base acceleration) is the load at the END of the next
/// step; the load at its start is the previous step's end load, and the step interpolates
/// linearly between them. Loads persist until changed or cleared.
///
/// Outputs at named points (structure frame): with base excitation, they add the quasi-static
/// base motion (PointMap::base_motion: P r u_b, and u_b itself on a point of the moving
/// support); the acceleration is absolute whenever the base
/// acceleration is set, displacement and velocity only if set_base_motion() supplied them.
class ReducedModalModel {
  public:
    /// Uses the first `modes` modes of the basis (all if modes < 0); dt_s [s] > 0.
    ReducedModalModel(const LinearModel& model, const ModalBasis& basis, double dt_s,
                      int modes = -1);

    [[nodiscard]] int modes() const { return static_cast<int>(omega_.size()); }
    [[nodiscard]] double dt_s() const { return dt_; }
    [[nodiscard]] double time_s() const { return time_; }

    /// Index of a named point for the fast overloads; throws std::out_of_range if unknown.
    [[nodiscard]] int point_index(std::string_view name) const;

    /// Removes every point load and the base acceleration.
    void clear_loads();
    /// Force [N] and moment [N m] at a named point (replaces that point's previous load).
    void set_point_load(std::string_view point, const Eigen::Vector3d& force_n,
                        const Eigen::Vector3d& moment_nm);
    void set_point_load(int point, const Eigen::Vector3d& force_n,
                        const Eigen::Vector3d& moment_nm);
    /// Base acceleration along the excitation direction [m/s^2]: modal load -phi^T M r a_b.
    void set_base_acceleration(double acceleration_m_s2);
    /// Base displacement [m], velocity [m/s] and acceleration [m/s^2] (absolute outputs).
    void set_base_motion(double displacement_m, double velocity_m_s, double acceleration_m_s2);

    /// Advances by dt.
    void step();

    /// Translation [m] of a named point.
    [[nodiscard]] Eigen::Vector3d displacement(std::string_view point) const;
    [[nodiscard]] Eigen::Vector3d displacement(int point) const;
    /// Velocity [m/s].
    [[nodiscard]] Eigen::Vector3d velocity(std::string_view point) const;
    [[nodiscard]] Eigen::Vector3d velocity(int point) const;
    /// Acceleration [m/s^2], from the equation of motion at the current time.
    [[nodiscard]] Eigen::Vector3d acceleration(std::string_view point) const;
    [[nodiscard]] Eigen::Vector3d acceleration(int point) const;
    /// Small rotation vector [rad].
    [[nodiscard]] Eigen::Vector3d rotation(std::string_view point) const;
    [[nodiscard]] Eigen::Vector3d rotation(int point) const;
    /// Angular velocity [rad/s].
    [[nodiscard]] Eigen::Vector3d angular_velocity(std::string_view point) const;
    [[nodiscard]] Eigen::Vector3d angular_velocity(int point) const;
    /// Angular acceleration [rad/s^2].
    [[nodiscard]] Eigen::Vector3d angular_acceleration(int point) const;

    /// Linear steady state under the force F sin(2 pi f t) along `direction` (normalised) at a
    /// point, evaluated at time_s; also sets that point load to its value at time_s, so the
    /// caller continues by setting F sin(2 pi f (t + dt)) before each step.
    void set_harmonic_steady_state(std::string_view point, const Eigen::Vector3d& direction,
                                   double force_amplitude_n, double frequency_hz, double time_s);
    /// Linear steady state under the base acceleration A sin(2 pi f t) [m/s^2]; sets the base
    /// motion (displacement, velocity, acceleration) to its value at time_s.
    void set_harmonic_base_steady_state(double acceleration_amplitude_m_s2, double frequency_hz,
                                        double time_s);
    /// General form: steady state of the modal load Re(f_hat e^{i w t}) at time_s; the load at
    /// the start of the next step is set to that value (point loads are left unchanged).
    void set_steady_state(const Eigen::VectorXcd& modal_load_phasor, double omega_rad_s,
                          double time_s);

    /// Modal state (for checkpoints and warm starts).
    [[nodiscard]] const Eigen::VectorXd& q() const { return q_; }
    [[nodiscard]] const Eigen::VectorXd& q_dot() const { return qd_; }
    /// Sets the modal state at time_s; the start-of-step load becomes the current load.
    void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot, double time_s);

  private:
    /// Writes the modal load of the loads set now into `out` (sized modes()); no allocation,
    /// since step() runs at the DEM time step.
    void modal_load_into(Eigen::VectorXd& out) const;
    void update_acceleration();

    double dt_;
    double time_ = 0.0;
    Eigen::VectorXd omega_;
    Eigen::VectorXd zeta_;
    std::vector<OscillatorStep> steps_;
    Eigen::VectorXd participation_;  ///< phi^T M r per mode (base excitation), else zeros
    std::vector<std::string> names_;
    std::vector<Eigen::Matrix<double, 6, Eigen::Dynamic>> rows_;  ///< op * Phi per point
    std::vector<Eigen::Matrix<double, 6, 1>> base_rows_;          ///< base_motion per point
    std::vector<Eigen::Matrix<double, 6, 1>> point_loads_;
    std::vector<bool> loaded_;
    double base_displacement_ = 0.0;
    double base_velocity_ = 0.0;
    double base_acceleration_ = 0.0;
    Eigen::VectorXd load_start_;  ///< modal load at the start of the next step
    Eigen::VectorXd load_end_;    ///< work vector of step(): modal load at the end of the step
    Eigen::VectorXd q_, qd_, qdd_;
};

}  // namespace sb::structure

// A joint's microslip and macroslip as a discrete Iwan element (physics.iwan_joint;
// bench/physics_attachments.hpp): parallel Jenkins elements (a spring in series with a Coulomb
// slider) whose slip displacements follow Segalman's power-law density.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "bench/attachment_types.hpp"
#include "bench/describing_function.hpp"

namespace sb::bench {

/// A joint the linear model holds stuck, with the stiffness K_T, along a direction d at its
/// point. Its Jenkins elements i (stiffness k_i, slip displacement phi_i, slider at p_i) carry
/// k_i (u - p_i) together; stuck they are the K_T u the model already has, so the element adds
/// only what slip takes away: F = sum_i k_i p_i along d (zero until the first slider moves).
///
/// The slip displacements follow Segalman's density rho(phi) = R phi^chi on (0, phi_max]
/// (Segalman 2005, the four-parameter model with beta = 0): K_T = int rho, the slip force
/// F_S = int phi rho = K_T phi_max (1 + chi) / (2 + chi). Below macroslip the dissipation per
/// cycle grows like the amplitude^(3 + chi), the damping ratio like amplitude^(1 + chi), and the
/// stiffness falls with it: the slight softening a power-law dashpot lacks. The density is
/// cut into `elements` bins, geometric from 1e-4 phi_max up (the microslip regime resolved
/// over four decades of amplitude) plus one bin below; each bin's element carries the bin's
/// share of K_T at the bin's mean slip displacement, so that K_T and F_S are exact. The
/// describing function's error falls as 1/elements^2: 96 elements are within 0.6 % of 8000
/// from 1e-3 to 3 phi_max for chi in [-0.8, 0] (tests/bench/iwan_joint_test.cpp).
class IwanJoint {
  public:
    IwanJoint(const Eigen::Vector3d& direction, double stiffness_n_per_m,
              double macroslip_displacement_m, double exponent, int elements,
              const Eigen::Vector3d& rest_position_m);

    /// Moves each slider that the point's displacement at the step's end, u = d . (x - x_rest
    /// + v dt), drags beyond its slip displacement and returns the load sum_i k_i p_i along d
    /// (the load the specimen applies at the step's end).
    PointLoad step(const PointMotion& motion, double dt_s);
    [[nodiscard]] PointLoad weight() const { return {}; }
    /// The sliders' positions.
    [[nodiscard]] AttachmentState state() const;
    [[nodiscard]] AttachmentState state_at(const PointMotion&) const { return state(); }
    /// Continues from `state`'s sliders (as many as this joint's elements; throws
    /// std::invalid_argument otherwise, or for a state of another model).
    void restore(const AttachmentState& state);
    void restore_at(const AttachmentState& state, const PointMotion&) { restore(state); }
    void set_frequency(double) {}

    /// Its describing function along d at the peak acceleration |a1| [m/s^2] and frequency
    /// [Hz], from the steady hysteresis loop of each Jenkins element at the displacement
    /// amplitude U = |a1| / w^2 (closed form below): the complex stiffness K*(U) = sum_i K_i*,
    /// the element's load (K_T - K*) U, so M = (K_T - K*) / w^2: a positive real part (the
    /// softening) and a negative imaginary one (the dissipation, pi U^2 Im K* per cycle).
    /// |Q3| / |Q1| from the loops' third harmonics; no even harmonic.
    [[nodiscard]] DescribingFunction::Value describing(double acceleration_m_s2,
                                                       double frequency_hz) const;

    /// The elements' stiffnesses k_i [N/m] and slip displacements phi_i [m].
    [[nodiscard]] const std::vector<double>& stiffnesses() const { return stiffness_; }
    [[nodiscard]] const std::vector<double>& slip_displacements() const { return slip_; }

  private:
    Eigen::Vector3d direction_;
    Eigen::Vector3d rest_position_m_;
    std::vector<double> stiffness_;
    std::vector<double> slip_;
    std::vector<double> sliders_;
};

}  // namespace sb::bench

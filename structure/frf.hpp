// Analytic modal frequency response functions between named points.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <string_view>

#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::structure {

/// Accelerance [m/s^2 per N] at `out_point` along out_direction for a force at `in_point`
/// along in_direction (directions normalised), at frequency_hz, over the first `modes` modes
/// (all if < 0): H = sum_r phi_out,r phi_in,r (-W^2) / (w_r^2 - W^2 + 2 i zeta_r w_r W)
/// (Ewins, Modal Testing, eq. 2.52, times -W^2). Phase convention: response = Re(H F e^{iWt}).
std::complex<double> modal_accelerance(const LinearModel& model, const ModalBasis& basis,
                                       std::string_view out_point,
                                       const Eigen::Vector3d& out_direction,
                                       std::string_view in_point,
                                       const Eigen::Vector3d& in_direction, double frequency_hz,
                                       int modes = -1);

/// Absolute acceleration [m/s^2 per m/s^2] at `out_point` along out_direction (normalised)
/// for a unit base acceleration along the model's excitation direction, at frequency_hz, over
/// the first `modes` modes (all if < 0). In coordinates relative to the base, q_r'' + 2 zeta_r
/// w_r q_r' + w_r^2 q_r = -G_r a_b with G_r = phi_r^T M r (Chopra, Dynamics of Structures,
/// eq. 13.1.5), so T = d . (b + sum_r P phi_r G_r W^2 / (w_r^2 - W^2 + 2 i zeta_r w_r W)),
/// b the point's quasi-static motion per unit base motion (PointMap::base_motion). Throws
/// std::invalid_argument if the model has no base influence vector.
std::complex<double> modal_base_transmissibility(const LinearModel& model, const ModalBasis& basis,
                                                 std::string_view out_point,
                                                 const Eigen::Vector3d& out_direction,
                                                 double frequency_hz, int modes = -1);

}  // namespace sb::structure

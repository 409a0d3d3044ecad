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

}  // namespace sb::structure

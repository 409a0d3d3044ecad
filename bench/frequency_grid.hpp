// The stepped-sine frequency grid: given, or built around the first mode.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "bench/campaign_spec.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::bench {

/// Frequency [Hz] of the first mode whose effective mass is largest along `direction`
/// among the three translations: the first mode the shaker drives. Throws if there is none.
double first_driven_mode_hz(const structure::ModalBasis& basis, const Eigen::Vector3d& direction);

/// The grid in sweep order. Built grids are equally spaced in the phase angle of a single
/// mode with grid_damping_ratio, atan(2 zeta r / (1 - r^2)), between low_ratio and high_ratio
/// of the first mode: the points crowd where the FRF changes fastest, as a lab engineer
/// places them for half-power and circle fits.
std::vector<double> frequency_grid(const FrequencyGridSpec& spec, double first_mode_hz);

}  // namespace sb::bench

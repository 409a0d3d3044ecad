// The stepped-sine frequency grid.
#include "bench/frequency_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sb::bench {

double first_driven_mode_hz(const structure::ModalBasis& basis, const Eigen::Vector3d& direction) {
    const Eigen::Vector3d d = direction.cwiseAbs().normalized();
    Eigen::Index axis = 0;
    d.maxCoeff(&axis);
    for (const auto& mode : basis.modes) {
        Eigen::Index largest = 0;
        mode.effective_mass_kg.maxCoeff(&largest);
        if (largest == axis && mode.effective_mass_kg[axis] > 0.0) {
            return mode.frequency_hz;
        }
    }
    throw std::runtime_error(
        "no mode of the structure moves mainly along the excitation direction: cannot build "
        "a frequency grid around the first mode (give campaign.frequencies.values_hz)");
}

std::vector<double> frequency_grid(const FrequencyGridSpec& spec, double first_mode_hz) {
    std::vector<double> grid = spec.values_hz;
    if (grid.empty()) {
        const double zeta = spec.grid_damping_ratio;
        const auto phase = [zeta](double r) { return std::atan2(2.0 * zeta * r, 1.0 - r * r); };
        const double lo = phase(spec.low_ratio);
        const double hi = phase(spec.high_ratio);
        for (int k = 0; k < spec.count; ++k) {
            const double theta = lo + (hi - lo) * k / (spec.count - 1);
            // sin(t) (1 - r^2) = 2 zeta r cos(t)  =>  r = (-zeta c + sqrt(zeta^2 c^2 + s^2)) / s
            const double c = std::cos(theta);
            const double s = std::sin(theta);
            const double r = (-zeta * c + std::sqrt(zeta * zeta * c * c + s * s)) / s;
            grid.push_back(r * first_mode_hz);
        }
    }
    std::sort(grid.begin(), grid.end());
    if (spec.direction == FrequencyGridSpec::Direction::down) {
        std::reverse(grid.begin(), grid.end());
    }
    return grid;
}

}  // namespace sb::bench

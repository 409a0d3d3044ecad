// Exact discretisation of a damped modal oscillator with a piecewise-linear load.
#pragma once

#include <Eigen/Core>

namespace sb::structure {

/// Step matrices of q'' + 2 zeta omega q' + omega^2 q = f(t) over a step h with f linear in
/// the step: x = [q, q']^T, x1 = phi x0 + gamma0 f0 + gamma1 (f1 - f0). Exact for any h.
struct OscillatorStep {
    Eigen::Matrix2d phi;     ///< state transition e^{A h} [-, s; 1/s, -]
    Eigen::Vector2d gamma0;  ///< response to a constant unit load over the step [s^2, s]
    Eigen::Vector2d gamma1;  ///< response to a load ramping from 0 to 1 over the step [s^2, s]
};

/// First-order-hold discretisation, computed in closed form when omega h > 1 and by the
/// matrix exponential otherwise (Franklin, Powell & Workman, Digital Control of Dynamic
/// Systems, 3rd ed., sec. 6.3.2 "triangle hold equivalent"): with A = [0 1; -w^2 -2 zeta w],
/// b = [0; 1], the augmented matrix exponential (Van Loan, IEEE TAC 23 (1978) 395)
/// exp([A b 0; 0 0 1/h; 0 0 0] h) = [phi gamma0 gamma1; 0 1 1; 0 0 1], since the ramp input
/// u(t) = t/h obeys u' = 1/h. omega [rad/s] >= 0, zeta in [0, 1), h [s] > 0.
OscillatorStep oscillator_step(double omega_rad_s, double zeta, double h_s);

}  // namespace sb::structure

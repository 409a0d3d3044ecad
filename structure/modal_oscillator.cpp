// Exact discretisation of a damped modal oscillator with a piecewise-linear load.
#include "structure/modal_oscillator.hpp"

#include <cmath>
#include <unsupported/Eigen/MatrixFunctions>

namespace sb::structure {
namespace {

/// Van Loan's augmented exponential, accurate when |A| h is moderate.
OscillatorStep by_matrix_exponential(double omega, double zeta, double h) {
    Eigen::Matrix4d augmented = Eigen::Matrix4d::Zero();
    augmented(0, 1) = 1.0;
    augmented(1, 0) = -omega * omega;
    augmented(1, 1) = -2.0 * zeta * omega;
    augmented(1, 2) = 1.0;                            // b
    augmented(2, 3) = 1.0 / h;                        // ramp input u' = 1/h
    const Eigen::Matrix4d e = (augmented * h).exp();  // scaling and squaring Pade
    return {e.topLeftCorner<2, 2>(), e.block<2, 1>(0, 2), e.block<2, 1>(0, 3)};
}

/// Closed form for an underdamped oscillator, used when omega h > 1 (no cancellation there):
/// phi = e^{-zeta w h} [c + (zeta w/wd) s, s/wd; -w^2 s/wd, c - (zeta w/wd) s]
/// (Clough & Penzien, Dynamics of Structures, eq. 2-49); gamma0 = A^-1 (phi - I) b and
/// gamma1 = gamma0 - A^-1 phi b + A^-2 (phi - I) b / h, from integrating e^{A s} and s e^{A s}.
OscillatorStep closed_form(double omega, double zeta, double h) {
    const double wd = omega * std::sqrt(1.0 - zeta * zeta);
    const double sigma = zeta * omega;
    const double decay = std::exp(-sigma * h);
    const double c = std::cos(wd * h);
    const double s = std::sin(wd * h);
    OscillatorStep step;
    step.phi << c + sigma / wd * s, s / wd, -omega * omega * s / wd, c - sigma / wd * s;
    step.phi *= decay;
    Eigen::Matrix2d a_inv;
    a_inv << -2.0 * zeta / omega, -1.0 / (omega * omega), 1.0, 0.0;
    const Eigen::Vector2d b(0.0, 1.0);
    const Eigen::Vector2d phi_minus_i_b = step.phi * b - b;
    step.gamma0 = a_inv * phi_minus_i_b;
    step.gamma1 = step.gamma0 - a_inv * (step.phi * b) + a_inv * (a_inv * phi_minus_i_b) / h;
    return step;
}

}  // namespace

OscillatorStep oscillator_step(double omega_rad_s, double zeta, double h_s) {
    if (omega_rad_s * h_s <= 1.0 || zeta >= 1.0) {
        return by_matrix_exponential(omega_rad_s, zeta, h_s);
    }
    return closed_form(omega_rad_s, zeta, h_s);
}

}  // namespace sb::structure

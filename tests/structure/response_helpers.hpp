// Running the reduced modal model and the Newmark integrator side by side in the tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "core/units.hpp"
#include "structure/newmark_integrator.hpp"
#include "structure/reduced_modal_model.hpp"

namespace sb::structure::testing {

/// Largest difference of the two integrators' outputs over a run, relative to the largest
/// output of the reduced model [-].
struct RunDifference {
    double displacement = 0.0;
    double acceleration = 0.0;
};

/// Steps both integrators (same dt) `steps` times from their present state, calling
/// `input(sim, t_end)` on each before its step to set the loads at the end of the step, and
/// compares the displacement and acceleration of `point` along `direction`.
template <typename Input>
RunDifference run_side_by_side(ReducedModalModel& reduced, NewmarkIntegrator& full,
                               const std::string& point, const Eigen::Vector3d& direction,
                               int steps, Input&& input) {
    double largest_u = 0.0, largest_a = 0.0, diff_u = 0.0, diff_a = 0.0;
    for (int n = 0; n < steps; ++n) {
        const double t_end = reduced.time_s() + reduced.dt_s();
        input(reduced, t_end);
        input(full, t_end);
        reduced.step();
        full.step();
        const double u = direction.dot(reduced.displacement(point));
        const double a = direction.dot(reduced.acceleration(point));
        largest_u = std::max(largest_u, std::abs(u));
        largest_a = std::max(largest_a, std::abs(a));
        diff_u = std::max(diff_u, std::abs(direction.dot(full.displacement(point)) - u));
        diff_a = std::max(diff_a, std::abs(direction.dot(full.acceleration(point)) - a));
    }
    return {diff_u / largest_u, diff_a / largest_a};
}

/// A sine of amplitude A at W whose envelope rises from 0 to 1 over `ramp_s` with the C2
/// smoothstep s = 10 u^3 - 15 u^4 + 6 u^5 (u = t / ramp): its value, rate and second rate
/// are continuous, so a start from rest leaves the higher modes without a free oscillation
/// (a sudden sine start rings them, and their free response is what Newmark's period error
/// acts on most).
struct SmoothSine {
    double amplitude = 1.0;
    double omega_rad_s = 1.0;
    double ramp_s = 1.0;

    [[nodiscard]] Eigen::Vector3d envelope(double t) const {  // s, s', s''
        if (t >= ramp_s) return {1.0, 0.0, 0.0};
        const double u = std::max(t, 0.0) / ramp_s;
        return {u * u * u * (10.0 + u * (-15.0 + 6.0 * u)),
                30.0 * u * u * (1.0 - u) * (1.0 - u) / ramp_s,
                60.0 * u * (1.0 - u) * (1.0 - 2.0 * u) / (ramp_s * ramp_s)};
    }
    [[nodiscard]] double value(double t) const {
        return amplitude * envelope(t)(0) * std::sin(omega_rad_s * t);
    }
    [[nodiscard]] double rate(double t) const {
        const Eigen::Vector3d s = envelope(t);
        const double w = omega_rad_s;
        return amplitude * (s(1) * std::sin(w * t) + s(0) * w * std::cos(w * t));
    }
    [[nodiscard]] double second_rate(double t) const {
        const Eigen::Vector3d s = envelope(t);
        const double w = omega_rad_s;
        return amplitude * (s(2) * std::sin(w * t) + 2.0 * s(1) * w * std::cos(w * t) -
                            s(0) * w * w * std::sin(w * t));
    }
};

/// Estimated error of the Newmark (trapezoidal) response relative to the present amplitude,
/// when a mode of frequency fr_hz and damping ratio zeta is driven at f_hz from rest for
/// `periods` periods with step h_s. The trapezoidal rule is the bilinear map: it responds at
/// W as the continuous system does at W (1 + e), e = (W h)^2 / 12 (Franklin, Powell &
/// Workman, Digital Control of Dynamic Systems, sec. 6.3.3), i.e. it detunes the mode by
/// e_r = (w_r h)^2 / 12 relative to the drive. A response building up from rest for a time t
/// moves by e_r w_r t / 2 (the phase of the detuning, averaged over the build-up), at most
/// by e_r / (2 zeta) once steady (the slope of a single-mode FRF at W = w_r (1 +- zeta));
/// the W^2 of accelerations adds 2 e.
inline double newmark_error_estimate(double f_hz, double fr_hz, double zeta, double h_s,
                                     int periods) {
    const double e = std::pow(kTwoPi * f_hz * h_s, 2) / 12.0;
    const double e_r = std::pow(kTwoPi * fr_hz * h_s, 2) / 12.0;
    const double build_up = kPi * fr_hz * periods / f_hz;  // w_r t / 2
    return e_r * std::min(build_up, 1.0 / (2.0 * zeta)) + 2.0 * e;
}

}  // namespace sb::structure::testing

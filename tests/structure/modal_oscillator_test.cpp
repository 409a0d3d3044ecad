// The exact first-order-hold discretisation of a modal oscillator.
#include "structure/modal_oscillator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/units.hpp"

namespace sb::structure {
namespace {

// Exact discretisation: only round-off accumulates (about 1e-16 per step over 1e3-1e4 steps).
constexpr double kExact = 1e-9;

TEST(ModalOscillator, FreeDecayMatchesTheAnalyticSolution) {
    const double w = kTwoPi * 10.0;
    const double zeta = 0.02;
    const double h = 1e-3;
    const OscillatorStep s = oscillator_step(w, zeta, h);
    Eigen::Vector2d x(1.0, 0.0);
    const double wd = w * std::sqrt(1.0 - zeta * zeta);
    for (int n = 1; n <= 2000; ++n) {
        x = s.phi * x;
        const double t = n * h;
        // Clough & Penzien eq. 2-49 with u0 = 1, v0 = 0.
        const double q =
            std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
        ASSERT_NEAR(x(0), q, kExact) << "step " << n;
    }
}

TEST(ModalOscillator, LoadRampingLinearlyIsFollowedExactlyAtCoarseAndFineSteps) {
    // Load f = a + b t has the particular solution q = (a + b t)/w^2 - 2 zeta b / w^3.
    const double w = 30.0;
    const double zeta = 0.1;
    const double a = 2.0;
    const double b = 5.0;
    for (const double h : {1e-4, 0.01, 0.5}) {
        const OscillatorStep s = oscillator_step(w, zeta, h);
        const auto q_exact = [&](double t) {
            return (a + b * t) / (w * w) - 2.0 * zeta * b / (w * w * w);
        };
        Eigen::Vector2d x(q_exact(0.0), b / (w * w));
        for (int n = 0; n < 50; ++n) {
            const double f0 = a + b * n * h;
            const double f1 = a + b * (n + 1) * h;
            x = s.phi * x + s.gamma0 * f0 + s.gamma1 * (f1 - f0);
        }
        EXPECT_NEAR(x(0) * w * w, q_exact(50 * h) * w * w, kExact) << h;
        EXPECT_NEAR(x(1) * w * w, b, kExact) << h;
    }
}

TEST(ModalOscillator, IsStableAtAStepFarLongerThanThePeriod) {
    const double w = kTwoPi * 1000.0;
    const double h = 1.0;  // w h = 6283
    for (const double zeta : {0.0, 0.005}) {
        const OscillatorStep s = oscillator_step(w, zeta, h);
        Eigen::Vector2d x(1.0, 0.0);
        for (int n = 0; n < 10000; ++n) {
            x = s.phi * x;
            const double energy = x(1) * x(1) + w * w * x(0) * x(0);
            ASSERT_LE(energy, w * w * (1.0 + kExact)) << "step " << n;
        }
        // A constant unit load settles on the static deflection 1 / w^2.
        x.setZero();
        for (int n = 0; n < 3; ++n) x = s.phi * x + s.gamma0;
        if (zeta > 0.0) {
            EXPECT_NEAR(x(0) * w * w, 1.0, 1e-6);
        }
    }
}

TEST(ModalOscillator, ClosedFormAndMatrixExponentialAgreeWhereTheyMeet) {
    const double w = 40.0;
    const double zeta = 0.05;
    // oscillator_step switches at w h = 1; both sides must agree to round-off.
    const OscillatorStep below = oscillator_step(w, zeta, 1.0 / w * (1.0 - 1e-12));
    const OscillatorStep above = oscillator_step(w, zeta, 1.0 / w * (1.0 + 1e-12));
    EXPECT_LT((below.phi - above.phi).norm(), 1e-9);
    EXPECT_LT((below.gamma0 - above.gamma0).norm() * w * w, 1e-9);
    EXPECT_LT((below.gamma1 - above.gamma1).norm() * w * w, 1e-9);
}

}  // namespace
}  // namespace sb::structure

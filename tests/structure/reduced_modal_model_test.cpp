// Steady-state response of the reduced modal model and the Newmark integrator against the
// analytic modal accelerance of the paper-000 beam.
#include "structure/reduced_modal_model.hpp"

#include <gtest/gtest.h>

#include <complex>

#include "beam_fixtures.hpp"
#include "structure/frf.hpp"
#include "structure/newmark_integrator.hpp"

namespace sb::structure {
namespace {

using namespace std::complex_literals;

// Reduced model: exact up to the linear interpolation of a sine within a step, which changes
// the load by ~(W dt)^2/12 = 2e-5 at 400 steps per period: far below 0.5 %.
constexpr double kReducedTolerance = 5e-3;
// Newmark's period error (W dt)^2/12 = 3e-6 at 1000 steps per period, amplified near
// resonance by 1/(2 zeta) = 100, plus the higher modes that the FRF truncates: below 1 %.
constexpr double kNewmarkTolerance = 1e-2;
constexpr int kModes = 8;
constexpr double kForceN = 0.1;

/// Complex amplitude of the fundamental of the sampled signal (last `periods` whole periods):
/// signal = Re(X e^{i W t}).
template <typename Integrator>
std::complex<double> run_and_extract(Integrator& sim, double frequency_hz, int steps_per_period,
                                     int periods) {
    const double w = kTwoPi * frequency_hz;
    std::complex<double> sum = 0.0;
    const int total = steps_per_period * periods;
    for (int n = 0; n < total; ++n) {
        const double t_next = sim.time_s() + sim.dt_s();
        sim.set_point_load("shaker", Eigen::Vector3d::UnitZ() * (kForceN * std::sin(w * t_next)),
                           Eigen::Vector3d::Zero());
        sim.step();
        sum += sim.acceleration("damper").z() * std::exp(-1i * (w * sim.time_s()));
    }
    return 2.0 * sum / static_cast<double>(total);
}

class Paper000Response : public ::testing::Test {
  protected:
    void SetUp() override {
        spec_ = testing::paper000_loaded();
        model_ = build_linear_model(spec_, {});
        basis_ = compute_modes(model_, spec_.damping, kModes);
    }
    [[nodiscard]] std::complex<double> analytic(double f) const {
        // Force F sin(W t) = Re(-i F e^{i W t}).
        return modal_accelerance(model_, basis_, "damper", Eigen::Vector3d::UnitZ(), "shaker",
                                 Eigen::Vector3d::UnitZ(), f) *
               (-1i * kForceN);
    }
    StructureSpec spec_;
    LinearModel model_;
    ModalBasis basis_;
};

TEST_F(Paper000Response, ReducedModelMatchesTheModalAccelerance) {
    for (const double f : {5.8, 6.2, basis_.modes[0].frequency_hz, 6.6, 7.0}) {
        constexpr int kSteps = 400;
        ReducedModalModel sim(model_, basis_, 1.0 / (f * kSteps));
        sim.set_harmonic_steady_state("shaker", Eigen::Vector3d::UnitZ(), kForceN, f, 0.0);
        const std::complex<double> got = run_and_extract(sim, f, kSteps, 3);
        const std::complex<double> expected = analytic(f);
        EXPECT_NEAR(std::abs(got) / std::abs(expected), 1.0, kReducedTolerance) << f << " Hz";
        EXPECT_NEAR(std::arg(got / expected), 0.0, kReducedTolerance) << f << " Hz";
    }
}

TEST_F(Paper000Response, NewmarkIntegratorOfTheFullModelAgrees) {
    for (const double f : {5.8, basis_.modes[0].frequency_hz, 7.0}) {
        constexpr int kSteps = 1000;
        NewmarkIntegrator sim(model_, basis_, spec_.damping, 1.0 / (f * kSteps));
        sim.set_harmonic_steady_state("shaker", Eigen::Vector3d::UnitZ(), kForceN, f, 0.0);
        const std::complex<double> got = run_and_extract(sim, f, kSteps, 2);
        const std::complex<double> expected = analytic(f);
        EXPECT_NEAR(std::abs(got) / std::abs(expected), 1.0, kNewmarkTolerance) << f << " Hz";
    }
}

TEST_F(Paper000Response, HugeStepStaysBoundedAndSettlesOnTheStaticDeflection) {
    // dt = 10 s is far beyond every period (the slowest is 0.16 s); a constant force must give
    // the static deflection of the kept modes, never blow up.
    ReducedModalModel sim(model_, basis_, 10.0);
    sim.set_point_load("shaker", Eigen::Vector3d::UnitZ() * kForceN, Eigen::Vector3d::Zero());
    for (int n = 0; n < 200; ++n) sim.step();
    const auto shapes = point_shapes(model_, basis_, "damper");
    const auto load = point_shapes(model_, basis_, "shaker");
    double expected = 0.0;
    for (int r = 0; r < kModes; ++r) {
        const double w = kTwoPi * basis_.modes[static_cast<std::size_t>(r)].frequency_hz;
        expected += shapes(2, r) * load(2, r) * kForceN / (w * w);
    }
    EXPECT_NEAR(sim.displacement("damper").z() / expected, 1.0, 1e-6);
}

TEST(ReducedModalModelBase, CantileverOnAMovingRootFollowsItsBaseQuasiStaticallyBelowResonance) {
    StructureSpec spec = testing::paper000_loaded();
    spec.excitation.kind = ExcitationSpec::Kind::base;
    spec.excitation.support = "root";
    const LinearModel model = build_linear_model(spec, {});
    const ModalBasis basis = compute_modes(model, spec.damping, kModes);
    // Well below the first mode the absolute acceleration approaches the base acceleration;
    // analytic: transmissibility 1 + sum_r Gamma_r phi_r W^2 / (w_r^2 - W^2 + ...).
    const double f = 0.5;
    ReducedModalModel sim(model, basis, 1.0 / (f * 400));
    sim.set_harmonic_base_steady_state(1.0, f, 0.0);
    const double w = kTwoPi * f;
    std::complex<double> sum = 0.0;
    for (int n = 0; n < 400; ++n) {
        const double t_next = sim.time_s() + sim.dt_s();
        sim.set_base_motion(-std::sin(w * t_next) / (w * w), -std::cos(w * t_next) / w,
                            std::sin(w * t_next));
        sim.step();
        sum += sim.acceleration("damper").z() * std::exp(-1i * (w * sim.time_s()));
    }
    const std::complex<double> got = 2.0 * sum / 400.0;
    const Eigen::VectorXd gamma = basis.shapes.transpose() * model.mass() * *model.base_influence();
    const auto phi = point_shapes(model, basis, "damper");
    std::complex<double> expected = 1.0;
    for (int r = 0; r < kModes; ++r) {
        const double wr = kTwoPi * basis.modes[static_cast<std::size_t>(r)].frequency_hz;
        const double z = basis.modes[static_cast<std::size_t>(r)].damping_ratio;
        expected += phi(2, r) * gamma(r) * w * w / (wr * wr - w * w + 2i * z * wr * w);
    }
    expected *= -1i;  // base acceleration sin(W t) = Re(-i e^{i W t})
    EXPECT_NEAR(std::abs(got / expected), 1.0, kReducedTolerance);
    EXPECT_NEAR(std::arg(got / expected), 0.0, kReducedTolerance);
}

}  // namespace
}  // namespace sb::structure

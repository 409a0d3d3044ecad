// Steady-state response of the reduced modal model and the Newmark integrator against the
// analytic modal accelerance of the paper-000 beam.
#include "structure/reduced_modal_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "beam_fixtures.hpp"
#include "response_helpers.hpp"
#include "structure/beam_model.hpp"
#include "structure/frf.hpp"
#include "structure/newmark_integrator.hpp"

namespace sb::structure {
namespace {

using namespace std::complex_literals;

// Reduced model started from rest: exact for loads linear within a step, so its error is the
// linear interpolation of the sine, whose fundamental shrinks by ~(W dt)^2/12 = 2e-5 at 400
// steps per period, plus the transient left after settling (kResidualTransient). The issue
// asks for 0.5 %; the model's own error budget is 3e-5, so 2e-4 still leaves room for
// round-off while catching any real defect.
constexpr double kReducedTolerance = 2e-4;
constexpr double kResidualTransient = 1e-5;  // transient left when the extraction starts
constexpr int kReducedSteps = 400;           // steps per period
constexpr int kExtractPeriods = 10;          // whole periods the amplitude is taken over
// Newmark against the reduced model: the error estimate of response_helpers.hpp (detuning by
// the trapezoidal rule) is first order; a factor 1.5 covers the higher modes' share and the
// modes the reduced model leaves out (their quasi-static response to the smoothly rising
// force is ~1e-6 of the resonant one).
constexpr double kNewmarkEstimateFactor = 1.5;
constexpr int kNewmarkSteps = 1000;    // steps per period
constexpr int kNewmarkPeriods = 10;    // periods run from rest
constexpr double kOnsetPeriods = 3.0;  // smooth rise of the force (response_helpers.hpp)
constexpr int kReducedModes = 8;
constexpr double kForceN = 0.1;

/// Complex amplitude of the fundamental of the damper acceleration over the next `periods`
/// whole periods, under the shaker force F sin(2 pi f t): signal = Re(X e^{i W t}).
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

/// Periods at f until the free response of a mode (fr, zeta) started from rest has decayed to
/// kResidualTransient of its initial size: e^{-zeta w_r t} = kResidualTransient.
int settling_periods(double f_hz, double fr_hz, double zeta) {
    return static_cast<int>(
        std::ceil(std::log(1.0 / kResidualTransient) * f_hz / (kTwoPi * zeta * fr_hz)));
}

class Paper000Response : public ::testing::Test {
  protected:
    void SetUp() override {
        spec_ = testing::paper000_loaded();
        model_ = build_linear_model(spec_, {});
        basis_ = compute_modes(model_, spec_.damping, kReducedModes);
        f1_ = basis_.modes[0].frequency_hz;
        zeta1_ = basis_.modes[0].damping_ratio;
    }
    [[nodiscard]] std::complex<double> analytic(double f) const {
        // Force F sin(W t) = Re(-i F e^{i W t}).
        return modal_accelerance(model_, basis_, "damper", Eigen::Vector3d::UnitZ(), "shaker",
                                 Eigen::Vector3d::UnitZ(), f) *
               (-1i * kForceN);
    }
    /// f1 (1 + k zeta1): k = -1, 1 are the half-power points of the first mode.
    [[nodiscard]] double around_resonance(int k) const { return f1_ * (1.0 + k * zeta1_); }
    StructureSpec spec_;
    LinearModel model_;
    ModalBasis basis_;
    double f1_ = 0.0;
    double zeta1_ = 0.0;
};

TEST_F(Paper000Response, ReducedModelStartedFromRestSettlesOnTheModalAccelerance) {
    ASSERT_DOUBLE_EQ(zeta1_, 0.005);
    for (int k = -3; k <= 3; ++k) {
        const double f = around_resonance(k);
        ReducedModalModel sim(model_, basis_, 1.0 / (f * kReducedSteps));
        (void)run_and_extract(sim, f, kReducedSteps, settling_periods(f, f1_, zeta1_));
        const std::complex<double> got = run_and_extract(sim, f, kReducedSteps, kExtractPeriods);
        const std::complex<double> expected = analytic(f);
        EXPECT_NEAR(std::abs(got) / std::abs(expected), 1.0, kReducedTolerance) << "k = " << k;
        EXPECT_NEAR(std::arg(got / expected), 0.0, kReducedTolerance) << "k = " << k;
    }
}

TEST_F(Paper000Response, NewmarkOnTheFullModelFollowsTheReducedModelAcrossTheResonance) {
    for (const int k : {-3, -1, 0, 1, 3}) {
        const double f = around_resonance(k);
        const double h = 1.0 / (f * kNewmarkSteps);
        const testing::SmoothSine force{kForceN, kTwoPi * f, kOnsetPeriods / f};
        ReducedModalModel reduced(model_, basis_, h);
        NewmarkIntegrator full(model_, basis_, spec_.damping, h);
        const auto diff = testing::run_side_by_side(
            reduced, full, "damper", Eigen::Vector3d::UnitZ(), kNewmarkSteps * kNewmarkPeriods,
            [&](auto& sim, double t) {
                sim.set_point_load("shaker", Eigen::Vector3d::UnitZ() * force.value(t),
                                   Eigen::Vector3d::Zero());
            });
        const double tolerance = kNewmarkEstimateFactor * testing::newmark_error_estimate(
                                                              f, f1_, zeta1_, h, kNewmarkPeriods);
        EXPECT_LT(diff.displacement, tolerance) << "k = " << k;
        EXPECT_LT(diff.acceleration, tolerance) << "k = " << k;
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
    for (int r = 0; r < kReducedModes; ++r) {
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
    const ModalBasis basis = compute_modes(model, spec.damping, kReducedModes);
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
    for (int r = 0; r < kReducedModes; ++r) {
        const double wr = kTwoPi * basis.modes[static_cast<std::size_t>(r)].frequency_hz;
        const double z = basis.modes[static_cast<std::size_t>(r)].damping_ratio;
        expected += phi(2, r) * gamma(r) * w * w / (wr * wr - w * w + 2i * z * wr * w);
    }
    expected *= -1i;  // base acceleration sin(W t) = Re(-i e^{i W t})
    EXPECT_NEAR(std::abs(got / expected), 1.0, kReducedTolerance);
    EXPECT_NEAR(std::arg(got / expected), 0.0, kReducedTolerance);
}

TEST(ReducedModalModelRotation, ATipMomentRampTurnsTheCantileverTipByMLOverEI) {
    // Euler-Bernoulli cantilever under a tip moment M about y: uniform curvature M/(E I), so
    // the tip turns by M L/(E I) and deflects by w = -M L^2/(2 E I) (r_y = -dw/dx); cubic
    // elements hold this quadratic deflection exactly and all modes sum to K^-1 f. A ramp
    // M = c t stepped with dt far beyond every period leaves, once the free response has
    // decayed, q = c t / w^2 - 2 zeta c / w^3 per mode: the lag's share is
    // 2 zeta / (w_1 t) < 1e-6 at t = 2000 s, the rate q' = c / w^2 exact.
    constexpr double kLagAndRoundOff = 1e-6;
    BeamSpec b = testing::steel_strip();
    b.min_elements = 20;
    b.supports = {testing::support("root", 0.0, SupportKind::clamped)};
    b.points = {NamedPoint{"tip", 1.0}};
    const LinearModel model = build_beam_model(b, ExcitationSpec{});
    const DampingSpec damping;  // 0.5 % on every mode
    const ModalBasis basis = compute_modes(model, damping, model.dofs());
    constexpr double kDt = 10.0;
    constexpr int kSteps = 200;
    ReducedModalModel sim(model, basis, kDt);
    const double rate_nm_per_s = 1e-3;
    for (int n = 0; n < kSteps; ++n) {
        sim.set_point_load("tip", Eigen::Vector3d::Zero(),
                           {0.0, rate_nm_per_s * (sim.time_s() + kDt), 0.0});
        sim.step();
    }
    const double ei = b.youngs_modulus_pa * b.width_m * std::pow(b.thickness_m, 3) / 12.0;
    const double moment = rate_nm_per_s * sim.time_s();
    EXPECT_NEAR(sim.rotation("tip").y() / (moment * b.length_m / ei), 1.0, kLagAndRoundOff);
    EXPECT_NEAR(sim.angular_velocity("tip").y() / (rate_nm_per_s * b.length_m / ei), 1.0,
                kLagAndRoundOff);
    EXPECT_NEAR(sim.displacement("tip").z() / (-moment * b.length_m * b.length_m / (2.0 * ei)), 1.0,
                kLagAndRoundOff);
    const double rotation_scale = moment * b.length_m / ei;
    EXPECT_NEAR(sim.rotation("tip").x() / rotation_scale, 0.0, kLagAndRoundOff);
    EXPECT_NEAR(sim.rotation("tip").z() / rotation_scale, 0.0, kLagAndRoundOff);
    const Eigen::Vector3d root_rotation = sim.rotation("root");
    EXPECT_EQ(root_rotation.norm(), 0.0);  // clamped DOFs have no column in the model
}

}  // namespace
}  // namespace sb::structure

// The Iwan joint (physics.iwan_joint): its describing function against the Fourier series of
// its own stepped loop, its dissipation against Segalman's closed form for the continuous
// power-law density, the effect of the number of elements, its state, and the prediction
// against the run on the linear paper-000 bench.
#include "bench/iwan_joint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bench/campaign.hpp"
#include "bench/physics_spec.hpp"
#include "bench/prediction.hpp"
#include "campaign_fixtures.hpp"

namespace sb::bench {
namespace {

constexpr double kStiffness = 2000.0;  // K_T [N/m]
constexpr double kMacroslip = 4e-4;    // phi_max [m]

/// The joint's slip force F_S = K_T phi_max (1 + chi) / (2 + chi) [N].
double slip_force(double chi) { return kStiffness * kMacroslip * (1.0 + chi) / (2.0 + chi); }

/// The joint stepped through three periods of u = U cos(theta) from rest (the first brings
/// the sliders onto their steady loop), the last period's fundamental and third harmonic
/// of its force as complex amplitudes of e^(i theta) and e^(3 i theta).
struct Harmonics {
    std::complex<double> first, third;
};
Harmonics stepped_harmonics(IwanJoint joint, double amplitude_m) {
    const Eigen::Vector3d rest(0.3, 0.0, 0.002);
    const int n = 20000;
    Harmonics h{0.0, 0.0};
    for (int period = 0; period < 3; ++period) {
        for (int i = 0; i < n; ++i) {
            const double theta = 2.0 * std::numbers::pi * (i + 0.5) / n;
            PointMotion motion;
            motion.position_m = rest + Eigen::Vector3d(0.0, 0.0, amplitude_m * std::cos(theta));
            const double f = joint.step(motion, 1e-5).force_n.z();
            if (period == 2) {
                h.first += 2.0 / n * f * std::exp(std::complex<double>(0.0, -theta));
                h.third += 2.0 / n * f * std::exp(std::complex<double>(0.0, -3.0 * theta));
            }
        }
    }
    return h;
}

TEST(IwanJoint, ItsDescribingFunctionIsTheFundamentalOfItsSteppedLoop) {
    const double f = 6.4, w = 2.0 * std::numbers::pi * f;
    for (const double chi : {-0.8, -0.5, 0.0}) {
        const IwanJoint joint(Eigen::Vector3d::UnitZ(), kStiffness, kMacroslip, chi, 96,
                              Eigen::Vector3d(0.3, 0.0, 0.002));
        // Deep microslip, halfway to macroslip, and sliding as a whole.
        for (const double ratio : {0.01, 0.5, 3.0}) {
            const double u = ratio * kMacroslip;
            const Harmonics stepped = stepped_harmonics(joint, u);
            const auto value = joint.describing(w * w * u, f);
            // F1 = M w^2 U: the apparent mass from the stepped loop's fundamental.
            const std::complex<double> expected = stepped.first / (w * w * u);
            EXPECT_NEAR(value.apparent_mass_kg.real(), expected.real(), 2e-3 * std::abs(expected))
                << chi << " " << ratio;
            EXPECT_NEAR(value.apparent_mass_kg.imag(), expected.imag(), 2e-3 * std::abs(expected))
                << chi << " " << ratio;
            // Softening and dissipation: the stiffness the slip takes away, the loop's area.
            EXPECT_GT(value.apparent_mass_kg.real(), 0.0);
            EXPECT_LT(value.apparent_mass_kg.imag(), 0.0);
            EXPECT_NEAR(value.h3_ratio, std::abs(stepped.third) / std::abs(stepped.first), 2e-3)
                << chi << " " << ratio;
            EXPECT_EQ(value.h2_ratio, 0.0);
        }
    }
}

TEST(IwanJoint, ItsElementsHoldTheJointsStiffnessAndSlipForceAndStickBelowTheFinestSlip) {
    const double chi = -0.5;
    const double slip_force_n = slip_force(chi);
    const IwanJoint joint(Eigen::Vector3d::UnitZ(), kStiffness, kMacroslip, chi, 96,
                          Eigen::Vector3d::Zero());
    double k = 0.0, force = 0.0;
    for (std::size_t i = 0; i < joint.stiffnesses().size(); ++i) {
        k += joint.stiffnesses()[i];
        force += joint.stiffnesses()[i] * joint.slip_displacements()[i];
    }
    EXPECT_NEAR(k, kStiffness, 1e-9 * kStiffness);
    EXPECT_NEAR(force, slip_force_n, 1e-9 * slip_force_n);
    // Below the smallest slip displacement nothing moves: no load, no describing function.
    const double smallest = joint.slip_displacements().front();
    IwanJoint stepped = joint;
    PointMotion motion;
    motion.position_m.z() = 0.9 * smallest;
    EXPECT_EQ(stepped.step(motion, 1e-4).force_n.norm(), 0.0);
    const double w = 2.0 * std::numbers::pi * 6.4;
    EXPECT_EQ(std::abs(joint.describing(0.9 * smallest * w * w, 6.4).apparent_mass_kg), 0.0);
}

/// Segalman's continuous density R phi^chi on (0, phi_max], R = K_T (1 + chi) / phi_max^(1+chi):
/// below macroslip every element with phi < U dissipates 4 k phi (U - phi) per cycle, so
/// D = 4 R U^(3 + chi) / ((2 + chi)(3 + chi)) (Segalman 2005, eq. 9).
double segalman_dissipation(double chi, double amplitude_m) {
    const double phi_max = kMacroslip;
    const double r = kStiffness * (1.0 + chi) / std::pow(phi_max, 1.0 + chi);
    return 4.0 * r * std::pow(amplitude_m, 3.0 + chi) / ((2.0 + chi) * (3.0 + chi));
}

TEST(IwanJoint, BelowMacroslipItDissipatesAsSegalmansPowerLawDensity) {
    const double f = 6.4, w = 2.0 * std::numbers::pi * f;
    for (const double chi : {-0.8, -0.5, -0.2}) {
        const IwanJoint joint(Eigen::Vector3d::UnitZ(), kStiffness, kMacroslip, chi, 96,
                              Eigen::Vector3d::Zero());
        for (const double ratio : {1e-3, 1e-2, 0.1, 0.5, 0.9}) {
            const double u = ratio * kMacroslip;
            // The loop's area pi U^2 Im K*, Im K* = -w^2 Im M.
            const double dissipated = -std::numbers::pi * u * u * w * w *
                                      joint.describing(w * w * u, f).apparent_mass_kg.imag();
            EXPECT_NEAR(dissipated / segalman_dissipation(chi, u), 1.0, 0.02)
                << chi << " " << ratio;
        }
    }
}

TEST(IwanJoint, TheDefaultNinetySixElementsAreWithinOnePercentOfEightThousand) {
    const double f = 6.4, w = 2.0 * std::numbers::pi * f;
    const int elements = IwanJointSpec{}.elements;
    EXPECT_EQ(elements, 96);
    for (const double chi : {-0.8, -0.5, -0.2, 0.0}) {
        const IwanJoint coarse(Eigen::Vector3d::UnitZ(), kStiffness, kMacroslip, chi, elements,
                               Eigen::Vector3d::Zero());
        const IwanJoint fine(Eigen::Vector3d::UnitZ(), kStiffness, kMacroslip, chi, 8000,
                             Eigen::Vector3d::Zero());
        for (double ratio = 1e-3; ratio < 3.0; ratio *= 1.07) {
            const double a = w * w * ratio * kMacroslip;
            const auto c = coarse.describing(a, f).apparent_mass_kg;
            const auto e = fine.describing(a, f).apparent_mass_kg;
            EXPECT_NEAR(c.real(), e.real(), 0.01 * std::abs(e.real())) << chi << " " << ratio;
            EXPECT_NEAR(c.imag(), e.imag(), 0.01 * std::abs(e.imag())) << chi << " " << ratio;
        }
    }
}

TEST(IwanJoint, ItsSlidersAreItsStateAndAStateOfAnotherSizeIsRefused) {
    IwanJoint joint(Eigen::Vector3d::UnitZ(), kStiffness, kMacroslip, -0.5, 8,
                    Eigen::Vector3d::Zero());
    PointMotion motion;
    motion.position_m.z() = 0.5 * kMacroslip;
    const PointLoad pushed = joint.step(motion, 1e-4);
    const AttachmentState saved = joint.state();
    ASSERT_TRUE(saved.sliders.has_value());
    IwanJoint resumed(Eigen::Vector3d::UnitZ(), kStiffness, kMacroslip, -0.5, 8,
                      Eigen::Vector3d::Zero());
    resumed.restore(saved);
    EXPECT_EQ(resumed.step(motion, 1e-4).force_n, pushed.force_n);
    AttachmentState wrong;
    wrong.sliders = std::vector<double>(5, 0.0);
    EXPECT_THROW(resumed.restore(wrong), std::invalid_argument);
    AttachmentState other;
    other.describing = DescribingState{};
    EXPECT_THROW(resumed.restore(other), std::invalid_argument);
}

/// The circle fit's natural frequency and damping ratio at a level.
std::pair<double, double> circle_fit(const CampaignResult& result, double level_g) {
    for (const auto& d : result.recording.damping) {
        if (d.method == "circle-fit" && std::abs(d.level_g - level_g) < 1e-9) {
            return {d.natural_frequency_hz, d.damping_ratio};
        }
    }
    ADD_FAILURE() << "no circle fit at " << level_g << " g";
    return {0.0, 0.0};
}

TEST(IwanJoint, ThePredictionBalancesTheJointAsTheRunStepsItAndTheModeSoftens) {
    // The linear paper-000 bench, 1 and 3 g on 25 frequencies over ±4 % of the mode.
    const auto bench = [] { return test::linear_paper000_bench(25); };
    auto config = bench();
    // A joint at the tip whose last slider moves at 30 mm (F_S = 0.1 N): in microslip at both
    // levels (about 6 and 18 mm of tip motion).
    config.physics.iwan_joint.point = "damper";
    config.physics.iwan_joint.stiffness_n_per_m = 10.0;
    config.physics.iwan_joint.macroslip_displacement_m = 0.03;
    config.physics.iwan_joint.exponent = -0.5;
    CampaignContext context;
    context.threads = 2;
    const CampaignResult bare = run_campaign(bench(), context);
    const CampaignResult run = run_campaign(config, context);
    const CampaignResult predicted = predict_campaign(config, {});
    for (const double level : {1.0, 3.0}) {
        const auto [f_run, zeta_run] = circle_fit(run, level);
        const auto [f_predicted, zeta_predicted] = circle_fit(predicted, level);
        const auto [f_bare, zeta_bare] = circle_fit(bare, level);
        EXPECT_NEAR(zeta_predicted, zeta_run, 0.01 * zeta_run) << level << " g";
        EXPECT_NEAR(f_predicted / f_run, 1.0, 2e-4) << level << " g";
        EXPECT_GT(zeta_run, zeta_bare + 0.001) << level << " g";
        EXPECT_LT(f_run, f_bare * (1.0 - 1e-4)) << level << " g: the joint softens the mode";
    }
}

}  // namespace
}  // namespace sb::bench

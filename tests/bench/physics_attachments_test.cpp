// The catalogue physics as attachments. The beam's air drag (physics.air_drag): the strip's
// describing function against the Fourier series of |v| v, the damping a response-controlled
// campaign identifies against the single-mode equivalent linearisation, its growth with the
// level, the prediction against the run, and how much the number of strips moves it. The
// microslip dashpot (physics.microslip): its describing function against the Fourier series
// of |v|^chi v, the prediction against the run.
#include "bench/physics_attachments.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bench/campaign.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/prediction.hpp"
#include "campaign_fixtures.hpp"
#include "core/units.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::bench {
namespace {

/// The linear paper-000 bench on nine frequencies (test::linear_paper000_bench) with air drag
/// of C_D = `drag_coefficient`.
CampaignConfig linear_bench(double drag_coefficient, int stations = 24) {
    auto config = test::linear_paper000_bench(9);
    config.physics.air_drag.drag_coefficient = drag_coefficient;
    config.physics.air_drag.stations = stations;
    return config;
}

/// The circle fit's damping ratio at a level.
double circle_fit_damping(const CampaignResult& result, double level_g) {
    for (const auto& d : result.recording.damping) {
        if (d.method == "circle-fit" && std::abs(d.level_g - level_g) < 1e-9) {
            return d.damping_ratio;
        }
    }
    ADD_FAILURE() << "no circle fit at " << level_g << " g";
    return 0.0;
}

/// The equivalent linearisation of the drag on the first mode alone: a strip s at modal
/// displacement phi_s q moves at V_s = w |phi_s| Q, its fundamental is that of a dashpot
/// (8 / 3 pi) k_s V_s, so the mass-normalised mode gains c = (8 / 3 pi) w Q sum k_s |phi_s|^3
/// and zeta by c / 2 w. The controller holds the control point's RMS acceleration at A g:
/// Q = sqrt(2) A g / (w^2 |phi_c|).
double single_mode_drag_damping(const CampaignConfig& config, double level_g) {
    const auto plan = plan_campaign(config, {});
    const auto& prepared = plan.arrangements.front();
    const auto& mode = prepared.basis.modes.front();
    EXPECT_NEAR(mode.frequency_hz, prepared.first_mode_hz, 1e-9) << "the first mode is driven";
    const double w = 2.0 * std::numbers::pi * mode.frequency_hz;
    const double phi_c = std::abs(structure::point_shapes(prepared.model, prepared.basis,
                                                          config.campaign.control_point)(2, 0));
    double sum = 0.0;
    for (const auto& strip : air_drag_attachments(config)) {
        const double phi =
            structure::point_shapes(prepared.model, prepared.basis, strip.point)(2, 0);
        sum += std::get<AirDragStrip>(strip.model).coefficient_kg_m() * std::pow(std::abs(phi), 3);
    }
    const double q = std::sqrt(2.0) * g_to_m_s2(level_g) / (w * w * phi_c);
    return 8.0 / (3.0 * std::numbers::pi) * w * q * sum / (2.0 * w);
}

TEST(AirDrag, AStripsDescribingFunctionIsTheFundamentalOfItsQuadraticForce) {
    const AirDragStrip strip(Eigen::Vector3d::UnitZ(), 0.37);
    const double f = 6.4, w = 2.0 * std::numbers::pi * f, v0 = 0.21;
    // The force over one period of v = v0 sin(w t), its first and third Fourier sines.
    const int n = 4096;
    double b1 = 0.0, b3 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double theta = 2.0 * std::numbers::pi * (i + 0.5) / n;
        PointMotion motion;
        motion.velocity_m_s = Eigen::Vector3d(0.3, -0.1, v0 * std::sin(theta));
        const PointLoad load = strip.step(motion, 1e-4);
        EXPECT_EQ(load.force_n.x(), 0.0);
        b1 += 2.0 / n * load.force_n.z() * std::sin(theta);
        b3 += 2.0 / n * load.force_n.z() * std::sin(3.0 * theta);
    }
    // F1 = -M a1 with a1 = i w v1: M = -F1 / (i w v1).
    const std::complex<double> expected = -b1 / (std::complex<double>(0.0, w) * v0);
    const auto value = strip.describing(w * v0, f);
    EXPECT_NEAR(value.apparent_mass_kg.real(), 0.0, 1e-15);
    EXPECT_NEAR(value.apparent_mass_kg.imag(), expected.imag(), 1e-6 * std::abs(expected));
    EXPECT_NEAR(value.h3_ratio, std::abs(b3 / b1), 1e-4);
    EXPECT_EQ(value.h2_ratio, 0.0);
}

TEST(AirDrag, TheCampaignsExtraDampingIsTheSingleModeLinearisationAndGrowsWithTheLevel) {
    CampaignContext context;
    context.threads = 2;
    const CampaignResult bare = run_campaign(linear_bench(0.0), context);
    const auto dragged = linear_bench(20.0);
    const CampaignResult with_drag = run_campaign(dragged, context);
    double added[2];
    for (int k = 0; k < 2; ++k) {
        const double level = k == 0 ? 1.0 : 3.0;
        added[k] = circle_fit_damping(with_drag, level) - circle_fit_damping(bare, level);
        const double expected = single_mode_drag_damping(dragged, level);
        // Response-controlled: each level is a linear system at its own amplitude, which the
        // circle fit sees exactly; 3 % for the other modes and the fit.
        EXPECT_NEAR(added[k], expected, 0.03 * expected) << level << " g";
    }
    EXPECT_NEAR(added[1] / added[0], 3.0, 0.09);
}

TEST(AirDrag, ThePredictionBalancesTheStripsAsTheRunStepsThem) {
    const auto config = linear_bench(20.0);
    CampaignContext context;
    context.threads = 2;
    const CampaignResult run = run_campaign(config, context);
    const CampaignResult predicted = predict_campaign(config, {});
    for (const double level : {1.0, 3.0}) {
        EXPECT_NEAR(circle_fit_damping(predicted, level), circle_fit_damping(run, level),
                    0.01 * circle_fit_damping(run, level))
            << level << " g";
    }
    for (const auto& p : predicted.recording.points) EXPECT_EQ(p.status, "predicted");
}

TEST(AirDrag, TwentyFourStripsGiveTheDampingOfNinetySixWithinHalfAPercent) {
    const double coarse = single_mode_drag_damping(linear_bench(20.0, 24), 1.0);
    const double fine = single_mode_drag_damping(linear_bench(20.0, 96), 1.0);
    EXPECT_NEAR(coarse / fine, 1.0, 0.005) << coarse << " " << fine;
}

TEST(Microslip, TheDashpotsDescribingFunctionIsTheFundamentalOfItsForce) {
    for (const double chi : {0.0, 0.5, 1.0, 1.5}) {
        const MicroslipDashpot dashpot(Eigen::Vector3d::UnitZ(), 3.0, chi, 0.1);
        const double f = 80.0, w = 2.0 * std::numbers::pi * f, v0 = 0.07;
        const int n = 8192;
        double b1 = 0.0, b3 = 0.0;
        for (int i = 0; i < n; ++i) {
            const double theta = 2.0 * std::numbers::pi * (i + 0.5) / n;
            PointMotion motion;
            motion.velocity_m_s = Eigen::Vector3d(0.0, 0.2, v0 * std::sin(theta));
            const PointLoad load = dashpot.step(motion, 1e-5);
            b1 += 2.0 / n * load.force_n.z() * std::sin(theta);
            b3 += 2.0 / n * load.force_n.z() * std::sin(3.0 * theta);
        }
        // F1 = -M a1 with v1 = -i v0 (v0 sin), a1 = i w v1 = w v0 and F1 = -i b1: Im M = b1 / w v0.
        const double expected = b1 / (w * v0);
        const auto value = dashpot.describing(w * v0, f);
        EXPECT_NEAR(value.apparent_mass_kg.imag(), expected, 1e-5 * std::abs(expected)) << chi;
        EXPECT_NEAR(value.h3_ratio, std::abs(b3 / b1), 1e-4) << chi;
    }
}

TEST(Microslip, ThePredictionBalancesTheDashpotAsTheRunStepsIt) {
    auto config = linear_bench(0.0);
    config.physics.microslip.point = "damper";
    config.physics.microslip.damping_n_s_per_m = 0.05;
    config.physics.microslip.exponent = 0.5;
    CampaignContext context;
    context.threads = 2;
    const CampaignResult bare = run_campaign(linear_bench(0.0), context);
    const CampaignResult run = run_campaign(config, context);
    const CampaignResult predicted = predict_campaign(config, {});
    double added[2];
    for (int k = 0; k < 2; ++k) {
        const double level = k == 0 ? 1.0 : 3.0;
        EXPECT_NEAR(circle_fit_damping(predicted, level), circle_fit_damping(run, level),
                    0.01 * circle_fit_damping(run, level))
            << level << " g";
        added[k] = circle_fit_damping(run, level) - circle_fit_damping(bare, level);
        EXPECT_GT(added[k], 0.0) << level << " g";
    }
    // At a response-controlled level the dashpot's damping grows like the amplitude^chi.
    EXPECT_NEAR(added[1] / added[0], std::sqrt(3.0), 0.03 * std::sqrt(3.0));
}

TEST(CubicSpring, ItsDescribingFunctionIsTheFundamentalOfItsForce) {
    const Eigen::Vector3d rest(0.5, 0.0, 0.01);
    const CubicSpring spring(Eigen::Vector3d::UnitZ(), 4000.0, rest);
    const double f = 6.4, w = 2.0 * std::numbers::pi * f, u0 = 0.02;
    const int n = 4096;
    double b1 = 0.0, b3 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double theta = 2.0 * std::numbers::pi * (i + 0.5) / n;
        PointMotion motion;
        motion.position_m = rest + Eigen::Vector3d(0.003, 0.0, u0 * std::sin(theta));
        const PointLoad load = spring.step(motion, 1e-4);
        b1 += 2.0 / n * load.force_n.z() * std::sin(theta);
        b3 += 2.0 / n * load.force_n.z() * std::sin(3.0 * theta);
    }
    // u1 = -i u0, a1 = -w^2 u1, F1 = -i b1: M = -F1 / a1 = b1 / (w^2 u0), real.
    const auto value = spring.describing(w * w * u0, f);
    EXPECT_NEAR(value.apparent_mass_kg.real(), b1 / (w * w * u0),
                1e-6 * std::abs(b1 / (w * w * u0)));
    EXPECT_EQ(value.apparent_mass_kg.imag(), 0.0);
    EXPECT_NEAR(value.h3_ratio, std::abs(b3 / b1), 1e-4);
}

TEST(CubicSpring, ThePredictionBalancesItAsTheRunStepsItAndTheModeHardens) {
    // A 0.5 %-damped mode on a grid fine enough for the prediction, which does not refine it.
    const auto fine = [](CampaignConfig c) {
        c.campaign.frequencies.count = 25;
        c.campaign.frequencies.grid_damping_ratio = 0.005;
        return c;
    };
    auto config = fine(linear_bench(0.0));
    config.physics.cubic_spring.point = "damper";
    config.physics.cubic_spring.stiffness_n_per_m3 = 5000.0;
    CampaignContext context;
    context.threads = 2;
    const CampaignResult bare = run_campaign(fine(linear_bench(0.0)), context);
    const CampaignResult run = run_campaign(config, context);
    const CampaignResult predicted = predict_campaign(config, {});
    const auto circle_fit = [](const CampaignResult& r, double level) {
        for (const auto& d : r.recording.damping) {
            if (d.method == "circle-fit" && std::abs(d.level_g - level) < 1e-9) return d;
        }
        ADD_FAILURE() << "no circle fit at " << level << " g";
        return identification::DampingRow{};
    };
    const auto frequency = [&](const CampaignResult& r, double level) {
        return circle_fit(r, level).natural_frequency_hz;
    };
    double shift[2];
    for (int k = 0; k < 2; ++k) {
        const double level = k == 0 ? 1.0 : 3.0;
        EXPECT_NEAR(frequency(predicted, level) / frequency(run, level), 1.0, 2e-4) << level;
        // The spring adds no damping: the run's is the prediction's. Read a step late, its
        // tangent stiffness damped the run 0.44 % less at 1 g and 4.2 % less at 3 g (as U^2);
        // read at the step's end, 0.004 % and 0.49 %, as U^4: the square of the spring's
        // share of the force, the order of the single-harmonic balance's error (its third
        // harmonic is a third of its fundamental).
        const double zeta = circle_fit(predicted, level).damping_ratio;
        EXPECT_NEAR(circle_fit(run, level).damping_ratio, zeta, (k == 0 ? 1e-3 : 1e-2) * zeta)
            << level;
        shift[k] = frequency(run, level) / frequency(bare, level) - 1.0;
        EXPECT_GT(shift[k], 0.0) << level << " g";
    }
    // The equivalent stiffness (3/4) k3 U^2 grows with the square of the amplitude.
    EXPECT_NEAR(shift[1] / shift[0], 9.0, 0.5);
}

}  // namespace
}  // namespace sb::bench

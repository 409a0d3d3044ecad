// The electrodynamic shaker (physics.shaker): its coil and suspension against the Fourier
// series of their own stepped load, its state, and on the linear paper-000 bench the two FRFs
// a rig records: referenced to the force into the structure, the structure's own (the
// armature, the suspension and the back-EMF stay on the shaker's side), referenced to the
// amplifier's voltage, damped by the back-EMF as a single-mode closed form says, in the
// prediction and in the run alike.
#include "bench/shaker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <iostream>
#include <numbers>

#include "bench/campaign.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/prediction.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"
#include "identification/damping_curve.hpp"
#include "structure/frf.hpp"

namespace sb::bench {
namespace {

namespace id = identification;

ShakerSpec small_shaker() {
    ShakerSpec s;
    s.force_factor_n_per_a = 12.0;
    s.coil_resistance_ohm = 3.0;
    s.coil_inductance_h = 2e-3;
    s.suspension_stiffness_n_per_m = 4000.0;
    s.suspension_damping_n_s_per_m = 3.0;
    return s;
}

/// The coil stepped through three periods of u = U cos(theta) from rest (its current settles
/// in the first), the last period's fundamental of its force as the complex amplitude of
/// e^(i theta).
std::complex<double> stepped_fundamental(ShakerCoil coil, double amplitude_m, double frequency_hz) {
    const Eigen::Vector3d rest(0.16, 0.0, 0.0);
    const int n = 20000;
    const double w = 2.0 * std::numbers::pi * frequency_hz;
    const double dt = 1.0 / (frequency_hz * n);
    std::complex<double> first = 0.0;
    for (int period = 0; period < 3; ++period) {
        for (int i = 0; i < n; ++i) {
            const double theta = 2.0 * std::numbers::pi * i / n;
            PointMotion motion;
            motion.position_m = rest + Eigen::Vector3d(0.0, 0.0, amplitude_m * std::cos(theta));
            motion.velocity_m_s = Eigen::Vector3d(0.0, 0.0, -w * amplitude_m * std::sin(theta));
            motion.acceleration_m_s2 =
                Eigen::Vector3d(0.0, 0.0, -w * w * amplitude_m * std::cos(theta));
            // The load applies at the step's end, theta + dtheta.
            const double f = coil.step(motion, dt).force_n.z();
            const double end = theta + 2.0 * std::numbers::pi / n;
            if (period == 2) first += 2.0 / n * f * std::exp(std::complex<double>(0.0, -end));
        }
    }
    return first;
}

TEST(ShakerCoil, ItsDescribingFunctionIsTheFundamentalOfItsSteppedLoad) {
    const ShakerCoil coil(Eigen::Vector3d::UnitZ(), small_shaker(), Eigen::Vector3d(0.16, 0, 0));
    // 6.4 Hz: the coil's lag w L / R is 0.03; 200 Hz: 0.84, the current well behind the motion.
    for (const double f : {6.4, 200.0}) {
        const double w = 2.0 * std::numbers::pi * f, u = 1e-3;
        const auto value = coil.describing(w * w * u, f);
        // F1 = M w^2 U (a1 = -w^2 U, F1 = -M a1).
        const std::complex<double> expected = stepped_fundamental(coil, u, f) / (w * w * u);
        EXPECT_NEAR(value.apparent_mass_kg.real(), expected.real(), 2e-3 * std::abs(expected)) << f;
        EXPECT_NEAR(value.apparent_mass_kg.imag(), expected.imag(), 2e-3 * std::abs(expected)) << f;
        EXPECT_LT(value.apparent_mass_kg.imag(), 0.0) << "the back-EMF dissipates";
    }
}

TEST(ShakerCoil, ItsCurrentIsItsStateAndAnotherModelsStateIsRefused) {
    ShakerCoil coil(Eigen::Vector3d::UnitZ(), small_shaker(), Eigen::Vector3d::Zero());
    PointMotion motion;
    motion.velocity_m_s = Eigen::Vector3d(0.0, 0.0, 0.2);
    for (int i = 0; i < 10; ++i) coil.step(motion, 1e-4);
    // L di/dt + R i = -Bl v: after 10 steps of 1e-4 s (1.5 times the time constant L / R),
    // i = -Bl v / R (1 - e^(-1.5)).
    EXPECT_NEAR(coil.current_a(), -12.0 * 0.2 / 3.0 * (1.0 - std::exp(-1.5)), 1e-12);
    ShakerCoil resumed(Eigen::Vector3d::UnitZ(), small_shaker(), Eigen::Vector3d::Zero());
    resumed.restore(coil.state());
    EXPECT_EQ(resumed.step(motion, 1e-4).force_n, coil.step(motion, 1e-4).force_n);
    AttachmentState other;
    other.sliders = std::vector<double>(3, 0.0);
    EXPECT_THROW(resumed.restore(other), std::invalid_argument);
}

/// The linear paper-000 bench driven through `shaker`, 25 frequencies over ±4 % of the mode.
CampaignConfig shaker_bench(const ShakerSpec& shaker) {
    auto config = test::linear_paper000_bench(25);
    config.physics.shaker = shaker;
    return config;
}

/// The circle fit of a level's FRF of the control channel over `reference` (a channel index).
std::pair<double, double> circle_fit(const CampaignResult& result, double level_g,
                                     std::size_t reference) {
    id::Recording rec;
    rec.info.excitation = "force";
    auto ref = result.recording.channels[reference];
    ref.role = id::ChannelRole::reference;
    auto control = result.recording.channels[1];
    rec.channels = {ref, control};
    for (const auto& p : result.recording.points) {
        if (std::abs(p.level_g - level_g) > 1e-9) continue;
        id::PointRow row = p;
        row.values = {p.values[reference], p.values[1]};
        rec.points.push_back(row);
    }
    const auto levels = id::identify_recording(rec);
    EXPECT_EQ(levels.size(), 1U);
    EXPECT_TRUE(levels.front().circle_fit.ok()) << levels.front().circle_fit.message;
    return {levels.front().circle_fit.natural_frequency_hz,
            levels.front().circle_fit.damping_ratio};
}

TEST(Shaker, TheForceReferencedFrfIsTheStructuresTheVoltageReferencedOneIsDampedByTheBackEmf) {
    // A small shaker through a voltage amplifier: the back-EMF's dashpot Bl^2 / R = 7.2 N s/m
    // at the drive point, 160 mm from the clamp, about four times the beam's damping in the
    // voltage-referenced FRF (as on the RubBeR beam); a 50 g armature.
    ShakerSpec shaker = small_shaker();
    shaker.force_factor_n_per_a = 6.0;
    shaker.coil_resistance_ohm = 5.0;
    shaker.suspension_stiffness_n_per_m = 0.0;
    shaker.suspension_damping_n_s_per_m = 0.0;
    shaker.armature_mass_kg = 0.05;
    const auto config = shaker_bench(shaker);
    // Single-mode closed forms, from the bench's modes alone (not the shaker's code): the
    // model's mode f0 carries the armature, phi_d^2 = 2 zeta0 |H_dd(f0)| at the drive point.
    // Voltage-referenced: the coil's Bl^2 / (R + i w L) at the drive point, a dashpot
    // c = Bl^2 R / |Z|^2 (2 zeta w += c phi_d^2) and a negative mass Bl^2 L / |Z|^2 (w up by
    // half its phi_d^2). Force-referenced: the beam without the armature, whose modal damping
    // (set on the model with it) becomes zeta0 f_bare / f0 at the bare mode.
    const auto plan = plan_campaign(config, {});
    const auto& prepared = plan.arrangements.front();
    const double f0 = prepared.basis.modes.front().frequency_hz;
    const double w0 = 2.0 * std::numbers::pi * f0;
    const double zeta0 = config.structure.damping.default_ratio;
    const Eigen::Vector3d d = config.structure.excitation.direction.normalized();
    const std::string& drive = config.structure.excitation.point;
    const double phi_d2 = 2.0 * zeta0 *
                          std::abs(structure::modal_accelerance(prepared.model, prepared.basis,
                                                                drive, d, drive, d, f0));
    const double bl2 = shaker.force_factor_n_per_a * shaker.force_factor_n_per_a;
    const double z2 =
        std::norm(std::complex<double>(shaker.coil_resistance_ohm, w0 * shaker.coil_inductance_h));
    const double zeta_voltage = zeta0 + bl2 * shaker.coil_resistance_ohm / z2 * phi_d2 / (2.0 * w0);
    const double f_voltage = f0 * (1.0 + 0.5 * bl2 * shaker.coil_inductance_h / z2 * phi_d2);
    const double f_bare = 6.3716;  // the rigid bench's mode (docs/validation.md)
    const double zeta_force = zeta0 * f_bare / f0;
    ASSERT_GT(zeta_voltage, 3.0 * zeta0) << "the back-EMF must matter in this test";
    ASSERT_LT(f0, f_bare * (1.0 - 1e-3)) << "so must the armature";

    CampaignContext context;
    context.threads = 2;
    const CampaignResult run = run_campaign(config, context);
    const CampaignResult predicted = predict_campaign(config, {});
    ASSERT_EQ(run.recording.channels.front().name, "voltage");
    ASSERT_EQ(run.recording.channels.back().name, "force");
    const std::size_t force = run.recording.channels.size() - 1;
    for (const auto* result : {&predicted, &run}) {
        const char* which = result == &run ? "run" : "prediction";
        for (const double level : {1.0, 3.0}) {
            const auto [f_v, zeta_v] = circle_fit(*result, level, 0);
            const auto [f_f, zeta_f] = circle_fit(*result, level, force);
            std::cout << which << " " << level << " g: voltage-referenced " << f_v << " Hz, "
                      << zeta_v << " (closed form " << f_voltage << " Hz, " << zeta_voltage
                      << "); force-referenced " << f_f << " Hz, " << zeta_f << " (" << f_bare
                      << " Hz, " << zeta_force << ")\n";
            EXPECT_NEAR(zeta_f, zeta_force, 0.005 * zeta_force) << which << " " << level << " g";
            EXPECT_NEAR(f_f / f_bare, 1.0, 2e-4) << which << " " << level << " g";
            EXPECT_NEAR(zeta_v, zeta_voltage, 0.02 * zeta_voltage) << which << " " << level;
            EXPECT_NEAR(f_v / f_voltage, 1.0, 5e-4) << which << " " << level << " g";
        }
    }
}

TEST(Shaker, AShakerDrivesAForceExcitationWithAPositiveResistance) {
    const std::string text =
        test::paper000_h0_with({}) + "\n[physics.shaker]\nforce_factor_n_per_a = 10\n";
    const auto config = load_campaign_config_text(text, "shaker.toml");
    EXPECT_TRUE(config.physics.shaker.on());
    try {
        (void)load_campaign_config_text(text + "coil_resistance_ohm = -1\n", "shaker.toml");
        ADD_FAILURE() << "a negative resistance was accepted";
    } catch (const config::ConfigException& e) {
        // Located at its line: the one after the text's last.
        const auto line = std::count(text.begin(), text.end(), '\n') + 1;
        EXPECT_NE(std::string(e.what()).find("shaker.toml:" + std::to_string(line) +
                                             ":23: physics.shaker.coil_resistance_ohm"),
                  std::string::npos)
            << e.what();
    }
    auto base = config;
    try {
        apply_overrides(
            base, {"structure.excitation.kind=\"base\"", "structure.excitation.support=\"root\""});
        ADD_FAILURE() << "a shaker driving a base was accepted";
    } catch (const config::ConfigException& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("physics.shaker.force_factor_n_per_a"), std::string::npos) << what;
        EXPECT_NE(what.find("force-excited"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace sb::bench

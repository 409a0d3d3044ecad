// The configs shipped in configs/ load and give the reference frequencies of design.md.
#include <gtest/gtest.h>

#include <string>

#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::bench {
namespace {

/// First mode whose effective mass is mostly along the excitation direction z: the first
/// bending mode the shaker drives.
double first_driven_frequency_hz(const std::string& config_name) {
    const auto config =
        load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/" + config_name);
    const auto model = structure::build_linear_model(config.structure, config.base_dir);
    const auto basis = structure::compute_modes(model, config.structure.damping, 6);
    for (const auto& mode : basis.modes) {
        const auto& m = mode.effective_mass_kg;
        if (m.z() > m.x() && m.z() > m.y()) {
            return mode.frequency_hz;
        }
    }
    ADD_FAILURE() << "no mode driven along z in " << config_name;
    return 0.0;
}

TEST(ShippedConfigs, Paper000BeamWithDamperAsRigidMassHasItsFirstModeNear6p37Hz) {
    const double f = first_driven_frequency_hz("paper000-beam.toml");
    EXPECT_GE(f, 6.30);
    EXPECT_LE(f, 6.45);
}

TEST(ShippedConfigs, Paper000BareBeamHas8p50Hz) {
    // design.md: bare beam 8.50 Hz; the issue allows 0.5 %.
    EXPECT_NEAR(first_driven_frequency_hz("paper000-bare-beam.toml"), 8.50, 0.005 * 8.50);
}

TEST(ShippedConfigs, Paper002ClampedPinnedBeamHasItsFirstModeNear144p7Hz) {
    const double f = first_driven_frequency_hz("paper002-beam.toml");
    EXPECT_GE(f, 144.0);
    EXPECT_LE(f, 146.0);
}

/// The paper-003 rig's first mode with its sphere as a rigid mass, with the clamps as `kind`
/// ("spring": the config's hinges with rotational springs; "clamped"; "pinned").
double paper003_first_mode_hz(const std::string& kind) {
    auto config = load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper003-beam.toml");
    if (kind != "spring") {
        std::erase_if(config.structure.beam.supports,
                      [](const auto& s) { return s.kind == structure::SupportKind::elastic; });
        for (auto& s : config.structure.beam.supports) {
            s.kind = kind == "clamped" ? structure::SupportKind::clamped
                                       : structure::SupportKind::pinned;
        }
    }
    return plan_campaign(config, {}).arrangements.front().first_mode_hz;
}

TEST(ShippedConfigs, Paper003BeamHasTheRigs46p62HzBetweenItsHingedAndClampedModes) {
    // docs/validation.md, paper 003: the rig's mode at 5 g, between a hinge's and a clamp's.
    EXPECT_NEAR(paper003_first_mode_hz("spring"), 46.62, 0.0005 * 46.62);
    EXPECT_NEAR(paper003_first_mode_hz("pinned"), 41.0, 1.0);
    EXPECT_NEAR(paper003_first_mode_hz("clamped"), 88.0, 1.5);
}

}  // namespace
}  // namespace sb::bench

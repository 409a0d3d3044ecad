// The configs shipped in configs/ load and give the reference frequencies of design.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/linear_estimate.hpp"
#include "core/units.hpp"
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

/// Paper 002's damper configs without their damper: the empty beam of the paper's Fig. 3.
CampaignConfig paper002_empty_beam(const std::string& name) {
    auto config = load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/" + name);
    config.campaign.dampers.clear();
    config.structure.beam.masses.clear();
    return config;
}

TEST(ShippedConfigs,
     Paper002DamperConfigsGiveTheEmptyBeamsMeasured142HzAnd66p5MetresPerSecondSquared) {
    // docs/validation.md, paper 002: the modulus is chosen for the measured 142 Hz, and the
    // fixed base acceleration at the driven pin for the measured 66.5 m/s^2 at the damper's
    // place at that resonance (Table 2, "without PD").
    for (const std::string name : {"paper002-nogrid.toml", "paper002-grid.toml"}) {
        const auto config = paper002_empty_beam(name);
        const auto plan = plan_campaign(config, {});
        const auto& p = plan.arrangements.front();
        EXPECT_NEAR(p.first_mode_hz, 142.0, 0.001 * 142.0) << name;
        double peak = 0.0;  // the transmissibility's peak, within 1e-5 of the mode
        for (double r = 0.999; r <= 1.001; r += 1e-5) {
            peak = std::max(peak, linear_response_per_unit_input(p.estimate_model, p.estimate_basis,
                                                                 p.structure.excitation, "damper",
                                                                 r * p.first_mode_hz));
        }
        ASSERT_EQ(config.campaign.drive.amplitudes.size(), 1U);
        EXPECT_NEAR(peak * config.campaign.drive.amplitudes.front(), 66.5, 0.005 * 66.5) << name;
    }
}

TEST(ShippedConfigs, Paper002DampersHoldTheMassesOfTable1) {
    // Table 1 at 90 % fill: 189 g without the grid, 153 g with it, of 2 mm balls.
    for (const auto& [name, grams, grid] :
         {std::tuple{"paper002-nogrid.toml", 189.0, false}, {"paper002-grid.toml", 153.0, true}}) {
        const auto config = load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/" + name);
        const auto& d = config.campaign.dampers.front();
        EXPECT_NEAR(particle_mass_kg(d, 1) * 1e3, grams, 0.05) << name;
        EXPECT_EQ(d.enclosure.rods.enabled, grid) << name;
    }
}

/// Half the peak-to-peak tip displacement of the last period of a paper-004 run.
double last_tip_half_swing_m(const CampaignResult& result) {
    const auto& envelope = result.sweeps.front().transient_envelope;
    const auto& channels = result.sweeps.front().transient_channels;
    const std::size_t n = channels.size();
    const std::size_t tip = static_cast<std::size_t>(
        std::find(channels.begin(), channels.end(), "tip") - channels.begin());
    EXPECT_LT(tip, n);
    std::vector<double> cells;
    std::stringstream in(envelope.back());
    std::string cell;
    while (std::getline(in, cell, ',')) cells.push_back(std::stod(cell));
    return (cells[2 + n + tip] - cells[2 + tip]) / 2.0;
}

TEST(ShippedConfigs, Paper004HeldSpheresGiveThePapers22CentimetresAndFreedOnesCutThem) {
    // docs/validation.md, paper 004: the dashpot is chosen for a locked transmissibility of
    // 22 at the drive (+-0.22 m at 10 mm); after 15 s from rest the free vibration has
    // decayed to e^-7.5 of the start. Freeing all three spheres at 5 s cuts the swing below
    // a third of it (0.042 m measured with the 100 mm gap; the paper: about 0.03 m).
    const std::string path = std::string(SB_SOURCE_DIR) + "/configs/paper004-4dof.toml";
    CampaignConfig config = load_campaign_config(path);
    CampaignContext context;
    context.threads = 1;
    const double held = last_tip_half_swing_m(run_campaign(config, context));
    EXPECT_NEAR(held, 0.22, 0.005 * 0.22);
    for (const std::string name : {"g1", "g2", "g3"}) {
        set_value_text(config, "dampers." + name + ".lock.release_time_s", "5.0", "test");
    }
    const double freed = last_tip_half_swing_m(run_campaign(config, context));
    EXPECT_LT(freed, held / 3.0);
}

/// The column `name` of the time histories of a run's single sweep.
std::vector<double> series_column(const CampaignResult& result, const std::string& name) {
    const auto& channels = result.sweeps.front().transient_channels;
    const auto column = static_cast<std::size_t>(std::find(channels.begin(), channels.end(), name) -
                                                 channels.begin());
    EXPECT_LT(column, channels.size()) << name;
    std::vector<double> out;
    for (const auto& line : result.sweeps.front().transient_series) {
        std::vector<std::string> cells;
        std::stringstream in(line);
        for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
        out.push_back(std::stod(cells.at(column + 1)));  // the time comes first
    }
    return out;
}

TEST(ShippedConfigs, Paper004CantileverCarriesItsHeldBedAsTheRigidMassModelDoes) {
    // The 0.49 kg of held granules outweigh the first mode's 0.40 kg at the tip: as a load one
    // step late the coupling diverges (within a millisecond with four modes), as rigid mass of
    // the beam it follows the model with the bed as a rigid mass. That model places the bed's
    // centre of gravity from a packing estimate, the held bed where it settled.
    const std::string path = std::string(SB_SOURCE_DIR) + "/configs/paper004-cantilever.toml";
    CampaignConfig config = load_campaign_config(path);
    set_value_text(config, "campaign.transient.duration_s", "0.75", "test");
    set_value_text(config, "structure.modes", "4", "test");
    // Undamped: the held bed adds mass to the beam and keeps its damping matrix, the rigid
    // model gives the loaded modes the config's ratios; without damping both are the same.
    // The contact stiffness the config's own run chooses (automatic sizing would take the
    // undamped resonance's unbounded response for the impact speed).
    set_value_text(config, "structure.damping.default_ratio", "0.0", "test");
    set_value_text(config, "dampers.empid.contact.normal_stiffness", "2.8e7", "test");
    CampaignContext context;
    context.threads = 1;
    const std::vector<double> held = series_column(run_campaign(config, context), "tip");
    config.campaign.dampers.front().model = DamperSpec::Model::rigid;
    config.campaign.channels.pop_back();  // the rigid bed applies no force of its own
    const std::vector<double> rigid = series_column(run_campaign(config, context), "tip");
    ASSERT_EQ(held.size(), rigid.size());
    // The held bed's weight bends the beam statically (18 mm); the rigid model's particles are
    // weightless structure (gravity acts on particles only).
    const double sag_m = held.front() - rigid.front();
    EXPECT_LT(sag_m, -0.01);
    double largest = 0.0, worst = 0.0;
    for (std::size_t k = 0; k < held.size(); ++k) {
        largest = std::max(largest, std::abs(rigid[k]));
        worst = std::max(worst, std::abs(held[k] - sag_m - rigid[k]));
    }
    EXPECT_GT(largest, 0.04);  // two periods from rest at resonance
    // 0.71 % measured: the rigid model places the bed from a packing estimate (0.6 of the
    // cavity, a 37 mm bed) where the poured bed settled.
    EXPECT_LT(worst, 0.01 * largest) << "largest " << largest;
}

}  // namespace
}  // namespace sb::bench

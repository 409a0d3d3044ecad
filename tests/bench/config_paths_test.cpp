// Campaign config values by dotted path: changed after loading as if the file held them,
// defaults that follow other keys resolved after the change, and every violation a leaf
// module can report placed at a declared key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bench/campaign_config.hpp"
#include "bench/config_schema.hpp"
#include "bench/frequency_grid.hpp"
#include "bench/resolved_config.hpp"
#include "config/errors.hpp"
#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::bench {
namespace {

CampaignConfig builtin() {
    return load_campaign_config_text(builtin_config_text(), kBuiltinConfigName);
}

/// The formatted errors of `change`, which must throw config::ConfigException.
template <class Change>
std::vector<std::string> errors_of(Change change) {
    try {
        change();
    } catch (const config::ConfigException& e) {
        std::vector<std::string> out;
        for (const auto& error : e.errors()) out.push_back(error.format());
        return out;
    }
    ADD_FAILURE() << "the change was accepted";
    return {};
}

double first_driven_mode_hz(const CampaignConfig& config) {
    const auto model = structure::build_linear_model(config.structure, config.base_dir);
    const auto basis = structure::compute_modes(model, config.structure.damping, 6);
    return bench::first_driven_mode_hz(basis, Eigen::Vector3d::UnitZ());
}

TEST(ConfigPaths, EveryDeclaredValueOfTheBuiltInConfigCanBeReadByItsPath) {
    const CampaignConfig config = builtin();
    EXPECT_EQ(std::get<double>(get_value(config, "dampers.pd.contact.sliding_friction")), 0.6);
    EXPECT_EQ(std::get<double>(get_value(config, "structure.beam.youngs_modulus_pa")), 72e9);
    EXPECT_EQ(std::get<double>(get_value(config, "structure.beam.masses[5].mass_kg")), 0.0238);
    EXPECT_EQ(std::get<double>(get_value(config, "structure.beam.points.damper")), 0.533);
    EXPECT_EQ(std::get<std::string>(get_value(config, "arrangements.H-0.oscillation")),
              "horizontal");
    EXPECT_TRUE(std::holds_alternative<std::monostate>(
        get_value(config, "dampers.pd.contact.normal_stiffness")));
}

TEST(ConfigPaths, ScalingTheStiffnessOfTheBeamByFourDoublesItsFirstMode) {
    // Young's and shear moduli together scale every stiffness term, so every frequency
    // scales exactly with their square root.
    CampaignConfig config = builtin();
    const double before = first_driven_mode_hz(config);
    set_value(config, "structure.beam.youngs_modulus_pa", 4.0 * 72e9, "test");
    set_value(config, "structure.beam.shear_modulus_pa", 4.0 * 27e9, "test");
    EXPECT_NEAR(first_driven_mode_hz(config) / before, 2.0, 1e-9);
}

TEST(ConfigPaths, WallFrictionFollowsAParticleFrictionChangedAfterLoading) {
    CampaignConfig config = builtin();
    set_value_text(config, "dampers.pd.contact.sliding_friction", "0.3", "--set");
    const auto& contact = config.campaign.dampers.front().contact;
    EXPECT_EQ(contact.particle_particle.sliding_friction, 0.3);
    EXPECT_EQ(contact.particle_wall().sliding_friction, 0.3);
    EXPECT_EQ(std::get<double>(get_value(config, "dampers.pd.contact.wall_sliding_friction")), 0.3);
    // Once given, the wall's own value stays.
    set_value_text(config, "dampers.pd.contact.wall_sliding_friction", "0.2", "--set");
    set_value_text(config, "dampers.pd.contact.sliding_friction", "0.5", "--set");
    EXPECT_EQ(config.campaign.dampers.front().contact.particle_wall().sliding_friction, 0.2);
}

/// A part of the enclosure that may have its own coefficients and material: the obstacle
/// grid's rods, the lateral surface.
struct WallPart {
    std::string prefix;  ///< of its contact keys: rod_, side_
    std::optional<dem::PairProperties> dem::ContactOptions::*pair;
    std::optional<dem::Material> dem::ContactOptions::*material;
};

class OwnWallPart : public ::testing::TestWithParam<WallPart> {};

TEST_P(OwnWallPart, FollowsTheWallsUntilGivenItsOwnValues) {
    const WallPart& part = GetParam();
    const std::string key = "dampers.pd.contact." + part.prefix;
    CampaignConfig config = builtin();
    const auto& contact = config.campaign.dampers.front().contact;
    // the wall's coefficients and material serve it
    EXPECT_FALSE(contact.contact_options(1e4).*part.pair);
    EXPECT_FALSE(contact.contact_options(1e4).*part.material);
    set_value_text(config, "dampers.pd.contact.wall_restitution", "0.7", "--set");
    set_value_text(config, "dampers.pd.contact.wall_youngs_modulus_pa", "70e9", "--set");
    EXPECT_EQ(std::get<double>(get_value(config, key + "restitution")), 0.7);
    EXPECT_EQ(std::get<double>(get_value(config, key + "youngs_modulus_pa")), 70e9);
    set_value_text(config, key + "restitution", "0.4", "--set");
    set_value_text(config, key + "youngs_modulus_pa", "3e9", "--set");
    const auto options = contact.contact_options(1e4);
    const auto& pair = options.*part.pair;
    const auto& material = options.*part.material;
    ASSERT_TRUE(pair);
    EXPECT_EQ(pair->restitution, 0.4);
    // What is not given follows the wall's.
    EXPECT_EQ(pair->sliding_friction, options.particle_wall.sliding_friction);
    ASSERT_TRUE(material);
    EXPECT_EQ(material->youngs_modulus_pa, 3e9);
    EXPECT_EQ(material->poisson_ratio, options.wall_material.poisson_ratio);
    EXPECT_EQ(options.particle_wall.restitution, 0.7);
    EXPECT_EQ(options.wall_material.youngs_modulus_pa, 70e9);
    EXPECT_FALSE(
        errors_of([&] { set_value_text(config, key + "restitution", "1.5", "--set"); }).empty());
    EXPECT_FALSE(
        errors_of([&] { set_value_text(config, key + "poisson_ratio", "0.6", "--set"); }).empty());
}

INSTANTIATE_TEST_SUITE_P(ConfigPaths, OwnWallPart,
                         ::testing::Values(WallPart{"rod_", &dem::ContactOptions::particle_rod,
                                                    &dem::ContactOptions::rod_material},
                                           WallPart{"side_", &dem::ContactOptions::particle_side,
                                                    &dem::ContactOptions::side_material}),
                         [](const ::testing::TestParamInfo<WallPart>& param) {
                             return param.param.prefix == "rod_" ? std::string("Rods")
                                                                 : std::string("LateralSurface");
                         });

TEST(ConfigPaths, TheDiameterScatterIsAddressedByItsDottedPathWithinItsBound) {
    CampaignConfig config = builtin();
    const std::string path = "dampers.pd.particles.diameter_scatter";
    EXPECT_EQ(std::get<double>(get_value(config, path)), 0.0);
    apply_overrides(config, {path + "=0.05"});
    EXPECT_EQ(config.campaign.dampers.front().particles.diameter_scatter, 0.05);
    set_value_text(config, path, "0.2", "--set");
    EXPECT_EQ(std::get<double>(get_value(config, path)), 0.2);
    for (const std::string value : {"-0.1", "0.3"}) {
        EXPECT_EQ(errors_of([&] { set_value_text(config, path, value, "--set"); }),
                  (std::vector<std::string>{
                      "--set: " + path + " = " + value +
                      ": must be in [0, 0.2] (relative standard deviation of the sphere "
                      "diameters [-])"}));
        EXPECT_EQ(config.campaign.dampers.front().particles.diameter_scatter, 0.2);
    }
}

TEST(ConfigPaths, AMassGivenByItsPointMovesWithThePoint) {
    CampaignConfig config = builtin();
    set_value_text(config, "structure.beam.points.acc4", "0.5", "--set");
    const auto beam = config.structure.beam.resolved();
    bool found = false;
    for (const auto& m : beam.masses) {
        if (m.name == "accelerometer 4") {
            EXPECT_EQ(m.x_m, 0.5);
            found = true;
        }
    }
    EXPECT_TRUE(found);
}

TEST(ConfigPaths, AnOutOfBoundValueIsRefusedNamingTheKeyAndItsOrigin) {
    CampaignConfig config = builtin();
    EXPECT_EQ(errors_of([&] { set_value_text(config, "structure.beam.length_m", "-1", "--set"); }),
              (std::vector<std::string>{
                  "--set: structure.beam.length_m = -1: must be > 0 (beam length [m])"}));
    EXPECT_EQ(config.structure.beam.length_m, 0.543);
}

TEST(ConfigPaths, AValueBreakingACheckAcrossModulesIsRefusedAndUndone) {
    CampaignConfig config = builtin();
    // The damper's point must exist: renaming it to nothing is refused as the file would be.
    const auto errors =
        errors_of([&] { set_value_text(config, "dampers.pd.point", "nowhere", "--set"); });
    ASSERT_EQ(errors.size(), 2u);
    EXPECT_EQ(errors[0],
              "--set: dampers.pd.point = \"nowhere\": must name a point of the "
              "structure (named point the damper is attached to)");
    // The enclosure mass, still in the file, is no longer at the damper's point.
    EXPECT_NE(errors[1].find(":30:18: dampers.pd.enclosure_mass = \"enclosure\""),
              std::string::npos)
        << errors[1];
    EXPECT_EQ(config.campaign.dampers.front().point, "damper");
    // A beam thicker than it is wide, across two keys of the structure module.
    EXPECT_EQ(errors_of([&] {
                  set_value(config, "structure.beam.thickness_m", 0.06, "calibration");
              }).size(),
              1u);
}

TEST(ConfigPaths, ApplyOverridesTakesKeyEqualsValueInOrder) {
    CampaignConfig config = builtin();
    apply_overrides(config, {"campaign.levels_g=[0.5]", "campaign.point_start=linear-steady-state",
                             "dampers.pd.contact.normal_stiffness=2e5"});
    EXPECT_EQ(config.campaign.levels_g, std::vector<double>{0.5});
    EXPECT_EQ(config.campaign.point_start, CampaignSpec::PointStart::linear_steady_state);
    EXPECT_EQ(config.campaign.dampers.front().contact.normal_stiffness, 2e5);
    EXPECT_EQ(errors_of([&] { apply_overrides(config, {"campaign.seed"}); }).size(), 1u);
}

TEST(ConfigPaths, AKeySwitchedOnByALaterOverrideIsAcceptedInAnyOrder) {
    // The joint's macroslip displacement applies only once its stiffness is set: given first,
    // it waits for the stiffness instead of being refused.
    const std::vector<std::string> joint{"physics.iwan_joint.macroslip_displacement_m=0.01",
                                         "physics.iwan_joint.point=damper",
                                         "physics.iwan_joint.stiffness_n_per_m=10"};
    for (const auto& order : {joint, std::vector<std::string>(joint.rbegin(), joint.rend())}) {
        CampaignConfig config = builtin();
        apply_overrides(config, order);
        EXPECT_EQ(config.physics.iwan_joint.macroslip_displacement_m, 0.01);
        EXPECT_EQ(config.physics.iwan_joint.stiffness_n_per_m, 10.0);
    }
    // Nothing switches it on: still refused, naming why, and nothing changed.
    CampaignConfig config = builtin();
    const auto errors =
        errors_of([&] { apply_overrides(config, {"physics.iwan_joint.exponent=-0.3"}); });
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors.front().find("physics.iwan_joint.exponent: does not apply"), std::string::npos)
        << errors.front();
    EXPECT_EQ(config.physics.iwan_joint.exponent, -0.5);
}

TEST(ConfigPaths, OverridesValidOnlyTogetherAreAcceptedInAnyOrderAndAllErrorsReported) {
    // A band moved above its old upper end: alone, the new lower end would pass the upper one.
    for (const std::vector<std::string>& order :
         {std::vector<std::string>{"campaign.frequencies.low_ratio=1.10",
                                   "campaign.frequencies.high_ratio=1.20"},
          std::vector<std::string>{"campaign.frequencies.high_ratio=1.20",
                                   "campaign.frequencies.low_ratio=1.10"}}) {
        CampaignConfig config = builtin();
        const std::size_t overrides = config.where.overrides.size();
        apply_overrides(config, order);
        EXPECT_EQ(config.campaign.frequencies.low_ratio, 1.10);
        EXPECT_EQ(config.campaign.frequencies.high_ratio, 1.20);
        EXPECT_EQ(config.where.overrides.size(), overrides + 2);
    }
    // Two bad keys and one good: both errors at once, and nothing changed.
    CampaignConfig config = builtin();
    const double low = config.campaign.frequencies.low_ratio;
    const auto errors = errors_of([&] {
        apply_overrides(config, {"campaign.frequencies.low_ratio=0.8", "campaign.nosuchkey=1",
                                 "structure.beam.length_m=-1"});
    });
    EXPECT_EQ(errors.size(), 2u);
    EXPECT_EQ(config.campaign.frequencies.low_ratio, low);
    // Valid alone, invalid together: the band inverted by the pair is refused as a whole.
    EXPECT_EQ(errors_of([&] {
                  apply_overrides(config, {"campaign.frequencies.low_ratio=1.3",
                                           "campaign.frequencies.high_ratio=1.2"});
              }).size(),
              1u);
    EXPECT_EQ(config.campaign.frequencies.low_ratio, low);
}

/// fuzz/corpus/config/regression-set-not-utf8.toml: a --set bare word that is not UTF-8 was
/// taken as the campaign's name, and the resolved config written from it could not be read.
TEST(ConfigPaths, ABareWordThatIsNotUtf8OrHoldsControlCharactersIsRefused) {
    CampaignConfig config = builtin();
    const std::string name = config.name;
    for (const std::string& value :
         {std::string("\xfd\xe2\xea}H"), std::string("a\x01b"), std::string("over\xc0\xafshort")}) {
        const auto errors = errors_of([&] { apply_overrides(config, {"campaign.name=" + value}); });
        ASSERT_EQ(errors.size(), 1u);
        EXPECT_NE(errors[0].find("--set: campaign.name = "), std::string::npos) << errors[0];
        EXPECT_NE(errors[0].find("must be a TOML value or a plain word"), std::string::npos)
            << errors[0];
        EXPECT_EQ(config.name, name);
    }
    // A name in another script is UTF-8 and is taken, and its resolved config reads back.
    apply_overrides(config, {"campaign.name=Schwingtisch-\xc3\xbc"});
    EXPECT_EQ(config.name, "Schwingtisch-\xc3\xbc");
    const auto again = load_campaign_config_text(resolved_config_toml(config), "resolved.toml");
    EXPECT_EQ(again.name, config.name);
    EXPECT_EQ(config_hash(again), config_hash(config));
}

TEST(ConfigPaths, AValueSpanningLinesIsRefusedRatherThanCutToItsFirstLine) {
    CampaignConfig config = builtin();
    const auto errors = errors_of(
        [&] { apply_overrides(config, {"structure.beam.length_m=0.5\n[campaign]\nseed = 3"}); });
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("must be one value on one line"), std::string::npos) << errors[0];
    EXPECT_EQ(config.campaign.seed, builtin().campaign.seed);
}

/// Every key a leaf module's validate() reports maps to a declared key of its table.
void expect_every_violation_declared(const config::Table& table, const Violations& violations) {
    ASSERT_FALSE(violations.empty());
    for (const auto& v : violations) {
        const auto mapped = config::map_leaf_key(table, v.key);
        EXPECT_TRUE(mapped.has_value() && mapped->decl != nullptr) << v.key;
    }
}

const config::Table& table_at(std::initializer_list<const char*> keys) {
    const config::Table* t = &campaign_schema();
    for (const char* key : keys) t = t->find(key)->table.get();
    return *t;
}

TEST(ConfigPaths, EveryViolationOfADamperNamesADeclaredKey) {
    DamperSpec d;
    d.threads = -1;
    d.guard_overlap_fraction = 2.0;
    d.enclosure.inner_diameter_m = -1.0;
    d.enclosure.height_m = 0.0;
    d.enclosure.rods = {true, -1.0, -1.0, {0, 0, 0}};
    d.enclosure.plates = {{{0, 0, 0}, {-1, 1, 1}}};
    d.particles.count = 0;
    d.particles.material = {-1.0, -1.0, 0.7};
    d.particles.size_distribution = {{-1.0, 0.2}, {3e-3, -0.1}};
    d.particles.diameter_scatter = 0.3;
    d.contact.normal_stiffness = -1.0;
    d.contact.particle_particle = {1.5, -1.0, -1.0};
    d.contact.wall_restitution = 0.0;
    d.contact.wall_sliding_friction = -1.0;
    d.contact.wall_rolling_friction = -1.0;
    d.contact.wall_material = {7800.0, -1.0, 0.6};
    d.contact.tangential_stiffness_ratio = 0.0;
    d.contact.slip_regularisation_m_s = 0.0;
    d.settle.dt_s = 0.0;
    d.settle.max_time_s = 0.0;
    d.settle.kinetic_threshold_j = 0.0;
    expect_every_violation_declared(table_at({"dampers"}), d.validate());
}

TEST(ConfigPaths, EveryViolationOfTheStructureNamesADeclaredKey) {
    CampaignConfig config = builtin();
    auto& s = config.structure;
    s.modes = 0;
    s.beam.length_m = -1.0;
    s.beam.thickness_m = 0.1;
    s.beam.min_elements = 0;
    s.beam.supports.front().x_m = -1.0;
    s.beam.points.front().x_m = -1.0;
    s.beam.masses.front().point = "nowhere";
    s.beam.masses.back().mass_kg = 0.0;
    s.damping.default_ratio = 1.0;
    s.damping.modal_ratios = {0.5, 2.0};
    s.excitation.direction = Eigen::Vector3d::Zero();
    expect_every_violation_declared(table_at({"structure"}), s.validate());
}

TEST(ConfigPaths, EveryViolationOfTheControllerNamesADeclaredKey) {
    control::ControllerOptions c;
    c.tolerance = 0.0;
    c.window_periods = 2;
    c.early_periods = 5;
    c.transient_periods = -1;
    c.max_periods = 1;
    c.closest_rerun_periods = 0;
    c.initial_amplitude = -1.0;
    c.min_amplitude = -1.0;
    c.max_step_factor = 1.0;
    c.overshoot = -1.0;
    c.limit_cycle_jump = 0.5;
    c.limit_cycle_periods = 5;
    c.max_restarts = -1;
    c.drift_horizon_periods = -1;
    expect_every_violation_declared(table_at({"controller"}), c.validate());
}

}  // namespace
}  // namespace sb::bench

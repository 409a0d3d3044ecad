// Arrangement geometry (paper 000, Figs. 1-2, Table 1) and the shipped six-arrangement
// campaign.
#include "bench/arrangement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"

namespace sb::bench {
namespace {

/// Geometry below is a few sums and products of millimetre numbers: only rounding.
constexpr double kRounding = 1e-12;
constexpr double kG = 9.80665;

/// Paper 000's damper: origin 1.5 mm (half beam) + 10 mm (bottom plate) above the point.
DamperSpec paper_damper() {
    DamperSpec d;
    d.name = "pd";
    d.point = "damper";
    d.mount_offset_m = {0.0, 0.0, 0.0115};
    d.bottom_thickness_m = 0.010;
    return d;
}

ArrangementSpec arrangement(double angle_deg, double cathetus_m = 0.0) {
    ArrangementSpec a;
    a.damper_angle_deg = angle_deg;
    a.block_cathetus_m = cathetus_m;
    return a;
}

void expect_near(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol) {
    EXPECT_NEAR((a - b).norm(), 0.0, tol) << a.transpose() << " vs " << b.transpose();
}

TEST(Arrangement, HorizontalPutsGravityAlongMinusYAndVerticalAlongMinusZ) {
    ArrangementSpec h;
    h.oscillation = ArrangementSpec::Oscillation::horizontal;
    ArrangementSpec v;
    v.oscillation = ArrangementSpec::Oscillation::vertical;
    expect_near(arrangement_gravity(h, kG), Eigen::Vector3d(0.0, -kG, 0.0), kRounding);
    expect_near(arrangement_gravity(v, kG), Eigen::Vector3d(0.0, 0.0, -kG), kRounding);
}

TEST(Arrangement, AGravityTiltTurnsGravityAboutTheBeamAxis) {
    ArrangementSpec h;
    h.gravity_tilt_deg = 3.0;
    const double s = std::sin(3.0 * std::numbers::pi / 180.0);
    const double c = std::cos(3.0 * std::numbers::pi / 180.0);
    // Horizontal: g sin(3 deg) along -z, the motion.
    expect_near(arrangement_gravity(h, kG), Eigen::Vector3d(0.0, -kG * c, -kG * s), kRounding);
    ArrangementSpec v;
    v.oscillation = ArrangementSpec::Oscillation::vertical;
    v.gravity_tilt_deg = 3.0;
    expect_near(arrangement_gravity(v, kG), Eigen::Vector3d(0.0, kG * s, -kG * c), kRounding);
}

TEST(Arrangement, TheConfigsGravityGivesTheMagnitudeEveryArrangementTurns) {
    // The shipped H-0 campaign on the Moon and weightless: the arrangement keeps the
    // direction (-y, horizontal oscillation), the config gives the magnitude.
    auto config = load_campaign_config_text(test::paper000_h0_with({}), "h0.toml");
    const auto gravity_of = [](const CampaignConfig& c) {
        return plan_campaign(c, {}).arrangements.front().structure.gravity_m_s2;
    };
    expect_near(gravity_of(config), Eigen::Vector3d(0.0, -kG, 0.0), kRounding);
    apply_overrides(config, {"structure.gravity_m_s2=[0, 0, -1.62]"});
    expect_near(gravity_of(config), Eigen::Vector3d(0.0, -1.62, 0.0), kRounding);
    apply_overrides(config, {"structure.gravity_m_s2=[0, 0, 0]"});
    expect_near(gravity_of(config), Eigen::Vector3d::Zero(), 0.0);
}

TEST(Arrangement, TheDamperAxisMakesTheArrangementAngleWithTheMotion) {
    for (double angle : {0.0, 45.0, 90.0}) {
        const Eigen::Matrix3d r = mounting_rotation(arrangement(angle));
        const Eigen::Vector3d axis = r.col(2);
        EXPECT_NEAR(std::acos(axis.dot(Eigen::Vector3d::UnitZ())) * 180.0 / std::numbers::pi, angle,
                    1e-9);
        EXPECT_NEAR((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 0.0, kRounding);
        EXPECT_NEAR(r.determinant(), 1.0, kRounding);
    }
    // H-90: the axis is vertical, so gravity points down the axis onto the floor; H-0: across.
    ArrangementSpec h90 = arrangement(90.0);
    const Eigen::Vector3d local_g =
        mounting_rotation(h90).transpose() * arrangement_gravity(h90, kG);
    expect_near(local_g, Eigen::Vector3d(0.0, 0.0, -kG), kRounding);
    ArrangementSpec h0 = arrangement(0.0);
    EXPECT_NEAR((mounting_rotation(h0).transpose() * arrangement_gravity(h0, kG)).z(), 0.0,
                kRounding);
}

TEST(Arrangement, AtZeroDegreesTheEnclosureSitsAtItsMountOffset) {
    const DamperMounting m = damper_mounting(arrangement(0.0), paper_damper());
    expect_near(m.origin_m, Eigen::Vector3d(0.0, 0.0, 0.0115), kRounding);
    expect_near(m.mounting_face_m, Eigen::Vector3d(0.0, 0.0, 0.0015), kRounding);
}

TEST(Arrangement, TheFortyFiveDegreeWedgeRaisesTheEnclosureOnItsHypotenuse) {
    // Table 1: cathetus 20 mm. The enclosure stands on the hypotenuse's midpoint, c/2 = 10 mm
    // above the beam face; its origin lies one bottom plate (10 mm) further along the
    // tilted axis (0, sin 45, cos 45).
    const DamperMounting m = damper_mounting(arrangement(45.0, 0.020), paper_damper());
    const double s = std::sqrt(0.5);
    expect_near(m.mounting_face_m, Eigen::Vector3d(0.0, 0.0, 0.0015 + 0.010), kRounding);
    expect_near(m.origin_m, Eigen::Vector3d(0.0, 0.010 * s, 0.0115 + 0.010 * s), kRounding);
    // The wedge's centroid: a third of each 20 mm leg from its right angle at y = -10 mm.
    expect_near(m.block_cg_m, Eigen::Vector3d(0.0, -0.010 + 0.020 / 3.0, 0.0015 + 0.020 / 3.0),
                kRounding);
    // No part of the enclosure's bottom face (12.5 mm outer radius) is below the beam face.
    const Eigen::Vector3d lowest_rim =
        m.mounting_face_m + m.rotation * Eigen::Vector3d(0.0, -0.0125, 0.0);
    EXPECT_GT(lowest_rim.z(), 0.0015);
}

TEST(Arrangement, TheEnclosureMassTurnsAndMovesWithTheEnclosure) {
    const DamperSpec d = paper_damper();
    structure::LumpedMass enclosure;
    enclosure.name = "enclosure";
    enclosure.mass_kg = 0.0238;
    enclosure.offset_m = {0.0, 0.0, 0.0165};  // 5 mm above the inner bottom centre
    enclosure.inertia_kg_m2 = {3.8e-6, 3.8e-6, 1.5e-6};
    for (double angle : {0.0, 45.0, 90.0}) {
        const ArrangementSpec a = arrangement(angle, angle == 45.0 ? 0.020 : 0.0);
        const DamperMounting m = damper_mounting(a, d);
        const structure::LumpedMass turned = mounted_enclosure_mass(enclosure, d, m);
        // Its centre of gravity is where the DEM enclosure's is: 5 mm up its own axis.
        expect_near(turned.offset_m, m.origin_m + 0.005 * m.rotation.col(2), kRounding);
        EXPECT_EQ(turned.mass_kg, enclosure.mass_kg);
        // Inertia about the structure's y and z: cos^2/sin^2 mixes of the axial 1.5e-6 and
        // the transverse 3.8e-6.
        const double c = std::cos(angle * std::numbers::pi / 180.0);
        const double s = std::sin(angle * std::numbers::pi / 180.0);
        EXPECT_NEAR(turned.inertia_kg_m2.x(), 3.8e-6, 1e-18);
        EXPECT_NEAR(turned.inertia_kg_m2.y(), c * c * 3.8e-6 + s * s * 1.5e-6, 1e-18);
        EXPECT_NEAR(turned.inertia_kg_m2.z(), s * s * 3.8e-6 + c * c * 1.5e-6, 1e-18);
    }
}

TEST(Arrangement, TheStructureOfAnArrangementCarriesTheBlockTheTurnedEnclosureAndItsGravity) {
    const auto config =
        load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper000-campaign.toml");
    const ArrangementSpec* v45 = nullptr;
    for (const auto& a : config.campaign.arrangements) {
        if (a.name == "V-45") v45 = &a;
    }
    ASSERT_NE(v45, nullptr);
    const auto spec = arrangement_structure(config, *v45, false);
    expect_near(spec.gravity_m_s2, Eigen::Vector3d(0.0, 0.0, -kG), kRounding);
    const DamperMounting m = damper_mounting(*v45, config.campaign.dampers.front());
    bool block = false;
    bool enclosure = false;
    for (const auto& mass : spec.beam.masses) {
        if (mass.name == "pd block") {
            block = true;
            EXPECT_EQ(mass.mass_kg, 0.031);
            expect_near(mass.offset_m, m.block_cg_m, kRounding);
        }
        if (mass.name == "enclosure") {
            enclosure = true;
            expect_near(mass.offset_m, m.origin_m + 0.005 * m.rotation.col(2), kRounding);
        }
    }
    EXPECT_TRUE(block);
    EXPECT_TRUE(enclosure);
}

TEST(Arrangement, ABlockCathetusNeedsTheFortyFiveDegreeAngle) {
    const std::string text = test::paper000_h0_with(
        {{"damper_angle_deg", "damper_angle_deg = 30.0\nblock_cathetus_m = 0.02"}});
    try {
        load_campaign_config_text(text, "wedge.toml");
        ADD_FAILURE() << "accepted";
    } catch (const config::ConfigException& e) {
        EXPECT_NE(e.errors().front().format().find("block_cathetus_m"), std::string::npos)
            << e.errors().front().format();
    }
}

TEST(Arrangement, AnEnclosureMassThatIsNotAtTheDamperPointIsAConfigError) {
    const std::string text =
        test::paper000_h0_with({{"enclosure_mass", "enclosure_mass = \"accelerometer 2\""}});
    try {
        load_campaign_config_text(text, "enclosure.toml");
        ADD_FAILURE() << "accepted";
    } catch (const config::ConfigException& e) {
        EXPECT_NE(e.errors().front().format().find("dampers.pd.enclosure_mass"), std::string::npos)
            << e.errors().front().format();
    }
}

TEST(ShippedConfigs, Paper000CampaignHasSixArrangementsNineLevelsAndTheCalibratedFriction) {
    const auto config =
        load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper000-campaign.toml");
    const auto& c = config.campaign;
    ASSERT_EQ(c.arrangements.size(), 6u);
    const char* names[] = {"H-0", "H-45", "H-90", "V-0", "V-45", "V-90"};
    for (std::size_t i = 0; i < 6; ++i) {
        const auto& a = c.arrangements[i];
        EXPECT_EQ(a.name, names[i]);
        EXPECT_EQ(a.oscillation, i < 3 ? ArrangementSpec::Oscillation::horizontal
                                       : ArrangementSpec::Oscillation::vertical);
        EXPECT_EQ(a.damper_angle_deg, 45.0 * static_cast<double>(i % 3));
        // Table 1: the 45-degree block, 31 g with a 20 mm cathetus, and only at 45 degrees.
        EXPECT_EQ(a.block_mass_kg, i % 3 == 1 ? 0.031 : 0.0);
        EXPECT_EQ(a.block_cathetus_m, i % 3 == 1 ? 0.020 : 0.0);
    }
    EXPECT_EQ(c.levels_g, (std::vector<double>{0.5, 0.75, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0}));
    ASSERT_EQ(c.dampers.size(), 1u);
    const auto& contact = c.dampers[0].contact;
    EXPECT_EQ(contact.particle_particle.sliding_friction, 0.6);
    EXPECT_EQ(contact.particle_particle.rolling_friction, 0.01);
    EXPECT_EQ(contact.particle_wall().sliding_friction, 0.6);
    EXPECT_EQ(contact.particle_wall().rolling_friction, 0.01);
    EXPECT_EQ(c.dampers[0].particles.count, 120);
    EXPECT_EQ(c.dampers[0].enclosure_mass, "enclosure");
}

}  // namespace
}  // namespace sb::bench

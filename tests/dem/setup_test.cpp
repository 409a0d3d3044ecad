// Set-up helpers: radii, filling, settling, files, VTK, automatic stiffness.
#include "dem/setup.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace sb::dem {
namespace {

TEST(MakeRadii, SizeDistributionFollowsTheNumberFractions) {
    ParticleOptions o;
    o.count = 10;
    o.size_distribution = {{1e-3, 0.25}, {2e-3, 0.75}};
    const auto r = make_radii(o, 3);
    ASSERT_EQ(r.size(), 10u);
    EXPECT_EQ(std::count(r.begin(), r.end(), 0.5e-3) + std::count(r.begin(), r.end(), 1e-3), 10);
    const auto small = std::count(r.begin(), r.end(), 0.5e-3);
    EXPECT_TRUE(small == 2 || small == 3);
    EXPECT_EQ(make_radii(o, 3), r);
}

TEST(FillRandom, PlacesNonOverlappingSpheresInsideDeterministically) {
    SolverOptions o;
    o.contact.normal_stiffness = 1e4;
    o.particles.count = 120;
    o.enclosure.height_m = 50e-3;
    const ParticleSet a = fill_random(o, 42), b = fill_random(o, 42);
    EXPECT_EQ(a.positions_m, b.positions_m);
    const Enclosure enc(o.enclosure);
    for (std::size_t i = 0; i < a.positions_m.size(); ++i) {
        EXPECT_GE(enc.clearance(a.positions_m[i]), a.radii_m[i] * (1 - 1e-9));
        for (std::size_t j = 0; j < i; ++j) {
            EXPECT_GE((a.positions_m[i] - a.positions_m[j]).norm(), 3e-3 * (1 - 1e-9));
        }
    }
}

TEST(FillRandom, AvoidsRodsAndPlates) {
    SolverOptions o;
    o.contact.normal_stiffness = 1e4;
    o.particles.count = 50;
    o.particles.diameter_m = 2e-3;
    o.enclosure.shape = EnclosureShape::box;
    o.enclosure.rods.enabled = true;
    o.enclosure.plates.push_back({{-15e-3, -1e-3, 0}, {15e-3, 1e-3, 10e-3}});
    ASSERT_TRUE(o.validate().empty());
    const ParticleSet a = fill_random(o, 1);
    const Enclosure enc(o.enclosure);
    for (const auto& x : a.positions_m) EXPECT_GE(enc.clearance(x), 1e-3 * (1 - 1e-9));
}

TEST(ParticleFile, SaveAndLoadRoundTripsExactly) {
    ParticleSet p;
    p.positions_m = {{1e-3, 2e-3, 3.3333333333333333e-3}, {-1, 0.5, 0.1}};
    p.radii_m = {1.5e-3, 1e-3};
    p.velocities_m_s = {{0.1, 0.2, 0.3}, {0, 0, 0}};
    p.angular_velocities_rad_s = {{1, 2, 3}, {4, 5, 6}};
    const auto path = std::filesystem::temp_directory_path() / "sb_dem_particles.csv";
    save_particles(path.string(), p);
    const ParticleSet q = load_particles(path.string());
    EXPECT_EQ(q.positions_m, p.positions_m);
    EXPECT_EQ(q.radii_m, p.radii_m);
    EXPECT_EQ(q.velocities_m_s, p.velocities_m_s);
    EXPECT_EQ(q.angular_velocities_rad_s, p.angular_velocities_rad_s);
    std::filesystem::remove(path);
}

TEST(Settle, SettledStateIsAtRestAndLoadable) {
    SolverOptions o;
    o.particles.count = 20;
    o.contact.normal_stiffness = 1e4;
    o.contact.particle_particle.restitution = 0.3;
    o.contact.particle_wall.restitution = 0.3;
    SettleOptions so;
    so.dt_s = 2e-5;
    const ParticleSet s = settle(o, fill_random(o, 2), so);
    ASSERT_EQ(s.positions_m.size(), 20u);
    for (const auto& x : s.positions_m) EXPECT_LT(x.z(), 12e-3);
}

TEST(WriteVtk, WritesLegacyPolydata) {
    ParticleState s;
    s.x = {{0, 0, 0}, {1, 2, 3}};
    s.v = s.w = s.x;
    s.radius = {1, 2};
    s.locked = {0, 1};
    const auto path = std::filesystem::temp_directory_path() / "sb_dem.vtk";
    write_vtk(path.string(), s);
    std::ifstream in(path);
    std::string first;
    std::getline(in, first);
    EXPECT_EQ(first, "# vtk DataFile Version 3.0");
    std::filesystem::remove(path);
}

TEST(AutoStiffness, LinearStiffnessKeepsTheOverlapAtTheImpactSpeed) {
    AutoStiffnessInput in;
    in.impact_speed_m_s = 1.0;
    in.max_overlap_fraction = 0.01;
    const AutoStiffness a = auto_stiffness(in);
    const double m = 7800.0 * 4.0 / 3.0 * kPi * std::pow(1.5e-3, 3);
    EXPECT_NEAR(a.stiffness, m * 1.0 / std::pow(3e-5, 2), 1e-9 * a.stiffness);
    EXPECT_NEAR(a.time_step_s, a.contact_time_s / 20.0, 1e-18);
}

TEST(AutoStiffness, EstimatesTheImpactSpeedFromLevelFrequencyAndGap) {
    AutoStiffnessInput in;
    in.law = NormalLaw::hertz;
    in.level_m_s2 = 3 * kStandardGravity;
    in.frequency_hz = 6.3;
    in.gap_m = 10e-3;
    const AutoStiffness a = auto_stiffness(in);
    const double v = in.level_m_s2 / (kTwoPi * 6.3) + std::sqrt(2 * 4 * kStandardGravity * 10e-3);
    EXPECT_NEAR(a.impact_speed_m_s, v, 1e-12);
    // Hertz energy: 1/2 m v^2 = 2/5 k delta^2.5
    const double d = 0.01 * 3e-3;
    EXPECT_NEAR(0.4 * a.stiffness * std::pow(d, 2.5), 0.5 * a.effective_mass_kg * v * v,
                1e-9 * a.effective_mass_kg * v * v);
}

TEST(AutoStiffness, RejectsMissingSpeedInputs) {
    AutoStiffnessInput in;
    EXPECT_THROW(auto_stiffness(in), std::invalid_argument);
}

}  // namespace
}  // namespace sb::dem

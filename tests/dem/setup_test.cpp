// Set-up helpers: radii, filling, settling, files, VTK, automatic stiffness.
#include "dem/setup.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

#include "core/units.hpp"
#include "dem/solver.hpp"
#include "test_helpers.hpp"

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

/// Relative deviations d_i / nominal_i - 1 of the scattered diameters from the unscattered
/// ones of the same seed.
std::vector<double> relative_deviations(const ParticleOptions& o, std::uint64_t seed) {
    ParticleOptions nominal = o;
    nominal.diameter_scatter = 0.0;
    const auto r = make_radii(o, seed), r0 = make_radii(nominal, seed);
    std::vector<double> x(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) x[i] = r[i] / r0[i] - 1.0;
    return x;
}

TEST(MakeRadii, DiameterScatterHasTheNominalMeanAndTheSetDeviation) {
    // x = s u with u uniform on [-sqrt 3, sqrt 3]: E u = 0, E u^2 = 1, E u^4 = 9/5. Over n
    // spheres the sample mean of x has the standard deviation s / sqrt(n), and the sample
    // standard deviation S that of sqrt((E u^4 - 1) / n) s / 2 = s sqrt(0.2 / n) (delta
    // method on S^2). Both within 4 of their standard deviations (a chance of 6e-5 each).
    ParticleOptions o;
    o.count = 400;
    const double n = o.count;
    for (const double s : {0.05, 0.2}) {
        for (const std::uint64_t seed : {1, 7, 42}) {
            SCOPED_TRACE("s = " + std::to_string(s) + ", seed " + std::to_string(seed));
            o.diameter_scatter = s;
            const std::vector<double> x = relative_deviations(o, seed);
            double mean = 0.0;
            for (double v : x) mean += v / n;
            double square = 0.0;
            for (double v : x) square += (v - mean) * (v - mean) / (n - 1.0);
            EXPECT_LE(std::abs(mean), 4.0 * s / std::sqrt(n));
            EXPECT_LE(std::abs(std::sqrt(square) - s), 4.0 * s * std::sqrt(0.2 / n));
        }
    }
}

TEST(MakeRadii, EveryScatteredDiameterLiesWithinItsBoundAndTheLargestPossible) {
    ParticleOptions o;
    o.count = 300;
    o.diameter_scatter = 0.2;
    const double half_width = std::sqrt(3.0) * o.diameter_scatter;
    for (const double r : make_radii(o, 5)) {
        EXPECT_GE(2.0 * r, (1.0 - half_width) * o.diameter_m);
        EXPECT_LE(2.0 * r, (1.0 + half_width) * o.diameter_m);
        EXPECT_LE(2.0 * r, o.largest_diameter_m());
    }
    EXPECT_DOUBLE_EQ(o.largest_diameter_m(), (1.0 + half_width) * o.diameter_m);
    // Each class scatters about its own diameter; the classes are shuffled as without it.
    o.size_distribution = {{1e-3, 0.25}, {2e-3, 0.75}};
    for (const double x : relative_deviations(o, 5)) EXPECT_LE(std::abs(x), half_width);
    EXPECT_DOUBLE_EQ(o.largest_diameter_m(), (1.0 + half_width) * 2e-3);
}

TEST(MakeRadii, ScatterIsTheSameForASeedAndNoneAtZero) {
    ParticleOptions o;
    o.count = 200;
    o.diameter_scatter = 0.1;
    EXPECT_EQ(make_radii(o, 11), make_radii(o, 11));
    EXPECT_NE(make_radii(o, 11), make_radii(o, 12));
    o.diameter_scatter = 0.0;
    EXPECT_EQ(make_radii(o, 11), std::vector<double>(200, 0.5 * o.diameter_m));
    EXPECT_EQ(o.largest_diameter_m(), o.diameter_m);
}

TEST(MakeRadii, AScatterOutsideItsBoundIsAViolation) {
    ParticleOptions o;
    for (const double s : {-0.1, 0.3}) {
        o.diameter_scatter = s;
        const Violations v = o.validate();
        ASSERT_EQ(v.size(), 1u);
        EXPECT_EQ(v.front().key, "diameter_scatter");
    }
}

TEST(FillRandom, PlacesTheScatteredSpheresOfItsSeed) {
    SolverOptions o;
    o.contact.normal_stiffness = 1e4;
    o.particles.count = 60;
    o.particles.diameter_scatter = 0.15;
    o.enclosure.height_m = 50e-3;
    const ParticleSet a = fill_random(o, 9);
    EXPECT_EQ(a.radii_m, make_radii(o.particles, 9));
    const Enclosure enc(o.enclosure);
    for (std::size_t i = 0; i < a.positions_m.size(); ++i) {
        EXPECT_GE(enc.clearance(a.positions_m[i]), a.radii_m[i] * (1 - 1e-9));
        for (std::size_t j = 0; j < i; ++j) {
            const double touch = a.radii_m[i] + a.radii_m[j];
            EXPECT_GE((a.positions_m[i] - a.positions_m[j]).norm(), touch * (1 - 1e-9));
        }
    }
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

/// The settle threshold of these tests [J]: 20 spheres of 3 mm steel (m = 0.11 g) share it,
/// an rms speed of sqrt(2e-9 / (20 * 1.1e-4)) = 1e-3 m/s.
constexpr double kRestKineticJ = 1e-9;

SolverOptions settle_options_for_test() {
    SolverOptions o;
    o.particles.count = 20;
    o.contact.normal_stiffness = 1e4;
    o.contact.tangential = TangentialLaw::coulomb_spring;  // the law settle() uses anyway
    o.contact.particle_particle.restitution = 0.3;
    o.contact.particle_wall.restitution = 0.3;
    return o;
}

TEST(Settle, SettledStateIsAtRestAndLoadable) {
    const SolverOptions o = settle_options_for_test();
    SettleOptions so;
    so.dt_s = 2e-5;
    so.kinetic_threshold_j = kRestKineticJ;
    const ParticleSet s = settle(o, fill_random(o, 2), so);
    ASSERT_EQ(s.positions_m.size(), 20u);
    // settle() hands back the velocities it stopped at: the rest check below is on them
    bool any_moving = false;
    for (const auto& v : s.velocities_m_s) any_moving = any_moving || v.squaredNorm() > 0.0;
    EXPECT_TRUE(any_moving);

    // at rest, by the solver's own energy, and it stays so (not a turning point of a bounce)
    Solver rest(o, s);
    EXPECT_LT(rest.energy().kinetic_translational, kRestKineticJ);
    double worst_ke = 0.0;
    for (int k = 0; k < 2500; ++k) {  // 0.05 s
        rest.step(so.dt_s);
        worst_ke = std::max(worst_ke, rest.energy().kinetic_translational);
    }
    EXPECT_LT(worst_ke, kRestKineticJ);
    // still coming to rest, not bouncing: the energy has dropped far below the bound
    EXPECT_LT(rest.energy().kinetic_translational, 1e-2 * kRestKineticJ);
    const ParticleSet later = rest.local_snapshot();
    for (std::size_t i = 0; i < s.positions_m.size(); ++i) {
        // what the rms speed of the bound, 1e-3 m/s, covers in the 0.05 s
        EXPECT_LT((later.positions_m[i] - s.positions_m[i]).norm(), 5e-5) << i;
        EXPECT_LT(s.positions_m[i].z(), 12e-3);  // a bed of 20 in the 19 mm cylinder
    }

    // save -> load is exact, and a solver continued from the loaded state is bitwise the same
    const auto path = std::filesystem::temp_directory_path() / "sb_dem_settled.csv";
    save_particles(path.string(), s);
    const ParticleSet q = load_particles(path.string());
    std::filesystem::remove(path);
    EXPECT_EQ(q.positions_m, s.positions_m);
    EXPECT_EQ(q.radii_m, s.radii_m);
    EXPECT_EQ(q.velocities_m_s, s.velocities_m_s);
    EXPECT_EQ(q.angular_velocities_rad_s, s.angular_velocities_rad_s);
    Solver from_memory(o, s), from_file(o, q);
    for (int k = 0; k < 500; ++k) {
        from_memory.step(so.dt_s);
        from_file.step(so.dt_s);
    }
    for (std::size_t i = 0; i < s.positions_m.size(); ++i) {
        ASSERT_EQ(from_memory.particles().x[i], from_file.particles().x[i]) << i;
        ASSERT_EQ(from_memory.particles().v[i], from_file.particles().v[i]) << i;
        ASSERT_EQ(from_memory.particles().w[i], from_file.particles().w[i]) << i;
    }
    EXPECT_EQ(from_memory.wall_force(), from_file.wall_force());
}

/// Paper 000's bed (120 steel spheres of 3 mm in the 19 x 25 mm cylinder) on contacts of
/// 1.7e6 N/m (four times its stiffness for 5 g): the pair contact lasts 1.8e-5 s, 1.8 steps
/// of 1e-5 s.
SolverOptions stiff_bed_options() {
    SolverOptions o;
    o.particles.count = 120;
    o.contact.normal_stiffness = 1.7e6;
    o.contact.tangential = TangentialLaw::coulomb_spring;
    return o;
}

double sphere_mass_kg(const SolverOptions& o) {
    const double d = o.particles.diameter_m;
    return o.particles.material.density_kg_m3 * kPi / 6.0 * d * d * d;
}

TEST(Settle, StiffHookeContactsSettleAtAThreeAndAHalfthOfTheShortestContact) {
    SolverOptions o = stiff_bed_options();
    const ParticleSet bed = fill_random(o, 3);
    SettleOptions so;
    so.dt_s = 1e-5;
    const double m = sphere_mass_kg(o);
    // two spheres (m* = m/2) on k: the undamped half period
    const double pair = kPi * std::sqrt(0.5 * m / o.contact.normal_stiffness);
    EXPECT_NEAR(settling_step_s(o, bed, so), pair / 3.5, 1e-12 * pair);
    // a wall four times stiffer: m* = m on 4k, 1/sqrt(2) of the pair's
    o.contact.wall_normal_stiffness = 4.0 * o.contact.normal_stiffness;
    EXPECT_NEAR(settling_step_s(o, bed, so), pair / std::sqrt(2.0) / 3.5, 1e-12 * pair);
    // a softer contact keeps the given step
    o = settle_options_for_test();  // 1e4 N/m: the pair contact lasts 1.7e-4 s
    EXPECT_EQ(settling_step_s(o, bed, so), so.dt_s);
}

/// Johnson's Hertz impact duration 2.87 (m*^2 / (R* E*^2 v))^{1/5} (Contact Mechanics, 1985,
/// §11.4), an expression of its own beside dem::hertz_contact_time's; 2.87 is rounded (2.868).
double johnson_contact_time(double m_eff, double r_star, double e_star, double v) {
    return 2.868 * std::pow(m_eff * m_eff / (r_star * e_star * e_star * v), 0.2);
}

TEST(Settle, SteelHertzContactsSettleAtAThreeAndAHalfthOfTheContactOfAFallAcrossTheEnclosure) {
    SolverOptions o;
    o.particles.count = 120;
    o.contact.normal = NormalLaw::hertz;
    o.contact.normal_stiffness = 0.0;  // from the materials: steel on steel
    const ParticleSet bed = fill_random(o, 3);
    SettleOptions so;
    so.dt_s = 1e-5;
    const double m = sphere_mass_kg(o), r = 0.5 * o.particles.diameter_m;
    const double e_star = 210e9 / (2.0 * (1.0 - 0.3 * 0.3));
    // the fastest impact of settling: a fall across the 25 mm height, the cylinder's largest
    // extent (its diameter is 19 mm)
    const double v = std::sqrt(2.0 * kStandardGravity * 25e-3);
    const double pair = johnson_contact_time(0.5 * m, 0.5 * r, e_star, v);
    const double wall = johnson_contact_time(m, r, e_star, v);
    ASSERT_LT(pair, wall);  // R*^{-1/5} m*^{2/5}: the pair's is shorter
    EXPECT_NEAR(settling_step_s(o, bed, so), pair / 3.5, 2e-3 * pair / 3.5);
    EXPECT_LT(settling_step_s(o, bed, so), 0.3 * so.dt_s);  // about 2.7 us: dt_s would not do
    // a wall of a much stiffer material: its contact, half of E* on the wall's side, is shorter
    o.contact.wall_material.youngs_modulus_pa = 1e15;
    const double hard_wall = johnson_contact_time(m, r, 210e9 / (1.0 - 0.3 * 0.3), v);
    ASSERT_LT(hard_wall, pair);
    EXPECT_NEAR(settling_step_s(o, bed, so), hard_wall / 3.5, 2e-3 * hard_wall / 3.5);
    // a given, soft Hertz constant keeps the given step
    o.contact.normal_stiffness = 1e6;  // N/m^1.5: the pair contact lasts about 3 ms
    EXPECT_EQ(settling_step_s(o, bed, so), so.dt_s);
}

TEST(Settle, AStiffBedSettlesWhereTheGivenStepWouldBlowUp) {
    const SolverOptions o = stiff_bed_options();
    const ParticleSet filled = fill_random(o, 3);
    SettleOptions so;
    so.dt_s = 1e-5;
    // at the given step the first contacts gain energy until the overlap guard stops the run
    EXPECT_THROW(
        {
            Solver raw(o, filled);
            for (int k = 0; k < 50000; ++k) raw.step(so.dt_s);
        },
        SimulationError);
    const ParticleSet settled = settle(o, filled, so);
    Solver rest(o, settled);
    EXPECT_LT(rest.energy().kinetic_translational, so.kinetic_threshold_j);
}

/// A box of 7 x 7 x 6 diameters and 250 spheres of 2 mm: 0.445 of the cavity, beyond what
/// random insertion reaches (jamming near 0.38, less with walls).
SolverOptions small_box_for_pouring(int count) {
    SolverOptions o;
    o.particles.count = count;
    o.particles.diameter_m = 2e-3;
    o.enclosure.shape = EnclosureShape::box;
    o.enclosure.length_x_m = 14e-3;
    o.enclosure.length_y_m = 14e-3;
    o.enclosure.height_m = 12e-3;
    // soft enough for dt = 2e-5 s (pair contact time 1.8e-4 s); the static overlap under the
    // whole column (6 layers, 2 mN) is 4e-7 m, 4e-4 of the radius
    o.contact.normal_stiffness = 5e3;
    o.contact.tangential = TangentialLaw::coulomb_spring;
    return o;
}

SettleOptions pour_settle_options() {
    SettleOptions so;
    so.dt_s = 2e-5;
    so.kinetic_threshold_j = 1e-9;  // 250 spheres of 33 mg: rms speed 5e-4 m/s
    so.min_time_s = 0.02;           // a fall of 12 mm takes 0.05 s: the quiet checks decide
    return so;
}

/// Poured frictional spheres pack at 0.55-0.6 away from walls and surface; random
/// insertion jams at 0.38. The bound sits between, clear of both.
constexpr double kPouredInteriorFractionAtLeast = 0.5;
/// Largest overlap allowed in the settled bed, as a fraction of the radius: 25 times the
/// static overlap under the whole column (the run-time guard stops at 0.5).
constexpr double kSettledOverlapFraction = 1e-2;

TEST(Pour, FillsABoxBeyondRandomInsertionWithABedAtRestInside) {
    const SolverOptions o = small_box_for_pouring(250);
    EXPECT_THROW(fill_random(o, 1, 2000), std::runtime_error);
    const SettleOptions so = pour_settle_options();
    const ParticleSet bed = pour(o, 1, so);
    ASSERT_EQ(bed.positions_m.size(), 250u);
    const Enclosure enc(o.enclosure);
    EXPECT_NEAR(solid_fraction(bed, enc), 250 * 4.0 / 3.0 * kPi * 1e-9 / (14e-3 * 14e-3 * 12e-3),
                1e-12);
    double top = 0.0;
    for (std::size_t i = 0; i < bed.positions_m.size(); ++i) {
        const Eigen::Vector3d& x = bed.positions_m[i];
        EXPECT_TRUE(enc.contains(x)) << i;
        EXPECT_GT(enc.clearance(x), bed.radii_m[i] * (1.0 - kSettledOverlapFraction)) << i;
        top = std::max(top, x.z() + bed.radii_m[i]);
    }
    EXPECT_LT(test::largest_pair_overlap_fraction(bed), kSettledOverlapFraction);
    // bulk packing: one diameter in from the side walls and the floor, two below the top
    const double d = 2e-3;
    const double interior =
        test::packing_fraction_in(bed, Eigen::Vector3d(-7e-3 + d, -7e-3 + d, d),
                                  Eigen::Vector3d(7e-3 - d, 7e-3 - d, top - 2 * d), 60);
    RecordProperty("interior_packing_fraction", std::to_string(interior));
    EXPECT_GT(interior, kPouredInteriorFractionAtLeast);
    // at rest by the solver's energy of the returned velocities, and staying at rest
    Solver s(o, bed);
    EXPECT_LT(s.energy().kinetic_translational, so.kinetic_threshold_j);
    double worst = 0.0;
    for (int k = 0; k < 1000; ++k) {  // 0.02 s
        s.step(so.dt_s);
        if (k % 50 == 49) worst = std::max(worst, s.energy().kinetic_translational);
    }
    EXPECT_LT(worst, so.kinetic_threshold_j);
}

TEST(Pour, IsDeterministicForASeed) {
    SolverOptions o = small_box_for_pouring(56);
    o.enclosure.length_y_m = 8e-3;
    o.enclosure.height_m = 6e-3;  // 56 spheres (0.35 of the box) need two batches here:
    EXPECT_THROW(fill_random(o, 5, 5000), std::runtime_error);  // one insertion cannot hold them
    const ParticleSet a = pour(o, 5, pour_settle_options());
    const ParticleSet b = pour(o, 5, pour_settle_options());
    EXPECT_EQ(a.positions_m, b.positions_m);
    EXPECT_EQ(a.velocities_m_s, b.velocities_m_s);
    EXPECT_EQ(a.angular_velocities_rad_s, b.angular_velocities_rad_s);
    const ParticleSet c = pour(o, 6, pour_settle_options());
    EXPECT_NE(a.positions_m, c.positions_m);
}

TEST(Pour, ResumedFromAnyOfItsProgressRecordsGivesTheUninterruptedBed) {
    SolverOptions o = small_box_for_pouring(56);
    o.enclosure.length_y_m = 8e-3;
    o.enclosure.height_m = 6e-3;  // two batches (above)
    PourOptions po;
    po.friction_scale = 0.5;  // and a final settle with the configured friction
    const SettleOptions so = pour_settle_options();
    const ParticleSet plain = pour(o, 5, so, po);

    std::vector<PourProgress> records;
    PourCheckpoints saving;
    saving.due = [] { return true; };
    saving.save = [&](const PourProgress& p) { records.push_back(p); };
    const ParticleSet recorded = pour(o, 5, so, po, saving);
    EXPECT_EQ(recorded.positions_m, plain.positions_m);  // saving changes nothing

    // the first record, the last of the first batch, one of the second, one of the final settle
    std::vector<const PourProgress*> picks;
    for (std::size_t k = 0; k < records.size(); ++k) {
        const PourProgress& p = records[k];
        const bool last_of_first = p.batch == 0 && !p.final_settle &&
                                   (k + 1 == records.size() || records[k + 1].batch != 0);
        if (k == 0 || last_of_first) picks.push_back(&p);
    }
    const auto in = [&](int batch, bool final_settle) {
        std::vector<const PourProgress*> of;
        for (const auto& p : records) {
            if (p.batch == batch && p.final_settle == final_settle) of.push_back(&p);
        }
        return of;
    };
    const auto second = in(1, false), last = in(1, true);
    ASSERT_FALSE(second.empty());
    ASSERT_FALSE(last.empty());
    picks.push_back(second[second.size() / 2]);
    picks.push_back(last[last.size() / 2]);
    ASSERT_EQ(picks.size(), 4u);
    for (const PourProgress* p : picks) {
        SCOPED_TRACE("batch " + std::to_string(p->batch) + (p->final_settle ? " final" : "") +
                     " step " + std::to_string(p->settle_steps));
        PourCheckpoints resuming;
        resuming.resume = p;
        const ParticleSet resumed = pour(o, 5, so, po, resuming);
        EXPECT_EQ(resumed.positions_m, plain.positions_m);
        EXPECT_EQ(resumed.velocities_m_s, plain.velocities_m_s);
        EXPECT_EQ(resumed.angular_velocities_rad_s, plain.angular_velocities_rad_s);
    }
    // a record of another pour is refused, not continued
    PourCheckpoints other;
    other.resume = picks[1];
    EXPECT_THROW(pour(o, 6, so, po, other), std::invalid_argument);
    PourProgress garbled = *picks[1];
    garbled.generator_state = "not a generator";
    other.resume = &garbled;
    EXPECT_THROW(pour(o, 5, so, po, other), std::invalid_argument);
}

TEST(Pour, FillsAHorizontallyMountedCylinderAlongGravity) {
    SolverOptions o = small_box_for_pouring(60);
    o.enclosure.shape = EnclosureShape::cylinder;
    o.enclosure.inner_diameter_m = 12e-3;
    o.enclosure.height_m = 14e-3;
    o.gravity_m_s2 = Eigen::Vector3d(-kStandardGravity, 0, 0);  // axis horizontal: down is -x
    const ParticleSet bed = pour(o, 3, pour_settle_options());
    const Enclosure enc(o.enclosure);
    double centre_x = 0.0;
    for (const auto& x : bed.positions_m) {
        EXPECT_TRUE(enc.contains(x));
        centre_x += x.x() / 60.0;
    }
    // 60 spheres fill 0.25 of the cylinder: their centroid lies well below the axis
    EXPECT_LT(centre_x, -2e-3);
}

TEST(Pour, ReportsACavityTooSmallForTheCount) {
    SolverOptions o = small_box_for_pouring(80);
    o.enclosure.length_x_m = o.enclosure.length_y_m = 6e-3;
    o.enclosure.height_m = 8e-3;  // room for about 36 poured spheres
    try {
        pour(o, 1, pour_settle_options());
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("too small for this count"), std::string::npos)
            << e.what();
    }
    o.gravity_m_s2.setZero();
    EXPECT_THROW(pour(o, 1, pour_settle_options()), std::invalid_argument);
}

/// Reads every whitespace-separated token of a file.
std::vector<std::string> tokens_of(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::vector<std::string> out;
    for (std::string t; in >> t;) out.push_back(t);
    return out;
}

TEST(WriteVtk, FollowsTheLegacyPolydataFormatAndReadsBack) {
    ParticleState s;
    s.x = {{0, 0, 0}, {1.2345678901e-3, -2.5e-3, 3.75e-2}, {-4e-3, 5e-3, 6e-3}};
    s.v = {{0.1, 0.2, 0.3}, {-1.5, 2.25, 1e-7}, {0, 0, -9.5}};
    s.w = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
    s.radius = {1e-3, 1.5e-3, 2e-3};
    s.locked = {0, 1, 0};
    const auto path = std::filesystem::temp_directory_path() / "sb_dem.vtk";
    write_vtk(path.string(), s);
    {
        // the first two lines are fixed lines of the legacy format (version, title)
        std::ifstream in(path);
        std::string version, title;
        std::getline(in, version);
        std::getline(in, title);
        EXPECT_EQ(version, "# vtk DataFile Version 3.0");
        EXPECT_FALSE(title.empty());
        EXPECT_LT(title.size(), 256u);
    }
    const auto t = tokens_of(path);
    std::filesystem::remove(path);
    std::size_t k = 0;
    auto expect = [&](const std::string& word) {
        ASSERT_LT(k, t.size());
        EXPECT_EQ(t[k], word) << "token " << k;
        ++k;
    };
    auto number = [&] { return k < t.size() ? std::stod(t[k++]) : std::nan(""); };
    // 10 significant digits are written
    auto near = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b) + 1e-300; };
    k = 0;
    while (k < t.size() && t[k] != "ASCII") ++k;  // skip the header lines checked above
    expect("ASCII");
    expect("DATASET");
    expect("POLYDATA");
    expect("POINTS");
    expect("3");
    expect("double");
    for (const auto& x : s.x) {
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(near(number(), x[a])) << "point " << x.transpose();
    }
    expect("VERTICES");
    expect("3");
    expect("6");  // cell list size: (1 + 1) per vertex
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(number(), 1.0);
        EXPECT_EQ(number(), i);
    }
    expect("POINT_DATA");
    expect("3");
    std::map<std::string, std::vector<double>> fields;
    while (k < t.size()) {
        const std::string kind = t[k++];
        ASSERT_TRUE(kind == "SCALARS" || kind == "VECTORS") << kind;
        const std::string name = t[k++];
        const std::string type = t[k++];
        EXPECT_TRUE(type == "double" || type == "int") << type;
        int components = 3;
        if (kind == "SCALARS") {
            components = std::stoi(t[k++]);
            expect("LOOKUP_TABLE");
            expect("default");
        }
        for (int q = 0; q < 3 * components; ++q) fields[name].push_back(number());
    }
    ASSERT_EQ(fields.count("radius"), 1u);
    ASSERT_EQ(fields.count("velocity"), 1u);
    ASSERT_EQ(fields.count("angular_velocity"), 1u);
    ASSERT_EQ(fields.count("id"), 1u);
    ASSERT_EQ(fields.count("locked"), 1u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_TRUE(near(fields["radius"][i], s.radius[i]));
        EXPECT_EQ(fields["id"][i], i);
        EXPECT_EQ(fields["locked"][i], s.locked[i]);
        for (int a = 0; a < 3; ++a) {
            EXPECT_TRUE(near(fields["velocity"][3 * i + a], s.v[i][a])) << i;
            EXPECT_TRUE(near(fields["angular_velocity"][3 * i + a], s.w[i][a])) << i;
        }
    }
}

TEST(AutoStiffness, LinearStiffnessKeepsTheOverlapAtTheImpactSpeed) {
    AutoStiffnessInput in;
    in.impact_speed_m_s = 1.0;
    in.max_overlap_fraction = 0.01;
    const AutoStiffness a = auto_stiffness(in);
    const double m = 7800.0 * 4.0 / 3.0 * kPi * std::pow(1.5e-3, 3);
    EXPECT_NEAR(a.stiffness, m * 1.0 / std::pow(3e-5, 2), 1e-9 * a.stiffness);
    EXPECT_NEAR(a.time_step_s, a.contact_time_s * AutoStiffnessInput{}.time_step_fraction, 1e-18);
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

TEST(AutoStiffness, TimeStepFollowsTheShorterParticleParticleContactTime) {
    const double m = 7800.0 * 4.0 / 3.0 * kPi * std::pow(1.5e-3, 3);
    AutoStiffnessInput in;
    in.impact_speed_m_s = 1.0;
    in.restitution = 1.0;  // undamped: the closed form pi sqrt(m*/k)
    const AutoStiffness a = auto_stiffness(in);
    EXPECT_NEAR(a.wall_contact_time_s, kPi * std::sqrt(m / a.stiffness),
                1e-12 * a.wall_contact_time_s);
    EXPECT_NEAR(a.pair_contact_time_s, kPi * std::sqrt(0.5 * m / a.stiffness),
                1e-12 * a.pair_contact_time_s);
    EXPECT_EQ(a.contact_time_s, a.pair_contact_time_s);
    EXPECT_NEAR(a.time_step_s, a.pair_contact_time_s * AutoStiffnessInput{}.time_step_fraction,
                1e-15 * a.time_step_s);
    // damped (e = 0.9): both times scale with sqrt(m*), so the ratio stays sqrt(2)
    in.restitution = 0.9;
    const AutoStiffness b = auto_stiffness(in);
    EXPECT_NEAR(b.wall_contact_time_s / b.pair_contact_time_s, std::sqrt(2.0), 1e-12);
    // Hertz: t = 2.94328 (5 m* / (4 k))^{2/5} v^{-1/5} (the constant 2 (2/5) B(2/5, 1/2) to
    // six digits, hence the 1e-5 tolerance; Johnson, Contact Mechanics, 11.2)
    in.law = NormalLaw::hertz;
    const AutoStiffness h = auto_stiffness(in);
    auto hertz = [&](double me) { return 2.94328 * std::pow(1.25 * me / h.stiffness, 0.4); };
    EXPECT_NEAR(h.wall_contact_time_s, hertz(m), 1e-5 * h.wall_contact_time_s);
    EXPECT_NEAR(h.pair_contact_time_s, hertz(0.5 * m), 1e-5 * h.pair_contact_time_s);
    EXPECT_NEAR(h.time_step_s, h.pair_contact_time_s * AutoStiffnessInput{}.time_step_fraction,
                1e-15 * h.time_step_s);
    const std::string line = describe(h, NormalLaw::hertz);
    EXPECT_NE(line.find("particle-particle"), std::string::npos) << line;
    EXPECT_NE(line.find("particle-wall"), std::string::npos) << line;
}

TEST(AutoStiffness, RejectsMissingSpeedInputs) {
    AutoStiffnessInput in;
    EXPECT_THROW(auto_stiffness(in), std::invalid_argument);
}

/// Two size classes (2 and 4 mm steel) in a 25 mm high cavity, excited at 2 g RMS, 120 Hz.
struct ExcitationCase {
    ParticleOptions particles;
    EnclosureOptions enclosure;
    double peak_m_s2 = std::sqrt(2.0) * 2.0 * kStandardGravity;
    double frequency_hz = 120.0;
    double overlap = 0.01;
    double fraction = 1.0 / 25.0;
    ExcitationCase() {
        particles.count = 40;
        particles.size_distribution = {{2e-3, 0.5}, {4e-3, 0.5}};
        enclosure.height_m = 25e-3;
    }
    /// auto_stiffness() sized for the largest spheres at this excitation, its contact times
    /// the smallest spheres'.
    AutoStiffnessInput input(NormalLaw law, double restitution) const {
        AutoStiffnessInput in;
        in.law = law;
        in.particle_diameter_m = 4e-3;
        in.smallest_diameter_m = 2e-3;
        in.density_kg_m3 = particles.material.density_kg_m3;
        in.max_overlap_fraction = overlap;
        in.level_m_s2 = peak_m_s2;
        in.frequency_hz = frequency_hz;
        in.gap_m = enclosure.height_m;
        in.restitution = restitution;
        in.time_step_fraction = fraction;
        return in;
    }
    ExcitationContact choose(NormalLaw law, double restitution, std::optional<double> given) const {
        return choose_contact(particles, enclosure, law, restitution, given, overlap, fraction,
                              peak_m_s2, frequency_hz);
    }
    double largest_mass_kg() const {
        return particles.material.density_kg_m3 * kPi * std::pow(4e-3, 3) / 6.0;
    }
    double smallest_mass_kg() const {
        return particles.material.density_kg_m3 * kPi * std::pow(2e-3, 3) / 6.0;
    }
    /// a / (2 pi f) + sqrt(2 (a + g) gap): the largest impact speed of the excitation.
    double impact_speed_m_s() const {
        return peak_m_s2 / (kTwoPi * frequency_hz) +
               std::sqrt(2.0 * (peak_m_s2 + kStandardGravity) * enclosure.height_m);
    }
};

std::string nine_digits(double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.9g", v);
    return buffer;
}

TEST(ChooseContact, AutomaticStiffnessIsSizedForTheLargestSpheresAtTheExcitation) {
    const ExcitationCase c;
    for (const NormalLaw law : {NormalLaw::hooke, NormalLaw::hertz}) {
        SCOPED_TRACE(law == NormalLaw::hooke ? "hooke" : "hertz");
        const ExcitationContact chosen = c.choose(law, 0.8, std::nullopt);
        const AutoStiffness expected = auto_stiffness(c.input(law, 0.8));
        EXPECT_EQ(chosen.stiffness, expected.stiffness);
        EXPECT_EQ(chosen.time_step_s, expected.time_step_s);
        EXPECT_EQ(chosen.log, "automatic: " + describe(expected, law));
        // 1/2 m v^2 = 1/2 k delta^2 (Hooke) or 2/5 k delta^{5/2} (Hertz) at delta = 1% of the
        // largest diameter, for a wall impact of the largest sphere (m* = m)
        const double m = c.largest_mass_kg(), v = c.impact_speed_m_s(), d = c.overlap * 4e-3;
        const double energy = 0.5 * m * v * v;
        const double stored = law == NormalLaw::hooke ? 0.5 * chosen.stiffness * d * d
                                                      : 0.4 * chosen.stiffness * std::pow(d, 2.5);
        EXPECT_NEAR(stored, energy, 1e-9 * energy);
        // the step: a fraction of the contact of two of the smallest spheres (2 mm, m* = m/2),
        // the shortest of the bed (a third of the largest pair's for Hooke)
        const double m_pair = 0.5 * c.smallest_mass_kg();
        const double t_c = law == NormalLaw::hooke
                               ? hooke_contact_time(m_pair, chosen.stiffness, 0.8)
                               : hertz_contact_time(m_pair, chosen.stiffness, v);
        EXPECT_NEAR(chosen.pair_contact_time_s, t_c, 1e-12 * t_c);
        EXPECT_NEAR(chosen.time_step_s, c.fraction * t_c, 1e-12 * t_c);
    }
}

TEST(ChooseContact, AScatterSizesTheStiffnessForTheLargestSphereItCanDrawAndTheStepForTheSmallest) {
    ExcitationCase c;
    c.particles.diameter_scatter = 0.1;
    AutoStiffnessInput in = c.input(NormalLaw::hooke, 0.8);
    in.particle_diameter_m = (1.0 + std::sqrt(3.0) * 0.1) * 4e-3;
    in.smallest_diameter_m = (1.0 - std::sqrt(3.0) * 0.1) * 2e-3;
    const AutoStiffness expected = auto_stiffness(in);
    const ExcitationContact chosen = c.choose(NormalLaw::hooke, 0.8, std::nullopt);
    EXPECT_EQ(chosen.stiffness, expected.stiffness);
    EXPECT_EQ(chosen.time_step_s, expected.time_step_s);
}

TEST(HertzConstant, IsFourThirdsOfTheEffectiveModulusTimesTheRootOfTheEffectiveRadius) {
    Material steel;  // 210 GPa, 0.3
    Material glass;
    glass.youngs_modulus_pa = 63e9;
    glass.poisson_ratio = 0.22;
    const double r = 1.5e-3;
    // two steel spheres: E* = E / (2 (1 - nu^2)), R* = r / 2
    EXPECT_NEAR(hertz_constant(steel, r, steel, r),
                4.0 / 3.0 * 210e9 / (2.0 * 0.91) * std::sqrt(0.75e-3), 1e-12 * 4.2e9);
    // a steel sphere on a flat glass wall: R* = r
    const double e_star = 1.0 / (0.91 / 210e9 + (1.0 - 0.22 * 0.22) / 63e9);
    const double k = 4.0 / 3.0 * e_star * std::sqrt(r);
    EXPECT_NEAR(hertz_constant(steel, r, glass, std::numeric_limits<double>::infinity()), k,
                1e-12 * k);
    // unequal spheres: R* = r_a r_b / (r_a + r_b), symmetric
    EXPECT_DOUBLE_EQ(hertz_constant(steel, 1e-3, glass, 3e-3),
                     hertz_constant(glass, 3e-3, steel, 1e-3));
}

/// Contact options whose walls, ends and lateral surface, are all of `material`.
ContactOptions walls_of(const Material& material) {
    ContactOptions c;
    c.wall_material = material;
    return c;
}

TEST(MaterialsContact, TheStepIsTheFractionOfTheShorterHertzContactOfTheMaterialsAtTheImpact) {
    const ExcitationCase c;  // steel spheres of 2 and 4 mm, 2 g RMS at 120 Hz, 25 mm high
    const Material steel;
    const ExcitationContact chosen = materials_contact(c.particles, c.enclosure, walls_of(steel),
                                                       c.fraction, c.peak_m_s2, c.frequency_hz);
    EXPECT_EQ(chosen.stiffness, 0.0);  // the solver takes each pair's from the materials
    EXPECT_NEAR(chosen.impact_speed_m_s, c.impact_speed_m_s(), 1e-12 * c.impact_speed_m_s());
    // the smallest spheres (2 mm) have the shortest contacts
    const double m = c.smallest_mass_kg(), r = 1e-3, v = c.impact_speed_m_s();
    const double e_star = 210e9 / (2.0 * 0.91);
    const double pair = johnson_contact_time(0.5 * m, 0.5 * r, e_star, v);
    EXPECT_NEAR(chosen.pair_contact_time_s, pair, 2e-3 * pair);
    EXPECT_NEAR(chosen.time_step_s, c.fraction * pair, 2e-3 * c.fraction * pair);
    EXPECT_NE(chosen.log.find("Hertz from the materials"), std::string::npos) << chosen.log;
    // a wall of tungsten carbide (600 GPa, 0.22) shortens the wall contact below the pair's
    Material carbide;
    carbide.youngs_modulus_pa = 600e9;
    carbide.poisson_ratio = 0.22;
    const double wall = johnson_contact_time(m, r, 1.0 / (0.91 / 210e9 + 0.9516 / 600e9), v);
    ASSERT_LT(wall, pair);
    const ExcitationContact hard = materials_contact(c.particles, c.enclosure, walls_of(carbide),
                                                     c.fraction, c.peak_m_s2, c.frequency_hz);
    EXPECT_NEAR(hard.time_step_s, c.fraction * wall, 2e-3 * c.fraction * wall);
    EXPECT_NEAR(hard.pair_contact_time_s, pair, 2e-3 * pair);
    // the same carbide as the lateral surface between ends of PMMA (3 GPa, 0.35): the
    // stiffer wall, wherever it is, sets the step
    ContactOptions tube = walls_of(Material{});
    tube.wall_material.youngs_modulus_pa = 3e9;
    tube.wall_material.poisson_ratio = 0.35;
    tube.side_material = carbide;
    const ExcitationContact side =
        materials_contact(c.particles, c.enclosure, tube, c.fraction, c.peak_m_s2, c.frequency_hz);
    EXPECT_NEAR(side.time_step_s, c.fraction * wall, 2e-3 * c.fraction * wall);
    EXPECT_NE(side.log.find("particle-side"), std::string::npos) << side.log;
    // and PMMA everywhere leaves the pair's contact the shorter
    tube.side_material.reset();
    const ExcitationContact soft =
        materials_contact(c.particles, c.enclosure, tube, c.fraction, c.peak_m_s2, c.frequency_hz);
    EXPECT_NEAR(soft.time_step_s, c.fraction * pair, 2e-3 * c.fraction * pair);
}

TEST(SolverOptions, RodsMustClearTheLargestScatteredSphere) {
    SolverOptions o;
    o.contact.normal_stiffness = 1e4;
    o.particles.diameter_m = 3e-3;
    o.enclosure.shape = EnclosureShape::box;
    o.enclosure.rods.enabled = true;
    o.enclosure.rods.rod_diameter_m = 1e-3;
    o.enclosure.rods.cell_size_m = 4.2e-3;  // clears 3 mm, not 3 (1 + sqrt(3) 0.1) = 3.52 mm
    EXPECT_TRUE(o.validate().empty());
    o.particles.diameter_scatter = 0.1;
    const Violations v = o.validate();
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v.front().key, "enclosure.rods.cell_size_m");
}

TEST(ChooseContact, GivenHookeStiffnessStepsAFractionOfThePairContactTime) {
    const ExcitationCase c;
    const double k = 3e4, m_pair = 0.5 * c.smallest_mass_kg();  // the shortest contact
    const ExcitationContact damped = c.choose(NormalLaw::hooke, 0.8, k);
    EXPECT_EQ(damped.stiffness, k);
    const double t_c = hooke_contact_time(m_pair, k, 0.8);
    EXPECT_DOUBLE_EQ(damped.time_step_s, c.fraction * t_c);
    EXPECT_EQ(damped.log, "stiffness " + nine_digits(k) + " (given), contact time " +
                              nine_digits(t_c) + " s, time step " +
                              nine_digits(damped.time_step_s) + " s");
    // undamped: half the period of the pair oscillator, pi sqrt(m*/k)
    const ExcitationContact elastic = c.choose(NormalLaw::hooke, 1.0, k);
    EXPECT_NEAR(elastic.time_step_s, c.fraction * kPi * std::sqrt(m_pair / k),
                1e-12 * elastic.time_step_s);
    EXPECT_GT(damped.time_step_s, elastic.time_step_s);  // the dashpot softens the contact
}

TEST(ChooseContact, GivenHertzStiffnessStepsAFractionOfThePairContactTimeAtTheImpactSpeed) {
    const ExcitationCase c;
    const double k = 8e9, m_pair = 0.5 * c.smallest_mass_kg(), v = c.impact_speed_m_s();
    const ExcitationContact chosen = c.choose(NormalLaw::hertz, 0.8, k);
    EXPECT_EQ(chosen.stiffness, k);
    // 2.94328 (5 m* / (4 k))^{2/5} v^{-1/5} (Johnson, Contact Mechanics, 11.2; the constant to
    // six digits)
    EXPECT_NEAR(chosen.time_step_s,
                c.fraction * 2.94328 * std::pow(1.25 * m_pair / k, 0.4) / std::pow(v, 0.2),
                1e-5 * chosen.time_step_s);
    EXPECT_DOUBLE_EQ(chosen.time_step_s, c.fraction * hertz_contact_time(m_pair, k, v));
    EXPECT_EQ(chosen.log.rfind("stiffness " + nine_digits(k) + " (given), contact time ", 0), 0u)
        << chosen.log;
}

TEST(ChooseContact, AutomaticStiffnessNeedsAnExcitation) {
    ExcitationCase c;
    c.peak_m_s2 = 0.0;
    EXPECT_THROW(c.choose(NormalLaw::hooke, 0.8, std::nullopt), std::invalid_argument);
    EXPECT_NO_THROW(c.choose(NormalLaw::hooke, 0.8, 3e4));  // a given Hooke k needs none
}

}  // namespace
}  // namespace sb::dem

// The automatic DEM time step: the largest step of the ladder whose impacts give the
// converged restitution, the finest when none does, and clean errors for inputs it cannot use.
#include "dem/time_step.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "dem/setup.hpp"

namespace sb::dem {
namespace {

/// Paper 000's spheres with restitution e and the stiffness a campaign chooses at 2 g.
struct Case {
    SolverOptions options;
    ExcitationContact chosen;
};

Case hooke_case(double e) {
    Case c;
    c.options.contact.particle_particle.restitution = e;
    c.options.contact.particle_wall.restitution = e;
    c.chosen =
        choose_contact(c.options.particles, c.options.enclosure, NormalLaw::hooke, e, std::nullopt,
                       0.01, kTimeStepLadder[0], std::sqrt(2.0) * 2.0 * kStandardGravity, 6.37);
    c.options.contact.normal_stiffness = c.chosen.stiffness;
    return c;
}

TEST(AutomaticTimeStep, AStronglyDampedContactIsGivenTheFinestStepAndSaysTheToleranceIsMissed) {
    // At e = 0.3 the dashpot's force at the first step of a contact is large against the
    // rebound: even at t_c/80 the mean restitution over the phases is 0.8 % off.
    const Case c = hooke_case(0.3);
    const TimeStepFraction f = automatic_time_step_fraction(c.options, c.chosen.pair_contact_time_s,
                                                            c.chosen.impact_speed_m_s);
    EXPECT_DOUBLE_EQ(f.fraction, std::end(kTimeStepLadder)[-1]);
    EXPECT_FALSE(f.met);
    EXPECT_GT(std::max(f.pair_mean_deviation, f.wall_mean_deviation), kRestitutionMeanTolerance);
    EXPECT_NE(f.describe().find("not met"), std::string::npos) << f.describe();
    // The converged restitution is the set one (the linear dashpot's constant is exact).
    EXPECT_NEAR(f.pair_restitution, 0.3, 0.003);
    EXPECT_NEAR(f.wall_restitution, 0.3, 0.003);
}

TEST(AutomaticTimeStep, AMetChoiceMeetsBothTolerancesAndAStifferBedIsGivenTheSameFraction) {
    // The fraction depends on the law's damping, not on the stiffness: the contact time
    // scales both the step and the dynamics.
    Case c = hooke_case(0.9);
    const TimeStepFraction f = automatic_time_step_fraction(c.options, c.chosen.pair_contact_time_s,
                                                            c.chosen.impact_speed_m_s);
    ASSERT_TRUE(f.met) << f.describe();
    EXPECT_LE(f.pair_mean_deviation, kRestitutionMeanTolerance);
    EXPECT_LE(f.wall_mean_deviation, kRestitutionMeanTolerance);
    EXPECT_LE(f.worst_deviation, kRestitutionWorstTolerance);
    c.options.contact.normal_stiffness *= 16.0;
    const TimeStepFraction stiff = automatic_time_step_fraction(
        c.options, 0.25 * c.chosen.pair_contact_time_s, c.chosen.impact_speed_m_s);
    EXPECT_DOUBLE_EQ(stiff.fraction, f.fraction) << f.describe() << "\n" << stiff.describe();
}

TEST(AutomaticTimeStep, ABedOfSeveralSizesIsSteppedForItsSmallestSpheresShorterContacts) {
    // Diameters scattered by 20 %: the smallest spheres (1 - sqrt 3 * 0.2 of the nominal) are
    // 0.48 times the largest's size, their Hooke contact (t_c ~ sqrt(m)) a third as long; a
    // step sized for the largest would be a third of theirs, and their impacts would lose or
    // gain energy by tens of per cent.
    Case c = hooke_case(0.9);
    c.options.particles.diameter_scatter = 0.2;
    const ParticleOptions& particles = c.options.particles;
    const double d_small = particles.smallest_diameter_m();
    EXPECT_NEAR(d_small, 3e-3 * (1.0 - std::sqrt(3.0) * 0.2), 1e-15);
    const ExcitationContact chosen = with_automatic_time_step(
        choose_contact(particles, c.options.enclosure, NormalLaw::hooke, 0.9, std::nullopt, 0.01,
                       kTimeStepLadder[0], std::sqrt(2.0) * 2.0 * kStandardGravity, 6.37),
        c.options);
    const double m_small = particles.material.density_kg_m3 * kPi * std::pow(d_small, 3) / 6.0;
    EXPECT_NEAR(
        chosen.pair_contact_time_s / hooke_contact_time(0.5 * m_small, chosen.stiffness, 0.9), 1.0,
        1e-12);
    // Two of the smallest spheres at the chosen step against a step of 1/320 of their contact.
    SolverOptions o = c.options;
    o.contact.normal_stiffness = chosen.stiffness;
    const double v = chosen.impact_speed_m_s;
    double converged = 0.0;
    for (int k = 0; k < 8; ++k)
        converged += head_on_restitution(o, d_small, false, v, chosen.pair_contact_time_s / 320.0,
                                         (k + 0.5) / 8.0) /
                     8.0;
    double worst = 0.0;
    for (int k = 0; k < 8; ++k) {
        const double e =
            head_on_restitution(o, d_small, false, v, chosen.time_step_s, (k + 0.5) / 8.0);
        worst = std::max(worst, std::abs(e - converged) / converged);
    }
    EXPECT_LE(worst, kRestitutionWorstTolerance) << chosen.log;
    EXPECT_NEAR(converged, 0.9, 0.01);
}

TEST(AutomaticTimeStep, ANonPositiveContactTimeOrSpeedIsRefused) {
    const Case c = hooke_case(0.9);
    EXPECT_THROW(automatic_time_step_fraction(c.options, 0.0, 1.0), std::invalid_argument);
    EXPECT_THROW(automatic_time_step_fraction(c.options, 1e-4, 0.0), std::invalid_argument);
    EXPECT_THROW(
        automatic_time_step_fraction(c.options, std::numeric_limits<double>::quiet_NaN(), 1.0),
        std::invalid_argument);
}

}  // namespace
}  // namespace sb::dem

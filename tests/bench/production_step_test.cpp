// The DEM time step a campaign runs at by default resolves a collision well enough: the
// restitution it gives is the one set, within 1 %.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/campaign_spec.hpp"
#include "core/units.hpp"
#include "dem/setup.hpp"
#include "dem/solver.hpp"

namespace sb::bench {
namespace {

constexpr double kSpeed = 0.5;  // m/s: an impact of the paper-000 bed at about 2 g

/// Restitution of one normal impact at step dt: a sphere onto the floor (wall), or two
/// spheres head-on.
double measured_restitution(const dem::SolverOptions& base, bool wall, double dt) {
    dem::SolverOptions o = base;
    o.gravity_m_s2 = Eigen::Vector3d::Zero();
    o.particles.count = wall ? 1 : 2;
    o.enclosure.shape = dem::EnclosureShape::box;
    o.enclosure.length_x_m = o.enclosure.length_y_m = o.enclosure.height_m = 0.1;
    const double r = 0.5 * o.particles.diameter_m;
    dem::ParticleSet p;
    if (wall) {
        p.positions_m = {{0.0, 0.0, r + 1e-7}};
        p.velocities_m_s = {{0.0, 0.0, -kSpeed}};
    } else {
        p.positions_m = {{0.0, 0.0, 0.05}, {0.0, 0.0, 0.05 + 2.0 * r + 1e-7}};
        p.velocities_m_s = {{0.0, 0.0, 0.5 * kSpeed}, {0.0, 0.0, -0.5 * kSpeed}};
    }
    p.radii_m.assign(p.positions_m.size(), r);
    p.angular_velocities_rad_s.assign(p.positions_m.size(), Eigen::Vector3d::Zero());
    dem::Solver s(o, p);
    bool touched = false;
    for (int k = 0; k < 100000; ++k) {
        s.step(dt);
        if (s.contact_count() > 0) {
            touched = true;
        } else if (touched) {
            break;
        }
    }
    EXPECT_TRUE(touched);
    const auto& v = s.particles().v;
    return wall ? v[0].z() / kSpeed : (v[1].z() - v[0].z()) / kSpeed;
}

TEST(ProductionStep, TheDefaultTimeStepGivesTheSetRestitutionWithinOnePercent) {
    const DamperSpec damper;  // the config's defaults: particles, enclosure, contact
    for (const auto law : {dem::NormalLaw::hooke, dem::NormalLaw::hertz}) {
        for (const double e : {0.5, 0.9}) {
            // The stiffness and step a campaign chooses at 2 g near paper 000's first mode.
            const dem::ExcitationContact chosen = dem::choose_contact(
                damper.particles, damper.enclosure, law, e, std::nullopt,
                damper.contact.max_overlap_fraction, damper.contact.time_step_fraction,
                std::sqrt(2.0) * g_to_m_s2(2.0), 6.37);
            ContactSpec contact = damper.contact;
            contact.normal = law;
            contact.particle_particle.restitution = e;
            dem::SolverOptions options = damper.solver_options(chosen.stiffness);
            options.contact = contact.contact_options(chosen.stiffness);
            options.track_energy = false;
            for (const bool wall : {true, false}) {
                const double measured = measured_restitution(options, wall, chosen.time_step_s);
                EXPECT_NEAR(measured / e, 1.0, 0.01)
                    << (law == dem::NormalLaw::hooke ? "hooke" : "hertz") << " e = " << e
                    << (wall ? " on the wall" : " between two spheres") << ": " << measured
                    << " at dt = " << chosen.time_step_s << " s";
            }
        }
    }
}

}  // namespace
}  // namespace sb::bench

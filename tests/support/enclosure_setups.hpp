// Dampers alone whose describing function and energy are known in closed form, for the
// characterisation tests: one particle in a gap (the impact oscillator) and a held bed.
#pragma once

#include <Eigen/Core>

#include "bench/characterization.hpp"
#include "core/units.hpp"
#include "dem/setup.hpp"

namespace sb::test {

inline double sphere_mass_kg(double diameter_m, double density_kg_m3) {
    return density_kg_m3 * kPi / 6.0 * diameter_m * diameter_m * diameter_m;
}

/// a = A sin(w t) along the enclosure's axis, no rotation.
inline bench::HarmonicDrive drive_along_axis(double acceleration_m_s2, double frequency_hz) {
    bench::HarmonicDrive d;
    d.direction = Eigen::Vector3d::UnitZ();
    d.acceleration_m_s2 = acceleration_m_s2;
    d.frequency_hz = frequency_hz;
    return d;
}

/// One steel sphere (3 mm) on the axis of a cylinder with an axial free gap `gap_m`, no
/// gravity (so that the particle's motion is the textbook impact oscillator), no friction nor
/// rolling resistance, restitution `e` against the walls. Hooke walls of 1e5 N/m: the largest
/// overlap at the ~0.4 m/s impacts of the tests is 14 um, 0.3 % of a 5 mm gap, and the
/// contact lasts 0.1 ms, 1e-3 of a period at 10 Hz, so the impacts are short against the
/// motion.
inline bench::EnclosureSetup single_particle(double gap_m, double e) {
    bench::EnclosureSetup s;
    auto& o = s.options;
    o.particles.count = 1;
    o.particles.diameter_m = 3e-3;
    o.enclosure.inner_diameter_m = 10e-3;
    o.enclosure.height_m = 3e-3 + gap_m;
    o.contact.normal_stiffness = 1e5;
    o.contact.tangential = dem::TangentialLaw::none;
    o.contact.rolling = dem::RollingLaw::none;
    o.contact.particle_wall = {e, 0.0, 0.0};
    o.contact.particle_particle = {e, 0.0, 0.0};
    o.gravity_m_s2 = Eigen::Vector3d::Zero();
    s.bed.positions_m = {Eigen::Vector3d(0.0, 0.0, 1.5e-3 + 0.5 * gap_m)};
    s.bed.radii_m = {1.5e-3};
    // About 1/50 of the contact time pi sqrt(m/k) = 0.10 ms.
    s.dt_max_s = 2e-6;
    return s;
}

/// A bed of 30 spheres settled in the paper-000 enclosure under `gravity` (enclosure
/// frame = structure frame: axis along z), held by the lock (lock.fraction = 1, never
/// released).
inline bench::EnclosureSetup locked_bed(const Eigen::Vector3d& gravity) {
    bench::EnclosureSetup s;
    auto& o = s.options;
    o.particles.count = 30;
    o.contact.normal_stiffness = 2e4;
    o.gravity_m_s2 = gravity;
    o.track_energy = false;
    s.bed = dem::settle(o, dem::fill_random(o, 1));
    o.track_energy = true;
    o.lock.fraction = 1.0;
    s.dt_max_s = 1e-5;
    return s;
}

/// A characterisation cut short for the tests: two fillings, one thread, one transient
/// period, windows of `window_periods`, at most `max_periods`.
inline bench::CharacterizeOptions short_characterization(int frequency_count, int window_periods,
                                                         int max_periods) {
    bench::CharacterizeOptions options;
    options.frequency_count = frequency_count;
    options.seeds = 2;
    options.steady.window_periods = window_periods;
    options.steady.transient_periods = 1;
    options.steady.max_periods = max_periods;
    options.threads = 1;
    return options;
}

}  // namespace sb::test

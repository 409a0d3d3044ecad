// DEM throughput in particle-steps per second (docs/performance.md).
#include <benchmark/benchmark.h>

#include "dem/setup.hpp"
#include "dem/solver.hpp"
#include "dem_reference_problems.hpp"

namespace sb::dem {
namespace {

using perf::axial_wiggle;

/// (a) Paper-000 damper: 120 x 3 mm steel spheres, 19 x 25 mm cylinder, 6.3 Hz, 3 g along the
/// axis, Hooke k = 2e5 N/m, e = 0.9, history-spring friction 0.6, dt = 2e-6 s (as the LAMMPS
/// comparison). Arg 0: threads; arg 1: energy ledger on/off.
void BM_Paper000Damper(benchmark::State& st) {
    SolverOptions o;
    o.contact.normal_stiffness = 2e5;
    o.contact.tangential = TangentialLaw::coulomb_spring;
    o.contact.rolling = RollingLaw::none;
    o.threads = static_cast<int>(st.range(0));
    o.track_energy = st.range(1) != 0;
    const double w = kTwoPi * 6.3, amp = 3 * kStandardGravity / (w * w), dt = 2e-6;
    Solver s(o, fill_random(o, 2021), axial_wiggle(0.0, amp, w));
    long k = 0;
    for (int q = 0; q < 200000; ++q, ++k) {  // 0.4 s: past the start-up transient
        s.set_enclosure_state(axial_wiggle(static_cast<double>(k) * dt, amp, w));
        s.step(dt);
    }
    for (auto _ : st) {
        s.set_enclosure_state(axial_wiggle(static_cast<double>(k++) * dt, amp, w));
        s.step(dt);
    }
    st.SetItemsProcessed(st.iterations() * 120);
    st.counters["contacts"] = static_cast<double>(s.contact_count());
}
BENCHMARK(BM_Paper000Damper)
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({2, 0})
    ->Iterations(300000)
    ->UseRealTime();

/// Fixed iteration counts: every variant runs the same trajectory (bitwise identical for any
/// thread count), so the numbers compare like with like.
/// (b) 5,000 x 2 mm steel spheres in a 30 x 30 x 50 mm box (paper 002 cavity) starting from a
/// touching cubic lattice, shaken vertically at 100 Hz, 5 g; Hooke k = 1e5 N/m, dt = 2e-6 s.
void BM_Box5000(benchmark::State& st) {
    SolverOptions o = perf::paper002_cavity_options(5000);
    o.threads = static_cast<int>(st.range(0));
    o.track_energy = st.range(1) != 0;
    ParticleSet p;
    for (int i = 0; i < 5000; ++i) {
        const int ix = i % 15, iy = (i / 15) % 15, iz = i / 225;
        p.positions_m.emplace_back(-14e-3 + 2e-3 * ix, -14e-3 + 2e-3 * iy, 1e-3 + 2.05e-3 * iz);
        p.radii_m.push_back(1e-3);
    }
    const double w = kTwoPi * 100.0, amp = 5 * kStandardGravity / (w * w), dt = 2e-6;
    Solver s(o, p, axial_wiggle(0.0, amp, w));
    long k = 0;
    for (int q = 0; q < 5000; ++q, ++k) {
        s.set_enclosure_state(axial_wiggle(static_cast<double>(k) * dt, amp, w));
        s.step(dt);
    }
    for (auto _ : st) {
        s.set_enclosure_state(axial_wiggle(static_cast<double>(k++) * dt, amp, w));
        s.step(dt);
    }
    st.SetItemsProcessed(st.iterations() * 5000);
    st.counters["contacts"] = static_cast<double>(s.contact_count());
}
BENCHMARK(BM_Box5000)->Args({1, 0})->Args({2, 0})->Args({1, 1})->Iterations(5000)->UseRealTime();

}  // namespace
}  // namespace sb::dem

BENCHMARK_MAIN();

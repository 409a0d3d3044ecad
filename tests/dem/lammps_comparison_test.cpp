// Cross-check against LAMMPS (validation/lammps/in.damper): the paper-000 damper (120 x 3 mm
// steel spheres, 19 x 25 mm cylinder) shaken along its axis at 6.3 Hz, 3 g, gravity along the
// axis; same Hooke law, e = 0.9, history-spring friction 0.6, no rolling resistance. The
// time-averaged dissipated power must agree within 10 %. Skipped when `lmp` is missing.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "dem/setup.hpp"
#include "dem/solver.hpp"
#include "test_helpers.hpp"

namespace sb::dem {
namespace {

/// The brief's requirement.
constexpr double kPowerTolerance = 0.10;

struct RunSetup {
    double frequency_hz = 6.3;
    double level_m_s2 = 3.0 * kStandardGravity;
    double k = 2e5;    ///< [N/m]; overlap ~1.4 % of d at 1.8 m/s
    double dt = 2e-6;  ///< ~ t_c(pp) / 26
    int periods = 12;
    int skip_periods = 4;  ///< transient from the random fill
    int every = 10;        ///< LAMMPS sampling [steps]
};

SolverOptions options_for(const RunSetup& r) {
    SolverOptions o = test::paper000_options();
    o.contact.normal_stiffness = r.k;
    o.contact.tangential = TangentialLaw::coulomb_spring;
    o.contact.rolling = RollingLaw::none;
    o.contact.particle_particle = {0.9, 0.6, 0.0};
    o.contact.particle_wall = {0.9, 0.6, 0.0};
    o.track_energy = true;
    return o;
}

double run_lammps(const RunSetup& r, const SolverOptions& o, const ParticleSet& p,
                  const std::filesystem::path& dir) {
    const double m = 7800.0 * kPi / 6.0 * 27e-9;
    const double zeta = linear_zeta_from_restitution(0.9);
    const double eta_pp = 2.0 * zeta * std::sqrt(r.k * 0.5 * m),
                 eta_pw = 2.0 * zeta * std::sqrt(r.k * m);
    {
        std::ofstream d(dir / "damper.data");
        d << std::setprecision(17) << "ShakerBench fill\n\n"
          << p.positions_m.size()
          << " atoms\n1 atom types\n-0.012 0.012 xlo xhi\n-0.012 0.012 ylo yhi\n"
             "-0.005 0.07 zlo zhi\n\nAtoms # sphere\n\n";
        for (std::size_t i = 0; i < p.positions_m.size(); ++i) {
            d << i + 1 << " 1 " << 2 * p.radii_m[i] << " 7800 " << p.positions_m[i].x() << ' '
              << p.positions_m[i].y() << ' ' << p.positions_m[i].z() << '\n';
        }
    }
    const double w = kTwoPi * r.frequency_hz, amp = r.level_m_s2 / (w * w);
    const auto steps = static_cast<long>(std::lround(r.periods / r.frequency_hz / r.dt));
    std::ostringstream cmd;
    cmd << std::setprecision(17) << "cd " << dir << " && lmp -log none -screen none -in "
        << SB_SOURCE_DIR << "/validation/lammps/in.damper -var data damper.data -var out series.txt"
        << " -var dt " << r.dt << " -var steps " << steps << " -var kn " << r.k << " -var kt "
        << o.contact.tangential_stiffness_ratio * r.k << " -var etapp " << eta_pp << " -var etapw "
        << eta_pw << " -var amp " << amp << " -var omega " << w << " -var every " << r.every;
    if (std::system(cmd.str().c_str()) != 0) return std::nan("");
    // Wall work by parts: W = [P_z v] - int P_z a dt + M g [z_enc]; D = W - dE.
    std::ifstream in(dir / "series.txt");
    std::string line;
    const double t0 = r.skip_periods / r.frequency_hz, t1 = r.periods / r.frequency_hz;
    const double mass = m * static_cast<double>(p.positions_m.size());
    double w_int = 0.0, prev_t = -1.0, prev_pa = 0.0;
    double e0 = 0.0, e1 = 0.0, pv0 = 0.0, pv1 = 0.0;
    bool started = false;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        double step, t, pz, ke, erot, pe, vz;
        ls >> step >> t >> pz >> ke >> erot >> pe >> vz;
        if (t < t0 - 1e-12 || t > t1 + 1e-12) continue;
        const double a = amp * w * w * std::cos(w * t);
        const double e = ke + erot + pe;
        if (!started) {
            started = true;
            e0 = e;
            pv0 = pz * vz;
        } else {
            w_int += 0.5 * (prev_pa + pz * a) * (t - prev_t);
        }
        prev_t = t;
        prev_pa = pz * a;
        e1 = e;
        pv1 = pz * vz;
    }
    const double z0 = amp * (1 - std::cos(w * t0)), z1 = amp * (1 - std::cos(w * t1));
    const double work = (pv1 - pv0) - w_int + mass * kStandardGravity * (z1 - z0);
    return (work - (e1 - e0)) / (t1 - t0);
}

double run_ours(const RunSetup& r, const SolverOptions& o, const ParticleSet& p) {
    const double w = kTwoPi * r.frequency_hz, amp = r.level_m_s2 / (w * w);
    auto state = [&](double t) {
        EnclosureState e;
        e.position_m = Eigen::Vector3d(0, 0, amp * (1 - std::cos(w * t)));
        e.velocity_m_s = Eigen::Vector3d(0, 0, amp * w * std::sin(w * t));
        return e;
    };
    Solver s(o, p, state(0.0));
    const auto steps = std::lround(r.periods / r.frequency_hz / r.dt);
    const auto skip = std::lround(r.skip_periods / r.frequency_hz / r.dt);
    double d0 = 0.0;
    for (long k = 0; k < steps; ++k) {
        if (k == skip) d0 = s.energy().dissipated();
        s.set_enclosure_state(state(static_cast<double>(k) * r.dt));
        s.step(r.dt);
    }
    return (s.energy().dissipated() - d0) / (static_cast<double>(steps - skip) * r.dt);
}

TEST(LammpsComparison, DissipatedPowerOfThePaper000DamperMatchesWithinTenPercent) {
    if (std::system("command -v lmp > /dev/null 2>&1") != 0) GTEST_SKIP() << "lmp not found";
    const RunSetup r;
    const SolverOptions o = options_for(r);
    const ParticleSet p = fill_random(o, 2021);
    const auto dir = std::filesystem::temp_directory_path() / "sb_dem_lammps";
    std::filesystem::create_directories(dir);
    const auto c0 = std::chrono::steady_clock::now();
    const double lammps = run_lammps(r, o, p, dir);
    const auto c1 = std::chrono::steady_clock::now();
    ASSERT_TRUE(std::isfinite(lammps)) << "lmp failed; see " << dir;
    const double ours = run_ours(r, o, p);
    const auto c2 = std::chrono::steady_clock::now();
    const double tl = std::chrono::duration<double>(c1 - c0).count();
    const double to = std::chrono::duration<double>(c2 - c1).count();
    std::printf("dissipated power: ShakerBench %.6g W, LAMMPS %.6g W, ratio %.4f\n", ours, lammps,
                ours / lammps);
    std::printf("wall time: ShakerBench %.2f s, LAMMPS %.2f s\n", to, tl);
    RecordProperty("power_shakerbench_w", std::to_string(ours));
    RecordProperty("power_lammps_w", std::to_string(lammps));
    EXPECT_GT(lammps, 0.0);
    EXPECT_NEAR(ours, lammps, kPowerTolerance * lammps);
}

}  // namespace
}  // namespace sb::dem

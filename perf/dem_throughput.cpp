// DEM throughput on the two reference problems of docs/performance.md, for the side-by-side
// run against LAMMPS (perf/run_dem_vs_lammps.sh):
//   (a) the paper-000 damper: 120 x 3 mm steel spheres in the 19 x 25 mm cylinder, 6.3 Hz,
//       3 g along the axis (gravity along the axis), Hooke k = 2e5 N/m, e = 0.9, history
//       spring with friction 0.6, no rolling resistance, dt = 2 us (as validation/lammps);
//   (b) 5,000 x 2 mm steel spheres in paper 002's 30 x 30 x 50 mm cavity, settled under
//       gravity from a body-centred lattice, then shaken along z at 120 Hz, 10.5 g (paper
//       002 section 4), Hooke k = 1e5 N/m, same pair properties, dt = 2 us.
// Both enclosures move as z = A (1 - cos wt), like LAMMPS's `wiggle` and `in.damper`.
//   (c) the damper of (a) as paper 000's campaign runs it (not a LAMMPS problem): gravity
//       across the axis, directional Coulomb with rolling resistance, k = 4.24e5 N/m,
//       dt = t_c/20, 2 g RMS at 6.37 Hz, the enclosure rocking by 0.04 rad with the beam.
//
// Usage: dem_throughput a|b|c [--threads N] [--warmup STEPS] [--steps STEPS] [--ledger 0|1]
//                           [--bed FILE] [--count N] [--write-lammps-data FILE]
//                           [--skin FRACTION] [--adapt-skin 0|1] [--level-g PEAK]
// --skin: the Verlet skin over the largest diameter (default 0.1; the largest one with
// --adapt-skin 1, the default; --adapt-skin 0 keeps it fixed, as LAMMPS's). --level-g: the
// peak acceleration of the shaking in g. The line printed ends with the neighbour-list builds
// and the skin the run ended with (skin_m).
// --count (case b): N spheres, the cavity's footprint scaled by N / 5,000 (default 5,000).
// --bed (case b): settled bed cache; read if present, else settled and written.
// --settled-csv FILE (case b): instead, a bed the bench poured (OUT/settled/*.csv of `run` or
// `characterize`, in paper 002's cavity): its spheres, count and size, the cavity unscaled;
// --order cell sorts them by cell of the neighbour grid first (default: as poured);
// --grid-quarter 1: the bed was poured in a quarter of paper 002's grid cavity (15 x 15 mm
// among 1 mm rods on 5 mm cells, validation/paper002/table2.sh), which it is then shaken in.
// --write-lammps-data: writes the initial state as a LAMMPS `atom_style sphere` data file
// and exits; --lammps-vars 1 prints the matching `-var` arguments of validation/lammps/
// in.damper (a) or in.box5000 (b) and exits. Otherwise prints one line `key=value ...` with
// particle-steps/s of the timed steps and a hash of the final state (state_hash: equal
// hashes mean bitwise equal runs).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "config/write.hpp"
#include "dem/setup.hpp"
#include "dem/solver.hpp"
#include "dem_reference_problems.hpp"

namespace {

using namespace sb::dem;

struct Case {
    SolverOptions options;
    double frequency_hz = 0.0;
    double level_m_s2 = 0.0;
    double dt_s = 2e-6;
    long warmup_steps = 0;
    long steps = 0;
    bool rocking = false;  ///< the enclosure turns with a beam's slope (case c)
};

Case case_a() {
    Case c;
    SolverOptions& o = c.options;
    o.particles.count = 120;
    o.particles.diameter_m = 3e-3;
    o.contact.normal_stiffness = 2e5;
    o.contact.tangential = TangentialLaw::coulomb_spring;
    o.contact.rolling = RollingLaw::none;
    o.contact.particle_particle = {0.9, 0.6, 0.0};
    o.contact.particle_wall = {0.9, 0.6, 0.0};
    c.frequency_hz = 6.3;
    c.level_m_s2 = 3.0 * sb::kStandardGravity;
    c.warmup_steps = 200000;  // 0.4 s: past the start-up transient of the random fill
    c.steps = 300000;
    return c;
}

/// The damper of case a as paper 000's campaign runs it (the H-0 sweep at 2 g near the first
/// mode, docs/performance.md): gravity across the cylinder's axis, the paper's directional
/// Coulomb law with rolling resistance, the contact sized for the campaign's 5 g (4.24e5 N/m,
/// t_c/20, the automatic step until t_c/10 replaced it: kept so that instruction counts and
/// state hashes compare) and the enclosure rocking with the beam's slope, so that every
/// position goes through the rotated frame as in a coupled run. Not a LAMMPS problem.
Case case_c() {
    Case c = case_a();
    SolverOptions& o = c.options;
    o.contact.normal_stiffness = 4.243e5;
    o.contact.tangential = TangentialLaw::directional_coulomb;
    o.contact.rolling = RollingLaw::constant_torque;
    o.contact.particle_particle = {0.9, 0.6, 0.01};
    o.contact.particle_wall = {0.9, 0.6, 0.01};
    o.gravity_m_s2 = Eigen::Vector3d(-sb::kStandardGravity, 0.0, 0.0);
    c.frequency_hz = 6.37;
    c.level_m_s2 = 2.0 * std::sqrt(2.0) * sb::kStandardGravity;  // 2 g RMS
    c.dt_s = 1.7917e-6;
    c.rocking = true;
    return c;
}

/// count spheres: paper 002's cavity for 5,000, its footprint scaled by count / 5,000 for
/// other counts (same depth of bed, so the same contacts per sphere: for the scaling in N).
Case case_b(int count) {
    Case c;
    c.options = sb::dem::perf::paper002_cavity_options(count);
    const double scale = std::sqrt(static_cast<double>(count) / 5000.0);
    c.options.enclosure.length_x_m *= scale;
    c.options.enclosure.length_y_m *= scale;
    SolverOptions& o = c.options;
    o.contact.tangential = TangentialLaw::coulomb_spring;
    o.contact.rolling = RollingLaw::none;
    o.contact.particle_particle = {0.9, 0.6, 0.0};
    o.contact.particle_wall = {0.9, 0.6, 0.0};
    c.frequency_hz = 120.0;
    c.level_m_s2 = 10.5 * sb::kStandardGravity;
    c.warmup_steps = 5000;
    c.steps = 10000;
    return c;
}

/// The beam's slope at the damper in case c: 0.04 rad at the tip displacement's peak.
constexpr double kRockingAmplitudeRad = 0.04;

EnclosureState shaken(const Case& c, double t) {
    const double w = sb::kTwoPi * c.frequency_hz, amp = c.level_m_s2 / (w * w);
    EnclosureState e = sb::dem::perf::axial_wiggle(t, amp, w);
    if (c.rocking) {  // the slope follows the displacement from its mean
        const double theta = -kRockingAmplitudeRad * std::cos(w * t);
        e.rotation = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()).toRotationMatrix();
        e.angular_velocity_rad_s =
            Eigen::Vector3d(0.0, kRockingAmplitudeRad * w * std::sin(w * t), 0.0);
    }
    return e;
}

/// Body-centred layers (15 x 15 on the corners, 14 x 14 on the centres) with 5 um gaps, so
/// that the bed settles into a dense packing instead of standing in columns.
ParticleSet bcc_lattice(const SolverOptions& o) {
    ParticleSet p;
    const double d = o.particles.diameter_m, r = 0.5 * d, gap = 5e-6;
    const double lx = o.enclosure.length_x_m;
    const double dz = std::sqrt(0.5) * (d + gap);  // touching spheres offset by (d/2, d/2)
    int placed = 0;
    for (int layer = 0; placed < o.particles.count; ++layer) {
        const bool centre = layer % 2 == 1;
        const int per_row =
            static_cast<int>(std::floor((lx - (centre ? 2 * d : d)) / d + 1e-9)) + 1;
        const double x0 = -0.5 * (per_row - 1) * d;
        for (int iy = 0; iy < per_row && placed < o.particles.count; ++iy) {
            for (int ix = 0; ix < per_row && placed < o.particles.count; ++ix, ++placed) {
                p.positions_m.emplace_back(x0 + ix * d, x0 + iy * d, r + gap + layer * dz);
                p.radii_m.push_back(r);
            }
        }
    }
    return p;
}

void write_bed(const std::filesystem::path& path, const ParticleSet& p) {
    std::ofstream out(path);
    out << std::setprecision(17);
    for (std::size_t i = 0; i < p.positions_m.size(); ++i) {
        out << p.positions_m[i].transpose() << ' ' << p.radii_m[i] << ' '
            << p.velocities_m_s[i].transpose() << ' ' << p.angular_velocities_rad_s[i].transpose()
            << '\n';
    }
}

[[noreturn]] void usage(const std::string& why);

/// A bed the bench wrote (bench/settled_bed.hpp): a header line, then per sphere
/// x, y, z, radius, velocity and angular velocity, comma-separated, in the enclosure frame.
ParticleSet read_settled_csv(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::string line;
    if (!std::getline(in, line) || line.rfind("x_m,", 0) != 0) {
        usage(path.string() + ": not a settled bed (its first line is not the x_m,... header)");
    }
    ParticleSet p;
    for (int number = 2; std::getline(in, line); ++number) {
        std::istringstream cells(line);
        double v[10];
        for (double& value : v) {
            std::string cell;
            char* end = nullptr;
            if (!std::getline(cells, cell, ',') ||
                (value = std::strtod(cell.c_str(), &end), end == cell.c_str() || *end != '\0')) {
                usage(path.string() + ":" + std::to_string(number) + ": expected 10 numbers");
            }
        }
        p.positions_m.emplace_back(v[0], v[1], v[2]);
        p.radii_m.push_back(v[3]);
        p.velocities_m_s.emplace_back(v[4], v[5], v[6]);
        p.angular_velocities_rad_s.emplace_back(v[7], v[8], v[9]);
    }
    if (p.radii_m.empty()) usage(path.string() + ": no spheres");
    return p;
}

/// The spheres ordered by cell (z, then y, then x) of side `cell_m` from the cavity's corner:
/// neighbours near each other in memory, as a sort at list rebuilds would keep them.
ParticleSet ordered_by_cell(const ParticleSet& p, const Eigen::Vector3d& corner_m, double cell_m) {
    std::vector<std::size_t> order(p.radii_m.size());
    std::vector<std::array<long, 3>> cell(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        order[i] = i;
        for (int a = 0; a < 3; ++a) {
            cell[i][static_cast<std::size_t>(2 - a)] =
                std::lround(std::floor((p.positions_m[i][a] - corner_m[a]) / cell_m));
        }
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return cell[a] < cell[b]; });
    ParticleSet sorted;
    for (const std::size_t i : order) {
        sorted.positions_m.push_back(p.positions_m[i]);
        sorted.radii_m.push_back(p.radii_m[i]);
        sorted.velocities_m_s.push_back(p.velocities_m_s[i]);
        sorted.angular_velocities_rad_s.push_back(p.angular_velocities_rad_s[i]);
    }
    return sorted;
}

ParticleSet read_bed(const std::filesystem::path& path) {
    ParticleSet p;
    std::ifstream in(path);
    double v[10];
    while (in >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> v[7] >> v[8] >> v[9]) {
        p.positions_m.emplace_back(v[0], v[1], v[2]);
        p.radii_m.push_back(v[3]);
        p.velocities_m_s.emplace_back(v[4], v[5], v[6]);
        p.angular_velocities_rad_s.emplace_back(v[7], v[8], v[9]);
    }
    return p;
}

/// Lets the lattice fall and rest in the static cavity: 0.03 s with e = 0.5 (faster to come
/// to rest), then 0.01 s with the benchmark's own law.
ParticleSet settled_bed(const Case& c) {
    SolverOptions o = c.options;
    o.track_energy = false;
    o.threads = 0;
    ParticleSet p = bcc_lattice(o);
    for (int phase = 0; phase < 2; ++phase) {
        SolverOptions op = o;
        if (phase == 0) op.contact.particle_particle.restitution = 0.5;
        if (phase == 0) op.contact.particle_wall.restitution = 0.5;
        Solver s(op, p);
        const long steps = std::lround((phase == 0 ? 0.03 : 0.01) / c.dt_s);
        for (long k = 0; k < steps; ++k) s.step(c.dt_s);
        p = s.local_snapshot();
    }
    return p;
}

void write_lammps_data(const std::filesystem::path& path, const Case& c, const ParticleSet& p) {
    const auto& e = c.options.enclosure;
    const double hx = e.shape == EnclosureShape::box ? 0.5 * e.length_x_m + 1e-3
                                                     : 0.5 * e.inner_diameter_m + 2.5e-3;
    const double hy = e.shape == EnclosureShape::box ? 0.5 * e.length_y_m + 1e-3 : hx;
    std::ofstream d(path);
    d << std::setprecision(17) << "ShakerBench initial state\n\n"
      << p.positions_m.size() << " atoms\n1 atom types\n"
      << -hx << ' ' << hx << " xlo xhi\n"
      << -hy << ' ' << hy << " ylo yhi\n"
      << -5e-3 << ' ' << e.height_m + 20e-3 << " zlo zhi\n\nAtoms # sphere\n\n";
    const double rho = c.options.particles.material.density_kg_m3;
    for (std::size_t i = 0; i < p.positions_m.size(); ++i) {
        d << i + 1 << " 1 " << 2 * p.radii_m[i] << ' ' << rho << ' ' << p.positions_m[i].x() << ' '
          << p.positions_m[i].y() << ' ' << p.positions_m[i].z() << '\n';
    }
    if (!p.velocities_m_s.empty()) {
        d << "\nVelocities\n\n";
        for (std::size_t i = 0; i < p.positions_m.size(); ++i) {
            d << i + 1 << ' ' << p.velocities_m_s[i].transpose() << ' '
              << p.angular_velocities_rad_s[i].transpose() << '\n';
        }
    }
}

/// FNV-1a (config::fnv1a_hex) over the bytes of the particles' positions, velocities and spins
/// and the last wall force and moment: equal hashes mean bitwise equal runs (for A/B builds of
/// the solver).
std::string state_hash(const Solver& s) {
    std::string bytes;
    auto append = [&bytes](const Eigen::Vector3d& v) {
        bytes.append(reinterpret_cast<const char*>(v.data()), 3 * sizeof(double));
    };
    const ParticleState& p = s.particles();
    for (std::size_t i = 0; i < p.size(); ++i) {
        append(p.x[i]);
        append(p.v[i]);
        append(p.w[i]);
    }
    append(s.wall_force());
    append(s.wall_moment());
    return sb::config::fnv1a_hex(bytes);
}

/// The timed steps, in a function of their own so that profilers can select them
/// (valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*timed_steps*').
[[gnu::noinline]] double timed_steps(Solver& s, const Case& c, long& k) {
    double contacts = 0.0;
    for (long q = 0; q < c.steps; ++q, ++k) {
        s.set_enclosure_state(shaken(c, static_cast<double>(k) * c.dt_s));
        s.step(c.dt_s);
        contacts += static_cast<double>(s.contact_count());
    }
    return contacts;
}

/// LAMMPS `-var` arguments for the same law, excitation and step counts: damping
/// eta = 2 zeta sqrt(k m*) with zeta from the restitution (no tensile force on both sides).
std::string lammps_vars(const Case& c) {
    const auto& o = c.options;
    const double d = o.particles.diameter_m;
    const double m = o.particles.material.density_kg_m3 * sb::kPi / 6.0 * d * d * d;
    const double k = o.contact.normal_stiffness;
    const double zeta = linear_zeta_from_restitution(o.contact.particle_particle.restitution);
    const double zeta_w = linear_zeta_from_restitution(o.contact.particle_wall.restitution);
    const double w = sb::kTwoPi * c.frequency_hz;
    std::ostringstream v;
    v << std::setprecision(12) << "-var dt " << c.dt_s << " -var warmup " << c.warmup_steps
      << " -var steps " << c.steps << " -var kn " << k << " -var kt "
      << o.contact.tangential_stiffness_ratio * k << " -var etapp "
      << 2.0 * zeta * std::sqrt(k * 0.5 * m) << " -var etapw " << 2.0 * zeta_w * std::sqrt(k * m)
      << " -var amp " << c.level_m_s2 / (w * w) << " -var omega " << w << " -var period "
      << 1.0 / c.frequency_hz << " -var skin " << o.neighbor_skin_fraction * d;
    if (o.enclosure.shape == EnclosureShape::box) {
        v << " -var half_x " << 0.5 * o.enclosure.length_x_m << " -var half_y "
          << 0.5 * o.enclosure.length_y_m << " -var height " << o.enclosure.height_m;
    }
    return v.str();
}

[[noreturn]] void usage(const std::string& why) {
    std::cerr << "dem_throughput: " << why
              << "\nusage: dem_throughput a|b|c [--threads N] [--warmup STEPS] [--steps STEPS]"
                 " [--ledger 0|1] [--bed FILE] [--count N (case b)] [--write-lammps-data FILE]"
                 " [--lammps-vars 1] [--skin FRACTION] [--adapt-skin 0|1] [--level-g PEAK]"
                 " [--settled-csv FILE [--order poured|cell] [--grid-quarter 0|1] (case b)]\n";
    std::exit(2);
}

long parse_long(const std::string& key, const char* text) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < 0) usage(key + ": expected a non-negative integer");
    return v;
}

/// A number in (0, max].
double parse_positive(const std::string& key, const char* text, double max) {
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(v > 0.0 && v <= max)) {
        std::ostringstream why;
        why << key << ": expected a number in (0, " << max << "]";
        usage(why.str());
    }
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) usage("missing case");
    const std::string name = argv[1];
    if (name != "a" && name != "b" && name != "c") {
        usage("case must be a, b or c, got '" + name + "'");
    }
    int count_b = 5000;
    for (int k = 2; k + 1 < argc; k += 2) {  // the case's size first: the others override it
        if (std::string(argv[k]) == "--count") {
            count_b = static_cast<int>(parse_long("--count", argv[k + 1]));
        }
    }
    if (count_b < 1 || count_b > 10000000) usage("--count: expected 1 to 10000000 spheres");
    if (name != "b" && count_b != 5000) usage("--count applies to case b only");
    Case c = name == "a" ? case_a() : name == "c" ? case_c() : case_b(count_b);
    int threads = 1;
    bool ledger = false;
    std::string bed, lammps_data, settled_csv, order = "poured";
    bool print_lammps_vars = false, grid_quarter = false;
    for (int k = 2; k < argc; ++k) {
        const std::string key = argv[k];
        if (k + 1 >= argc) usage(key + ": missing value");
        const char* value = argv[++k];
        if (key == "--threads") {
            threads = static_cast<int>(parse_long(key, value));
        } else if (key == "--warmup") {
            c.warmup_steps = parse_long(key, value);
        } else if (key == "--steps") {
            c.steps = parse_long(key, value);
        } else if (key == "--ledger") {
            ledger = parse_long(key, value) != 0;
        } else if (key == "--count") {
            // read above
        } else if (key == "--bed") {
            bed = value;
        } else if (key == "--settled-csv") {
            settled_csv = value;
        } else if (key == "--grid-quarter") {
            grid_quarter = parse_long(key, value) != 0;
        } else if (key == "--order") {
            order = value;
            if (order != "poured" && order != "cell") usage("--order: expected poured or cell");
        } else if (key == "--level-g") {
            c.level_m_s2 = parse_positive(key, value, 1000.0) * sb::kStandardGravity;
        } else if (key == "--adapt-skin") {
            c.options.adapt_neighbor_skin = parse_long(key, value) != 0;
        } else if (key == "--skin") {
            c.options.neighbor_skin_fraction = parse_positive(key, value, 1.0);
        } else if (key == "--lammps-vars") {
            print_lammps_vars = parse_long(key, value) != 0;
        } else if (key == "--write-lammps-data") {
            lammps_data = value;
        } else {
            usage("unknown option " + key);
        }
    }
    c.options.threads = threads;
    c.options.track_energy = ledger;
    if (print_lammps_vars) {
        std::cout << lammps_vars(c) << '\n';
        return 0;
    }

    if (!settled_csv.empty() && (name != "b" || !bed.empty() || count_b != 5000)) {
        usage("--settled-csv applies to case b, without --bed and --count");
    }
    if (grid_quarter && settled_csv.empty()) {
        usage("--grid-quarter 1 needs --settled-csv (a bed poured among the rods)");
    }
    if (grid_quarter) {  // validation/paper002/table2.sh's quarter of the grid's cavity
        auto& e = c.options.enclosure;
        e.length_x_m = 15e-3;
        e.length_y_m = 15e-3;
        e.rods.enabled = true;
        e.rods.rod_diameter_m = 1e-3;
        e.rods.cell_size_m = 5e-3;
        e.rods.origin_m = Eigen::Vector3d(2.5e-3, 2.5e-3, 0.0);
    }
    ParticleSet p;
    if (name != "b") {
        p = fill_random(c.options, 2021);
    } else if (!settled_csv.empty()) {
        p = read_settled_csv(settled_csv);
        c.options.particles.count = static_cast<int>(p.radii_m.size());
        c.options.particles.diameter_m =
            2.0 * *std::max_element(p.radii_m.begin(), p.radii_m.end());
        if (order == "cell") {
            const auto& e = c.options.enclosure;
            const double cell_m =
                c.options.particles.diameter_m * (1.0 + c.options.neighbor_skin_fraction);
            p = ordered_by_cell(p, Eigen::Vector3d(-0.5 * e.length_x_m, -0.5 * e.length_y_m, 0.0),
                                cell_m);
        }
    } else if (!bed.empty() && std::filesystem::exists(bed)) {
        p = read_bed(bed);
    } else {
        p = settled_bed(c);
        if (!bed.empty()) write_bed(bed, p);
    }
    if (!lammps_data.empty()) {
        write_lammps_data(lammps_data, c, p);
        return 0;
    }
    try {
        Solver s(c.options, p, shaken(c, 0.0));
        long k = 0;
        for (; k < c.warmup_steps; ++k) {
            s.set_enclosure_state(shaken(c, static_cast<double>(k) * c.dt_s));
            s.step(c.dt_s);
        }
        const auto t0 = std::chrono::steady_clock::now();
        const std::clock_t cpu0 = std::clock();
        const double contacts = timed_steps(s, c, k);
        // process CPU time (all threads): on a shared host it excludes the time the process
        // waited for a core, which wall time does not
        const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double n = static_cast<double>(p.positions_m.size());
        std::printf(
            "case=%s threads=%d ledger=%d particles=%.0f steps=%ld wall_s=%.4f cpu_s=%.4f "
            "us_per_step=%.4g particle_steps_per_s=%.4g particle_steps_per_cpu_s=%.4g "
            "mean_contacts=%.1f neighbor_builds=%lld skin_m=%.6g state_hash=%s\n",
            name.c_str(), threads, ledger ? 1 : 0, n, c.steps, wall, cpu,
            1e6 * wall / static_cast<double>(c.steps), n * static_cast<double>(c.steps) / wall,
            n * static_cast<double>(c.steps) / cpu,
            contacts / static_cast<double>(std::max(1L, c.steps)),
            static_cast<long long>(s.neighbor_builds()), s.neighbor_skin(), state_hash(s).c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "dem_throughput: %s\n", e.what());
        return 1;
    }
    return 0;
}

// Set-up helpers: radii, random filling, settling, particle files, VTK, automatic stiffness.
#include "dem/setup.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <random>
#include <sstream>
#include <stdexcept>

namespace sb::dem {

namespace {
/// Portable uniform [0,1) from the raw 64-bit engine output (std distributions differ).
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
}  // namespace

std::vector<double> make_radii(const ParticleOptions& o, std::uint64_t seed) {
    const auto n = static_cast<std::size_t>(std::max(0, o.count));
    if (o.size_distribution.empty()) return std::vector<double>(n, 0.5 * o.diameter_m);
    std::vector<std::size_t> counts(o.size_distribution.size());
    std::vector<std::pair<double, std::size_t>> rem;
    std::size_t total = 0;
    for (std::size_t k = 0; k < counts.size(); ++k) {
        const double exact = o.size_distribution[k].number_fraction * static_cast<double>(n);
        counts[k] = static_cast<std::size_t>(std::floor(exact));
        total += counts[k];
        rem.emplace_back(-(exact - std::floor(exact)), k);
    }
    std::sort(rem.begin(), rem.end());
    for (std::size_t q = 0; total < n; ++q, ++total) ++counts[rem[q % rem.size()].second];
    std::vector<double> r;
    for (std::size_t k = 0; k < counts.size(); ++k) {
        r.insert(r.end(), counts[k], 0.5 * o.size_distribution[k].diameter_m);
    }
    std::mt19937_64 rng(seed);
    for (std::size_t i = r.size(); i > 1; --i) {  // Fisher-Yates with the portable uniform
        const auto j = static_cast<std::size_t>(uniform01(rng) * static_cast<double>(i));
        std::swap(r[i - 1], r[std::min(j, i - 1)]);
    }
    return r;
}

ParticleSet fill_random(const SolverOptions& options, std::uint64_t seed, int max_attempts) {
    const Enclosure enc(options.enclosure);
    ParticleSet s;
    std::vector<double> radii = make_radii(options.particles, seed);
    std::vector<std::size_t> order(radii.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return radii[a] > radii[b]; });
    std::mt19937_64 rng(seed ^ 0x9E3779B97F4A7C15ull);
    s.positions_m.assign(radii.size(), Eigen::Vector3d::Zero());
    s.radii_m = radii;
    std::vector<std::size_t> placed;
    const Eigen::Vector3d lo = enc.lower(), hi = enc.upper();
    for (std::size_t i : order) {
        const double r = radii[i];
        bool ok = false;
        for (int a = 0; a < max_attempts && !ok; ++a) {
            Eigen::Vector3d x;
            for (int d = 0; d < 3; ++d) {
                x[d] = lo[d] + r + uniform01(rng) * std::max(0.0, hi[d] - lo[d] - 2.0 * r);
            }
            if (!enc.contains(x) || enc.clearance(x) < r * (1.0 + 1e-9)) continue;
            ok = true;
            for (std::size_t j : placed) {
                const double rs = r + radii[j];
                if ((x - s.positions_m[j]).squaredNorm() < rs * rs * (1.0 + 1e-9)) {
                    ok = false;
                    break;
                }
            }
            if (ok) s.positions_m[i] = x;
        }
        if (!ok) {
            throw std::runtime_error("fill_random: could not place particle " +
                                     std::to_string(placed.size() + 1) + " of " +
                                     std::to_string(radii.size()) +
                                     " without overlap; the cavity is too full for random "
                                     "insertion (use a taller cavity and settle)");
        }
        placed.push_back(i);
    }
    return s;
}

Violations SettleOptions::validate() const {
    Violations out;
    require_positive(out, "dt_s", dt_s, "settling time step [s]");
    require_positive(out, "kinetic_threshold_j", kinetic_threshold_j, "rest threshold [J]");
    require_positive(out, "max_time_s", max_time_s, "longest settling time [s]");
    require_non_negative(out, "min_time_s", min_time_s, "shortest settling time [s]");
    return out;
}

ParticleSet settle(const SolverOptions& options, const ParticleSet& initial,
                   const SettleOptions& so) {
    SolverOptions o = options;
    o.lock = {};
    o.track_energy = false;
    Solver solver(o, initial);
    const auto steps = static_cast<std::int64_t>(std::ceil(so.max_time_s / so.dt_s));
    const auto min_steps = static_cast<std::int64_t>(std::ceil(so.min_time_s / so.dt_s));
    for (std::int64_t k = 0; k < steps; ++k) {
        solver.step(so.dt_s);
        if (k >= min_steps && k % 100 == 0) {
            double ke = 0.0;
            const auto& p = solver.particles();
            for (std::size_t i = 0; i < p.size(); ++i) {
                // translational only: spin about a contact normal meets no resistance
                ke += 0.5 / p.inv_mass[i] * p.v[i].squaredNorm();
            }
            if (ke < so.kinetic_threshold_j) {
                ParticleSet s = solver.local_snapshot();
                for (auto& v : s.velocities_m_s) v.setZero();
                for (auto& w : s.angular_velocities_rad_s) w.setZero();
                return s;
            }
        }
    }
    throw std::runtime_error("settle: kinetic energy still above " +
                             format_value(so.kinetic_threshold_j) + " J after " +
                             format_value(so.max_time_s) + " s");
}

void save_particles(const std::string& path, const ParticleSet& p) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("save_particles: cannot write " + path);
    out << "x_m,y_m,z_m,radius_m,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s\n";
    out << std::setprecision(17);
    for (std::size_t i = 0; i < p.positions_m.size(); ++i) {
        const Eigen::Vector3d v =
            p.velocities_m_s.size() > i ? p.velocities_m_s[i] : Eigen::Vector3d::Zero();
        const Eigen::Vector3d w = p.angular_velocities_rad_s.size() > i
                                      ? p.angular_velocities_rad_s[i]
                                      : Eigen::Vector3d::Zero();
        const auto& x = p.positions_m[i];
        out << x.x() << ',' << x.y() << ',' << x.z() << ',' << p.radii_m[i] << ',' << v.x() << ','
            << v.y() << ',' << v.z() << ',' << w.x() << ',' << w.y() << ',' << w.z() << '\n';
    }
}

ParticleSet load_particles(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("load_particles: cannot read " + path);
    ParticleSet p;
    std::string line;
    std::getline(in, line);
    int lineno = 1;
    while (std::getline(in, line)) {
        ++lineno;
        if (line.empty()) continue;
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream ls(line);
        double a[10];
        for (double& x : a) {
            if (!(ls >> x)) {
                throw std::runtime_error(path + ":" + std::to_string(lineno) +
                                         ": expected 10 numbers");
            }
        }
        p.positions_m.emplace_back(a[0], a[1], a[2]);
        p.radii_m.push_back(a[3]);
        p.velocities_m_s.emplace_back(a[4], a[5], a[6]);
        p.angular_velocities_rad_s.emplace_back(a[7], a[8], a[9]);
    }
    return p;
}

void write_vtk(const std::string& path, const ParticleState& s) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("write_vtk: cannot write " + path);
    const std::size_t n = s.size();
    out << "# vtk DataFile Version 3.0\nShakerBench DEM particles\nASCII\nDATASET POLYDATA\n";
    out << std::setprecision(10);
    out << "POINTS " << n << " double\n";
    for (const auto& x : s.x) out << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
    out << "VERTICES " << n << ' ' << 2 * n << '\n';
    for (std::size_t i = 0; i < n; ++i) out << "1 " << i << '\n';
    out << "POINT_DATA " << n << "\nSCALARS radius double 1\nLOOKUP_TABLE default\n";
    for (double r : s.radius) out << r << '\n';
    out << "SCALARS id int 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < n; ++i) out << i << '\n';
    out << "SCALARS locked int 1\nLOOKUP_TABLE default\n";
    for (auto l : s.locked) out << static_cast<int>(l) << '\n';
    out << "VECTORS velocity double\n";
    for (const auto& v : s.v) out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    out << "VECTORS angular_velocity double\n";
    for (const auto& w : s.w) out << w.x() << ' ' << w.y() << ' ' << w.z() << '\n';
}

Violations AutoStiffnessInput::validate() const {
    Violations out;
    require_positive(out, "particle_diameter_m", particle_diameter_m, "diameter [m]");
    require_positive(out, "density_kg_m3", density_kg_m3, "density [kg/m^3]");
    require_in_range(out, "max_overlap_fraction", max_overlap_fraction, 1e-6, 0.5,
                     "allowed overlap / diameter [-]");
    require_non_negative(out, "impact_speed_m_s", impact_speed_m_s, "impact speed [m/s]");
    if (impact_speed_m_s <= 0.0) {
        require_positive(out, "level_m_s2", level_m_s2, "acceleration amplitude [m/s^2]");
        require_positive(out, "frequency_hz", frequency_hz, "frequency [Hz]");
        require_non_negative(out, "gap_m", gap_m, "free flight across the cavity [m]");
    }
    require_in_range(out, "time_step_fraction", time_step_fraction, 1e-4, 0.5,
                     "dt / contact time [-]");
    if (!(restitution > 0.0 && restitution <= 1.0)) {
        out.push_back(
            {"restitution", format_value(restitution), "must be in (0, 1]", "restitution [-]"});
    }
    return out;
}

double hertz_contact_time(double m_eff, double k, double v) {
    // t_c = 2 (delta_max / v) (2/5) B(2/5, 1/2), delta_max = (5 m v^2 / (4 k))^{2/5}
    const double beta = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
    return 2.0 * 0.4 * beta * std::pow(1.25 * m_eff / k, 0.4) * std::pow(v, -0.2);
}

double hooke_contact_time(double m_eff, double k, double e) {
    const double zeta = linear_zeta_from_restitution(e);
    const double w0 = std::sqrt(k / m_eff);
    return kPi / (w0 * std::sqrt(1.0 - zeta * zeta));
}

AutoStiffness auto_stiffness(const AutoStiffnessInput& in) {
    const Violations v = in.validate();
    if (!v.empty()) {
        throw std::invalid_argument("auto_stiffness: " + v.front().key + " = " + v.front().value +
                                    ": " + v.front().constraint);
    }
    AutoStiffness out;
    const double r = 0.5 * in.particle_diameter_m;
    const double m = in.density_kg_m3 * 4.0 / 3.0 * kPi * r * r * r;
    out.effective_mass_kg = in.wall_contact ? m : 0.5 * m;
    if (in.impact_speed_m_s > 0.0) {
        out.impact_speed_m_s = in.impact_speed_m_s;
    } else {
        const double amax = in.level_m_s2 + in.gravity_m_s2;
        out.impact_speed_m_s =
            in.level_m_s2 / (kTwoPi * in.frequency_hz) + std::sqrt(2.0 * amax * in.gap_m);
    }
    const double vi = out.impact_speed_m_s;
    out.max_overlap_m = in.max_overlap_fraction * in.particle_diameter_m;
    const double d = out.max_overlap_m, me = out.effective_mass_kg;
    if (in.law == NormalLaw::hooke) {
        out.stiffness = me * vi * vi / (d * d);  // 1/2 m v^2 = 1/2 k delta^2
        out.contact_time_s = hooke_contact_time(me, out.stiffness, in.restitution);
    } else {
        out.stiffness = 1.25 * me * vi * vi / std::pow(d, 2.5);  // 1/2 m v^2 = 2/5 k delta^2.5
        out.contact_time_s = hertz_contact_time(me, out.stiffness, vi);
    }
    out.time_step_s = in.time_step_fraction * out.contact_time_s;
    return out;
}

}  // namespace sb::dem

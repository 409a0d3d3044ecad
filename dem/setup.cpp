// Set-up helpers: radii, random filling, settling, pouring, particle files, VTK, automatic
// stiffness.
#include "dem/setup.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/significant_text.hpp"
#include "dem/contact_law.hpp"

namespace sb::dem {

namespace {
/// Portable uniform [0,1) from the raw 64-bit engine output (std distributions differ).
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// Uniform grid of the spheres placed so far, for the overlap test of random insertion: a
/// candidate is compared with the spheres of its 27 neighbouring cells only (cells at least
/// the largest diameter wide), not with every placed sphere.
class InsertionGrid {
  public:
    InsertionGrid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double cell,
                  std::size_t capacity)
        : lo_(lo), next_(capacity, -1) {
        const Eigen::Vector3d ext = hi - lo;
        // at most ~4 cells per sphere slot (plus a floor), so tiny spheres in a big cavity
        // do not allocate a huge grid; larger cells stay correct, only slower
        const double cells_max = 4.0 * static_cast<double>(capacity) + 4096.0;
        cell_ = std::max(cell, std::cbrt(ext.prod() / cells_max));
        for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, static_cast<int>(ext[a] / cell_) + 1);
        head_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2], -1);
    }
    void add(std::size_t id, const Eigen::Vector3d& x) {
        const std::size_t c = flat(index(x));
        next_[id] = head_[c];
        head_[c] = static_cast<std::int64_t>(id);
    }
    /// True if the sphere (x, r) overlaps a placed sphere (with the 1e-9 relative margin of
    /// the insertion, so that touching spheres start just apart).
    bool overlaps(const Eigen::Vector3d& x, double r, const std::vector<Eigen::Vector3d>& pos,
                  const std::vector<double>& radii) const {
        const std::array<int, 3> c = index(x);
        for (int k = std::max(c[2] - 1, 0); k <= std::min(c[2] + 1, dims_[2] - 1); ++k) {
            for (int j = std::max(c[1] - 1, 0); j <= std::min(c[1] + 1, dims_[1] - 1); ++j) {
                for (int i = std::max(c[0] - 1, 0); i <= std::min(c[0] + 1, dims_[0] - 1); ++i) {
                    for (std::int64_t q = head_[flat({i, j, k})]; q >= 0;
                         q = next_[static_cast<std::size_t>(q)]) {
                        const auto u = static_cast<std::size_t>(q);
                        const double rs = r + radii[u];
                        if ((x - pos[u]).squaredNorm() < rs * rs * (1.0 + 1e-9)) return true;
                    }
                }
            }
        }
        return false;
    }

  private:
    std::array<int, 3> index(const Eigen::Vector3d& x) const {
        std::array<int, 3> c{};
        for (int a = 0; a < 3; ++a) {
            c[a] =
                std::clamp(static_cast<int>(std::floor((x[a] - lo_[a]) / cell_)), 0, dims_[a] - 1);
        }
        return c;
    }
    std::size_t flat(const std::array<int, 3>& c) const {
        return (static_cast<std::size_t>(c[2]) * static_cast<std::size_t>(dims_[1]) +
                static_cast<std::size_t>(c[1])) *
                   static_cast<std::size_t>(dims_[0]) +
               static_cast<std::size_t>(c[0]);
    }

    Eigen::Vector3d lo_;
    double cell_ = 1.0;
    int dims_[3]{1, 1, 1};
    std::vector<std::int64_t> head_, next_;
};

/// Draws up to max_attempts candidate centres for a sphere of radius r, uniform over the
/// cavity's bounding box (three portable uniforms per attempt); the first one that clears the
/// walls, the obstacles and every sphere in the grid is returned.
std::optional<Eigen::Vector3d> find_free_place(const Enclosure& enc, const InsertionGrid& grid,
                                               double r, const std::vector<Eigen::Vector3d>& pos,
                                               const std::vector<double>& radii,
                                               std::mt19937_64& rng, int max_attempts) {
    const Eigen::Vector3d lo = enc.lower(), hi = enc.upper();
    for (int a = 0; a < max_attempts; ++a) {
        Eigen::Vector3d x;
        for (int d = 0; d < 3; ++d) {
            x[d] = lo[d] + r + uniform01(rng) * std::max(0.0, hi[d] - lo[d] - 2.0 * r);
        }
        if (!enc.contains(x) || enc.clearance(x) < r * (1.0 + 1e-9)) continue;
        if (grid.overlaps(x, r, pos, radii)) continue;
        return x;
    }
    return std::nullopt;
}

double largest(const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

double sphere_volume(double r) { return 4.0 / 3.0 * kPi * r * r * r; }

/// Volume of the spheres order[0..count) [m^3].
double volume_of(const std::vector<double>& radii, const std::vector<std::size_t>& order,
                 std::size_t count) {
    double v = 0.0;
    for (std::size_t k = 0; k < count; ++k) v += sphere_volume(radii[order[k]]);
    return v;
}

/// Multiplies every radius by 1 + s u, u uniform in [-sqrt 3, sqrt 3): a law of mean 0 and
/// standard deviation 1, so the diameters scatter by exactly s about their nominal value,
/// bounded (no sphere shrinks towards nothing, the largest is known before the draw: the
/// stiffness and the time step are sized for it, ParticleOptions::largest_diameter_m). Size
/// dispersion moves the packing and the clearance the damping depends on (Friend and Kinra
/// 2000). A stream of the filling's seed of its own: the classes are shuffled as without it.
void scatter_radii(std::vector<double>& radii, double scatter, std::uint64_t seed) {
    if (scatter == 0.0) return;
    std::mt19937_64 rng(seed ^ 0x94D049BB133111EBull);
    const double half_width = std::sqrt(3.0);
    for (double& r : radii) r *= 1.0 + scatter * half_width * (2.0 * uniform01(rng) - 1.0);
}

/// Nominal radii of the size classes by number fraction, largest remainder rounding, the
/// classes interleaved by a seeded shuffle [m].
std::vector<double> class_radii(const ParticleOptions& o, std::uint64_t seed) {
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

/// The enclosure's wall materials with their names in the run log: the ends' (the wall's),
/// then the lateral surface's where it has its own.
std::vector<std::pair<const char*, const Material*>> wall_materials(const ContactOptions& c) {
    std::vector<std::pair<const char*, const Material*>> out{{"particle-wall", &c.wall_material}};
    if (c.side_material) out.emplace_back("particle-side", &*c.side_material);
    return out;
}

/// The Hertz constant of a sphere on the stiffest of the enclosure's walls, each taken flat
/// (the cylinder's concave side is softer still).
double stiffest_wall_constant(const Material& particle, double radius, const ContactOptions& c) {
    double k = 0.0;
    for (const auto& [name, material] : wall_materials(c)) {
        k = std::max(k, hertz_constant(particle, radius, *material,
                                       std::numeric_limits<double>::infinity()));
    }
    return k;
}

}  // namespace

std::vector<double> make_radii(const ParticleOptions& o, std::uint64_t seed) {
    std::vector<double> r = class_radii(o, seed);
    scatter_radii(r, o.diameter_scatter, seed);
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
    InsertionGrid grid(enc.lower(), enc.upper(), 2.0 * largest(radii), radii.size());
    std::size_t placed = 0;
    for (std::size_t i : order) {
        const auto x =
            find_free_place(enc, grid, radii[i], s.positions_m, s.radii_m, rng, max_attempts);
        if (!x) {
            throw std::runtime_error(
                "fill_random: could not place particle " + std::to_string(placed + 1) + " of " +
                std::to_string(radii.size()) +
                " without overlap: random insertion jams near a solid fraction of 0.38 (here " +
                format_value(volume_of(radii, order, placed) / enc.volume()) +
                " of the cavity); fill denser beds with pour(), which settles batches under "
                "gravity");
        }
        s.positions_m[i] = *x;
        grid.add(i, *x);
        ++placed;
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

double settling_step_s(const SolverOptions& options, const ParticleSet& initial,
                       const SettleOptions& so) {
    const ContactOptions& c = options.contact;
    if (initial.radii_m.empty()) return so.dt_s;
    const double r = *std::min_element(initial.radii_m.begin(), initial.radii_m.end());
    const double m = options.particles.material.density_kg_m3 * 4.0 / 3.0 * kPi * r * r * r;
    if (c.normal == NormalLaw::hertz) {
        // A Hertz contact stiffens with the impact speed; the fastest impacts of settling are
        // of a sphere falling across the enclosure. The smallest spheres have the shortest
        // contacts (t_c ~ m*^{2/5} R*^{-1/5}).
        const EnclosureOptions& e = options.enclosure;
        const double extent =
            std::max({e.height_m, e.shape == EnclosureShape::cylinder ? e.inner_diameter_m : 0.0,
                      e.shape == EnclosureShape::box ? std::max(e.length_x_m, e.length_y_m) : 0.0});
        const double fall_speed = std::sqrt(2.0 * options.gravity_m_s2.norm() * extent);
        if (!(fall_speed > 0.0)) return so.dt_s;
        const Material& pm = options.particles.material;
        const double k_pair =
            c.normal_stiffness > 0.0 ? c.normal_stiffness : hertz_constant(pm, r, pm, r);
        const double k_wall =
            c.normal_stiffness > 0.0 ? c.normal_stiffness : stiffest_wall_constant(pm, r, c);
        const double contact_time = std::min(hertz_contact_time(0.5 * m, k_pair, fall_speed),
                                             hertz_contact_time(m, k_wall, fall_speed));
        return std::min(so.dt_s, contact_time / kSettleStepsPerContact);
    }
    const double k_wall =
        c.wall_normal_stiffness > 0.0 ? c.wall_normal_stiffness : c.normal_stiffness;
    // Undamped half periods (the damped ones are longer): two of the smallest spheres
    // (m* = m/2) and one against a wall (m* = m).
    const double contact_time =
        std::min(kPi * std::sqrt(0.5 * m / c.normal_stiffness), kPi * std::sqrt(m / k_wall));
    return std::min(so.dt_s, contact_time / kSettleStepsPerContact);
}

namespace {

void require_valid(const SettleOptions& so) {
    if (const Violations v = so.validate(); !v.empty()) {
        throw std::invalid_argument("settle: " + v.front().key + " = " + v.front().value + ": " +
                                    v.front().constraint);
    }
}

/// The options a settle runs with: free (no lock), no energy ledger, and the history-spring
/// friction where SettleOptions::static_friction asks for it.
SolverOptions settling_options(const SolverOptions& options, const SettleOptions& so) {
    SolverOptions o = options;
    o.lock = {};
    o.track_energy = false;
    if (so.static_friction && o.contact.tangential == TangentialLaw::directional_coulomb) {
        o.contact.tangential = TangentialLaw::coulomb_spring;
    }
    return o;
}

/// Steps `solver` on from step `first` of a settle (with `quiet` quiet checks behind it) until
/// the bed is at rest by the criterion of settle(); `at_check(k, quiet)`, when given, is
/// called after every kSettleCheckInterval-th step k. The settled particles, enclosure frame.
ParticleSet settle_to_rest(Solver& solver, double dt, const SettleOptions& so, std::int64_t first,
                           int quiet, const std::function<void(std::int64_t, int)>& at_check) {
    const auto steps = static_cast<std::int64_t>(std::ceil(so.max_time_s / dt));
    const auto min_steps = static_cast<std::int64_t>(std::ceil(so.min_time_s / dt));
    for (std::int64_t k = first; k < steps; ++k) {
        solver.step(dt);
        if (k % kSettleCheckInterval != 0) continue;
        if (k >= min_steps) {
            // a bouncing bed passes through low kinetic energy at its turning points: demand
            // several consecutive quiet checks
            quiet = translational_kinetic_energy(solver.particles()) < so.kinetic_threshold_j
                        ? quiet + 1
                        : 0;
            if (quiet >= kSettleQuietChecks) return solver.local_snapshot();
        }
        if (at_check) at_check(k, quiet);
    }
    throw std::runtime_error("settle: kinetic energy still above " +
                             format_value(so.kinetic_threshold_j) + " J after " +
                             format_value(so.max_time_s) + " s");
}

}  // namespace

ParticleSet settle(const SolverOptions& options, const ParticleSet& initial,
                   const SettleOptions& so) {
    require_valid(so);
    const SolverOptions o = settling_options(options, so);
    Solver solver(o, initial);
    return settle_to_rest(solver, settling_step_s(o, initial, so), so, 0, 0, {});
}

double translational_kinetic_energy(const ParticleState& p) {
    double ke = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) ke += 0.5 / p.inv_mass[i] * p.v[i].squaredNorm();
    return ke;
}

Violations PourOptions::validate() const {
    Violations out;
    if (max_attempts_per_particle < 1) {
        out.push_back({"max_attempts_per_particle", std::to_string(max_attempts_per_particle),
                       "must be >= 1", "candidate places tried per sphere and batch"});
    }
    if (!(batch_kinetic_factor >= 1.0 && std::isfinite(batch_kinetic_factor))) {
        out.push_back({"batch_kinetic_factor", format_value(batch_kinetic_factor), "must be >= 1",
                       "rest threshold of the intermediate batches / final threshold [-]"});
    }
    require_in_range(out, "friction_scale", friction_scale, 0.0, 1.0,
                     "friction of the pour / configured friction [-]");
    if (max_batches < 1) {
        out.push_back({"max_batches", std::to_string(max_batches), "must be >= 1",
                       "insert-and-settle rounds before giving up"});
    }
    return out;
}

namespace {

/// Refuses a progress record that another pour (other spheres, other options) wrote, and sets
/// the insertion generator to the record's.
void take_generator(const PourProgress& p, std::uint64_t seed, const std::vector<double>& radii,
                    const PourOptions& po, std::mt19937_64& rng) {
    const std::size_t m = p.solver.positions_m.size();
    const auto refuse = [](const std::string& why) {
        throw std::invalid_argument("pour: the progress to resume does not fit this pour: " + why);
    };
    if (p.seed != seed) refuse("seed " + std::to_string(p.seed) + ", not " + std::to_string(seed));
    if (p.batch < 0 || p.batch >= po.max_batches) refuse("batch " + std::to_string(p.batch));
    if (p.settle_steps < 0 || p.quiet_checks < 0) refuse("a negative step or check count");
    if (m == 0 || m > radii.size() || p.solver.radii_m.size() != m ||
        !std::equal(p.solver.radii_m.begin(), p.solver.radii_m.end(), radii.begin())) {
        refuse("its spheres are not the first of this pour's");
    }
    if (p.final_settle && (m != radii.size() || po.friction_scale == 1.0)) {
        refuse("a final settle where this pour has none");
    }
    std::istringstream in(p.generator_state);
    if (!(in >> rng)) refuse("its generator state does not read");
}

/// The options of batch settles: the pour's with `count` spheres and the batch friction.
SolverOptions batch_options(const SolverOptions& options, const PourOptions& po,
                            std::size_t count) {
    SolverOptions o = options;
    o.particles.count = static_cast<int>(count);
    for (PairProperties* pair : {&o.contact.particle_particle, &o.contact.particle_wall,
                                 o.contact.particle_rod ? &*o.contact.particle_rod : nullptr,
                                 o.contact.particle_side ? &*o.contact.particle_side : nullptr}) {
        if (pair == nullptr) continue;
        pair->sliding_friction *= po.friction_scale;
        pair->rolling_friction *= po.friction_scale;
    }
    return o;
}

/// Inserts the next batch into the free space left by the settled `bed`, in the (size-mixed)
/// order of make_radii, until the first sphere finds no free place: each batch is a loose
/// random layer on top of the bed. Throws std::runtime_error when not one sphere fits.
void insert_batch(const Enclosure& enc, const std::vector<double>& radii, const PourOptions& po,
                  std::mt19937_64& rng, ParticleSet& bed) {
    const std::size_t n = radii.size();
    const std::size_t before = bed.positions_m.size();
    InsertionGrid grid(enc.lower(), enc.upper(), 2.0 * largest(radii), n);
    for (std::size_t i = 0; i < before; ++i) grid.add(i, bed.positions_m[i]);
    bed.positions_m.reserve(n);
    std::vector<double> r = bed.radii_m;
    r.reserve(n);
    for (std::size_t i = before; i < n; ++i) {
        r.push_back(radii[i]);
        const auto x = find_free_place(enc, grid, radii[i], bed.positions_m, r, rng,
                                       po.max_attempts_per_particle);
        if (!x) {
            r.pop_back();
            break;
        }
        bed.positions_m.push_back(*x);
        grid.add(i, *x);
    }
    const std::size_t now = bed.positions_m.size();
    if (now == before) {
        throw std::runtime_error(
            "pour: the settled bed of " + std::to_string(now) + " of " + std::to_string(n) +
            " spheres (solid fraction " + format_value(solid_fraction(bed, enc)) +
            " of the cavity) leaves no free place for the next one: the cavity is too small "
            "for this count");
    }
    bed.radii_m = r;
    bed.velocities_m_s.resize(now, Eigen::Vector3d::Zero());
    bed.angular_velocities_rad_s.resize(now, Eigen::Vector3d::Zero());
}

}  // namespace

ParticleSet pour(const SolverOptions& options, std::uint64_t seed, const SettleOptions& so,
                 const PourOptions& po, const PourCheckpoints& checkpoints) {
    Violations v = options.validate();
    append_prefixed(v, "settle", so.validate());
    append_prefixed(v, "pour", po.validate());
    if (!(options.gravity_m_s2.norm() > 0.0)) {
        v.push_back({"gravity_m_s2", "0", "must be non-zero", "gravity that settles the bed"});
    }
    if (!v.empty()) {
        throw std::invalid_argument("pour: " + v.front().key + " = " + v.front().value + ": " +
                                    v.front().constraint);
    }
    const Enclosure enc(options.enclosure);
    const std::vector<double> radii = make_radii(options.particles, seed);
    const std::size_t n = radii.size();
    std::mt19937_64 rng(seed ^ 0xD1B54A32D192ED03ull);
    const PourProgress* resume = checkpoints.resume;
    if (resume != nullptr) take_generator(*resume, seed, radii, po, rng);

    // One settle of the pour, from `bed` or, when it is the one in progress, from the record.
    const auto settle_once = [&](const ParticleSet& bed, int batch, bool final_settle) {
        const std::size_t now =
            resume != nullptr ? resume->solver.positions_m.size() : bed.positions_m.size();
        SettleOptions s = so;
        if (now < n) s.kinetic_threshold_j *= po.batch_kinetic_factor;
        const SolverOptions o =
            settling_options(final_settle ? options : batch_options(options, po, now), s);
        ParticleSet sizes;  // what the settling step depends on
        sizes.radii_m = resume != nullptr ? resume->solver.radii_m : bed.radii_m;
        std::optional<Solver> solver;
        std::int64_t first = 0;
        int quiet = 0;
        if (resume != nullptr) {
            solver.emplace(o, resume->solver, EnclosureState{});
            first = resume->settle_steps + 1;
            quiet = resume->quiet_checks;
            resume = nullptr;
        } else {
            solver.emplace(o, bed);
        }
        const double dt = settling_step_s(o, sizes, s);
        std::function<void(std::int64_t, int)> at_check;
        if (checkpoints.due && checkpoints.save) {
            at_check = [&](std::int64_t k, int quiet_now) {
                if (!checkpoints.due()) return;
                std::ostringstream generator;
                generator << rng;
                checkpoints.save(PourProgress{seed, batch, final_settle, k, quiet_now,
                                              generator.str(), solver->state()});
            };
        }
        return settle_to_rest(*solver, dt, s, first, quiet, at_check);
    };

    ParticleSet bed;  // always the first bed.radii_m.size() spheres of `radii`, settled
    for (int batch = resume != nullptr ? resume->batch : 0; batch < po.max_batches; ++batch) {
        const bool resuming_final = resume != nullptr && resume->final_settle;
        if (resume == nullptr) insert_batch(enc, radii, po, rng, bed);
        if (!resuming_final) bed = settle_once(bed, batch, false);
        const bool full = resuming_final || bed.positions_m.size() == n;
        if (full && po.friction_scale != 1.0) bed = settle_once(bed, batch, true);
        if (full) return bed;
    }
    throw std::runtime_error("pour: " + std::to_string(bed.positions_m.size()) + " of " +
                             std::to_string(n) + " spheres placed after " +
                             std::to_string(po.max_batches) +
                             " batches (pour.max_batches); the cavity is nearly full");
}

double solid_fraction(const ParticleSet& particles, const Enclosure& enclosure) {
    double v = 0.0;
    for (double r : particles.radii_m) v += sphere_volume(r);
    return v / enclosure.volume();
}

std::string particles_text(const ParticleSet& p) {
    std::ostringstream out;
    out << "x_m,y_m,z_m,radius_m,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s\n";
    // 17 significant digits: every double reads back exactly.
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
    return out.str();
}

ParticleSet parse_particles_text(const std::string& text, const std::string& name) {
    std::istringstream in(text);
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
                throw std::runtime_error(name + ":" + std::to_string(lineno) +
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

void save_particles(const std::string& path, const ParticleSet& p) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("save_particles: cannot write " + path);
    out << particles_text(p);
}

ParticleSet load_particles(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("load_particles: cannot read " + path);
    std::ostringstream text;
    text << in.rdbuf();
    return parse_particles_text(text.str(), path);
}

namespace {

/// Legacy VTK polydata of spheres: points, radius, id, locked flag, velocity, spin.
std::string vtk_polydata(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& radius,
                         const std::vector<std::uint8_t>& locked,
                         const std::vector<Eigen::Vector3d>& v,
                         const std::vector<Eigen::Vector3d>& w) {
    std::ostringstream out;
    const std::size_t n = x.size();
    out << "# vtk DataFile Version 3.0\nShakerBench DEM particles\nASCII\nDATASET POLYDATA\n";
    out << std::setprecision(10);
    out << "POINTS " << n << " double\n";
    for (const auto& p : x) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    out << "VERTICES " << n << ' ' << 2 * n << '\n';
    for (std::size_t i = 0; i < n; ++i) out << "1 " << i << '\n';
    out << "POINT_DATA " << n << "\nSCALARS radius double 1\nLOOKUP_TABLE default\n";
    for (double r : radius) out << r << '\n';
    out << "SCALARS id int 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < n; ++i) out << i << '\n';
    out << "SCALARS locked int 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < n; ++i) out << (i < locked.size() ? int{locked[i]} : 0) << '\n';
    out << "VECTORS velocity double\n";
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d u = i < v.size() ? v[i] : Eigen::Vector3d::Zero();
        out << u.x() << ' ' << u.y() << ' ' << u.z() << '\n';
    }
    out << "VECTORS angular_velocity double\n";
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d u = i < w.size() ? w[i] : Eigen::Vector3d::Zero();
        out << u.x() << ' ' << u.y() << ' ' << u.z() << '\n';
    }
    return out.str();
}

}  // namespace

std::string vtk_text(const ParticleSet& local) {
    return vtk_polydata(local.positions_m, local.radii_m, {}, local.velocities_m_s,
                        local.angular_velocities_rad_s);
}

void write_vtk(const std::string& path, const ParticleState& s) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("write_vtk: cannot write " + path);
    out << vtk_polydata(s.x, s.radius, s.locked, s.v, s.w);
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
    require_non_negative(out, "smallest_diameter_m", smallest_diameter_m,
                         "smallest diameter of the bed [m] (0: one size)");
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

double hertz_constant(const Material& a, double r_a_m, const Material& b, double r_b_m) {
    const double r_star = std::isinf(r_b_m) ? r_a_m : r_a_m * r_b_m / (r_a_m + r_b_m);
    return 4.0 / 3.0 * effective_modulus_pa(a, b) * std::sqrt(r_star);
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
    // The shortest contacts are the smallest spheres' (t_c ~ m*^{1/2} for Hooke, ~ m*^{2/5}
    // for Hertz): the time step must resolve theirs.
    const double r_small = in.smallest_diameter_m > 0.0
                               ? 0.5 * std::min(in.smallest_diameter_m, in.particle_diameter_m)
                               : r;
    const double m_small = in.density_kg_m3 * 4.0 / 3.0 * kPi * r_small * r_small * r_small;
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
    // The same k serves both contact types; the pair contact (m* = m/2) is the shorter one
    // (t_c ~ sqrt(m*) for Hooke, ~ m*^{2/5} for Hertz), so it sets the time step.
    auto contact_time = [&](double m_eff) {
        return in.law == NormalLaw::hooke ? hooke_contact_time(m_eff, out.stiffness, in.restitution)
                                          : hertz_contact_time(m_eff, out.stiffness, vi);
    };
    if (in.law == NormalLaw::hooke) {
        out.stiffness = me * vi * vi / (d * d);  // 1/2 m v^2 = 1/2 k delta^2
    } else {
        out.stiffness = 1.25 * me * vi * vi / std::pow(d, 2.5);  // 1/2 m v^2 = 2/5 k delta^2.5
    }
    out.wall_contact_time_s = contact_time(m_small);
    out.pair_contact_time_s = contact_time(0.5 * m_small);
    out.contact_time_s = std::min(out.wall_contact_time_s, out.pair_contact_time_s);
    out.time_step_s = in.time_step_fraction * out.contact_time_s;
    return out;
}

std::string describe(const AutoStiffness& a, NormalLaw law) {
    std::ostringstream out;
    out << std::setprecision(4) << "stiffness " << a.stiffness
        << (law == NormalLaw::hooke ? " N/m" : " N/m^1.5") << " (impact speed "
        << a.impact_speed_m_s << " m/s, largest overlap " << a.max_overlap_m
        << " m), contact time particle-particle " << a.pair_contact_time_s << " s, particle-wall "
        << a.wall_contact_time_s << " s, time step " << a.time_step_s << " s";
    return out.str();
}

namespace {
/// auto_stiffness()'s input for the largest spheres at an excitation (peak acceleration, its
/// frequency, the enclosure height as the free flight).
AutoStiffnessInput excitation_input(const ParticleOptions& particles,
                                    const EnclosureOptions& enclosure, NormalLaw law,
                                    double time_step_fraction, double peak_acceleration_m_s2,
                                    double frequency_hz) {
    AutoStiffnessInput in;
    in.law = law;
    in.particle_diameter_m = particles.largest_diameter_m();
    in.smallest_diameter_m = particles.smallest_diameter_m();
    in.density_kg_m3 = particles.material.density_kg_m3;
    in.level_m_s2 = peak_acceleration_m_s2;
    in.frequency_hz = frequency_hz;
    in.gap_m = enclosure.height_m;
    in.time_step_fraction = time_step_fraction;
    return in;
}
}  // namespace

ExcitationContact choose_contact(const ParticleOptions& particles,
                                 const EnclosureOptions& enclosure, NormalLaw law,
                                 double restitution, std::optional<double> given_stiffness,
                                 double max_overlap_fraction, double time_step_fraction,
                                 double peak_acceleration_m_s2, double frequency_hz) {
    // The largest spheres overlap most at a given speed (auto_stiffness); the smallest have
    // the shortest contact, and the time step follows from the contact of two of them.
    const double d = particles.smallest_diameter_m();
    const double mass = particles.material.density_kg_m3 * kPi * d * d * d / 6.0;
    AutoStiffnessInput in = excitation_input(particles, enclosure, law, time_step_fraction,
                                             peak_acceleration_m_s2, frequency_hz);
    in.max_overlap_fraction = max_overlap_fraction;
    in.restitution = restitution;
    ExcitationContact out;
    // A given Hooke stiffness needs no excitation (the impact speed is then only reported
    // when there is one); the rest sizes from it.
    const bool needs_speed = !given_stiffness || law == NormalLaw::hertz;
    const bool has_speed = needs_speed || in.validate().empty();
    const AutoStiffness sized = has_speed ? auto_stiffness(in) : AutoStiffness{};
    out.impact_speed_m_s = sized.impact_speed_m_s;
    if (!given_stiffness) {
        out.stiffness = sized.stiffness;
        out.time_step_s = sized.time_step_s;
        out.pair_contact_time_s = sized.pair_contact_time_s;
        out.log = "automatic: " + describe(sized, law);
    } else {
        out.stiffness = *given_stiffness;
        const double contact_time =
            law == NormalLaw::hooke
                ? hooke_contact_time(0.5 * mass, out.stiffness, restitution)
                : hertz_contact_time(0.5 * mass, out.stiffness, sized.impact_speed_m_s);
        out.time_step_s = time_step_fraction * contact_time;
        out.pair_contact_time_s = contact_time;
        out.log = "stiffness " + significant_text(out.stiffness) + " (given), contact time " +
                  significant_text(contact_time) + " s, time step " +
                  significant_text(out.time_step_s) + " s";
    }
    out.stiffness_log = out.log.substr(0, out.log.rfind(", time step "));
    return out;
}

ExcitationContact materials_contact(const ParticleOptions& particles,
                                    const EnclosureOptions& enclosure,
                                    const ContactOptions& contact, double time_step_fraction,
                                    double peak_acceleration_m_s2, double frequency_hz) {
    // The smallest spheres have the shortest contacts (t_c ~ m*^{2/5} R*^{-1/5}).
    const double d = particles.smallest_diameter_m();
    const double mass = particles.material.density_kg_m3 * kPi * d * d * d / 6.0;
    // auto_stiffness() estimates the impact speed (and checks the inputs); its stiffness,
    // sized from an overlap, is not used.
    const double speed =
        auto_stiffness(excitation_input(particles, enclosure, NormalLaw::hertz, time_step_fraction,
                                        peak_acceleration_m_s2, frequency_hz))
            .impact_speed_m_s;
    const Material& pm = particles.material;
    const double k_pair = hertz_constant(pm, 0.5 * d, pm, 0.5 * d);
    const double pair_time = hertz_contact_time(0.5 * mass, k_pair, speed);
    ExcitationContact out;
    out.stiffness = 0.0;
    out.impact_speed_m_s = speed;
    out.pair_contact_time_s = pair_time;
    double shortest = pair_time;
    std::string constants = significant_text(k_pair) + " N/m^1.5 particle-particle";
    std::string times = "contact time particle-particle " + significant_text(pair_time) + " s";
    for (const auto& [name, material] : wall_materials(contact)) {  // each taken flat
        const double k =
            hertz_constant(pm, 0.5 * d, *material, std::numeric_limits<double>::infinity());
        const double time = hertz_contact_time(mass, k, speed);
        shortest = std::min(shortest, time);
        constants += ", " + significant_text(k) + " N/m^1.5 " + name;
        times += ", " + std::string(name) + " " + significant_text(time) + " s";
    }
    out.time_step_s = time_step_fraction * shortest;
    out.stiffness_log = "Hertz from the materials: k " + constants + " (impact speed " +
                        significant_text(speed) + " m/s), " + times;
    out.log = out.stiffness_log + ", time step " + significant_text(out.time_step_s) + " s";
    return out;
}

}  // namespace sb::dem

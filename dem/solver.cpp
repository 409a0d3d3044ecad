// Solver: broad phase, per-contact forces (law visited once per step), deterministic gather,
// semi-implicit Euler (paper 000), guards, wall force and moment, energy ledger.
#include "dem/solver.hpp"

#include <omp.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <type_traits>

namespace sb::dem {

namespace {

std::string join(const Violations& v) {
    std::ostringstream out;
    out << "invalid DEM options:";
    for (const auto& x : v) {
        out << "\n  " << x.key << " = " << x.value << ": " << x.constraint << " (" << x.meaning
            << ")";
    }
    return out.str();
}

const char* kind_name(SimulationError::Kind k) {
    switch (k) {
        case SimulationError::Kind::not_finite:
            return "non-finite state";
        case SimulationError::Kind::overlap:
            return "overlap beyond the allowed fraction";
        case SimulationError::Kind::outside:
            return "particle outside the enclosure";
    }
    return "?";
}

constexpr int kNoParticle = std::numeric_limits<int>::max();

/// What rebuilding the neighbour list costs per particle, in candidate tests of the sweep
/// (the frame change, the grid's counting sort, the scan of 27 cells, the sort of the list,
/// the merge of the pair slots and the reverse index, against one distance test). Measured,
/// not derived: with 6, 12, 24, 36 and 48 the instructions per step of the damper benchmarks
/// (docs/performance.md) were least at 24-36 and within 2 % of that over the whole range.
constexpr double kRebuildCostPerParticle = 24.0;

}  // namespace

// Forces inlining of the per-particle kernels into the sweep loop (not under the sanitizers,
// where the 36 instantiations of the inlined sweep make compilation far slower).
#if defined(__SANITIZE_ADDRESS__)
#define SB_ALWAYS_INLINE inline
#else
#define SB_ALWAYS_INLINE inline __attribute__((always_inline))
#endif

namespace {

/// Threads worth using for a loop of n items (at most kMaxChunks).
int threads_for(int nt, std::size_t n, std::size_t grain) {
    const auto k = static_cast<int>(std::min<std::size_t>(n / grain, Solver::kMaxChunks));
    return std::max(1, std::min(nt, k));
}

}  // namespace

SimulationError::SimulationError(Kind k, std::int64_t s, double t, int id, const std::string& what)
    : std::runtime_error(what), kind(k), step(s), time_s(t), particle_id(id) {}

Solver::Solver(const SolverOptions& options, const ParticleSet& particles,
               const EnclosureState& enclosure)
    : Solver(options, particles, enclosure, true) {}

Solver::Solver(const SolverOptions& options, const SolverState& state,
               const EnclosureState& enclosure)
    : Solver(options, local_particles(state), enclosure, false) {
    restore(state);
}

Solver::Solver(const SolverOptions& options, const ParticleSet& particles,
               const EnclosureState& enclosure, bool lock_from_options)
    : options_(options),
      enclosure_(options.enclosure),
      enclosure_state_(enclosure),
      snap_enclosure_(enclosure) {
    // SolverOptions::validate() checks the contact options too: each violation once.
    Violations v = options_.validate();
    law_ = make_contact_law(options_.contact);
    const std::size_t n = particles.positions_m.size();
    if (n != static_cast<std::size_t>(options_.particles.count) || particles.radii_m.size() != n) {
        v.push_back(
            {"particles.count", std::to_string(options_.particles.count),
             "must equal the number of positions and radii given (" + std::to_string(n) + ")",
             "number of particles"});
    }
    if (!enclosure.finite()) {
        v.push_back({"enclosure_state", "non-finite", "must be finite",
                     "initial enclosure pose and velocity"});
    }
    if (!v.empty()) throw std::invalid_argument(join(v));
    // HorizontalLayers::for_gravity, with its input kept for SolverState::layers_up
    layers_up_ = enclosure.rotation.transpose() * (-options_.gravity_m_s2);
    layers_ = HorizontalLayers(enclosure_, layers_up_, options_.energy_layers);

    // Pair coefficients: [0] particle-particle, [1] particle-wall, [2] particle-rod, [3]
    // particle-side (the rods and the lateral surface the wall's unless they have their own).
    const auto& c = options_.contact;
    const Material& pm = options_.particles.material;
    const Material& wm = c.wall_material;
    const Material& rm = c.rod_material ? *c.rod_material : wm;
    const Material& sm = c.side_material ? *c.side_material : wm;
    const PairProperties* props[4] = {&c.particle_particle, &c.particle_wall,
                                      c.particle_rod ? &*c.particle_rod : &c.particle_wall,
                                      c.particle_side ? &*c.particle_side : &c.particle_wall};
    const Material* other[4] = {&pm, &wm, &rm, &sm};
    for (int k = 0; k < 4; ++k) {
        PairCoefficients& p = coeff_[k];
        p.mu = props[k]->sliding_friction;
        p.mu_r = props[k]->rolling_friction;
        p.kt_ratio = c.tangential_stiffness_ratio;
        p.slip_reg = c.slip_regularisation_m_s;
        p.e_star_sqrt_factor = 4.0 / 3.0 * effective_modulus_pa(pm, *other[k]);
        p.k_n = c.normal_stiffness;
        if (k >= 1 && c.normal == NormalLaw::hooke && c.wall_normal_stiffness > 0.0) {
            p.k_n = c.wall_normal_stiffness;
        }
        p.damping =
            std::holds_alternative<LinearDashpot>(law_.damping)
                ? linear_zeta_from_restitution(props[k]->restitution)
            : std::holds_alternative<HertzDashpot>(law_.damping)
                ? hertz_alpha_from_restitution(props[k]->restitution)
            : std::holds_alternative<Viscoelastic>(law_.damping) ? props[k]->dissipative_constant_s
            : std::holds_alternative<ViscousDashpot>(law_.damping) ? props[k]->dashpot_n_s_per_m
                                                                   : 0.0;
    }
    has_history_ = std::holds_alternative<CoulombSpring>(law_.tangential);

    // Particles.
    state_.x.resize(n);
    state_.v.resize(n);
    state_.w.resize(n);
    state_.radius = particles.radii_m;
    state_.inv_mass.resize(n);
    state_.inv_inertia.resize(n);
    state_.locked.assign(n, 0);
    const double rho = options_.particles.material.density_kg_m3;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = state_.radius[i];
        const double m = rho * 4.0 / 3.0 * kPi * r * r * r;
        state_.inv_mass[i] = 1.0 / m;
        state_.inv_inertia[i] = 1.0 / (0.4 * m * r * r);
        state_.x[i] = enclosure_state_.to_world(particles.positions_m[i]);
        const Eigen::Vector3d vrel =
            particles.velocities_m_s.size() == n
                ? Eigen::Vector3d(enclosure_state_.rotation * particles.velocities_m_s[i])
                : Eigen::Vector3d::Zero();
        state_.v[i] = enclosure_state_.velocity_at(state_.x[i]) + vrel;
        state_.w[i] =
            particles.angular_velocities_rad_s.size() == n
                ? Eigen::Vector3d(enclosure_state_.rotation * particles.angular_velocities_rad_s[i])
                : enclosure_state_.angular_velocity_rad_s;
    }
    build_size_classes();
    const auto& eo = options_.enclosure;
    // Hertz radii of curvature against the curved walls (elliptical contacts, computed once
    // per distinct radius): rods are convex, the cylinder side concave, the rest flat.
    hertz_r_side_ = state_.radius;
    hertz_r_rod_ = state_.radius;
    if (std::holds_alternative<Hertz>(law_.normal)) {
        double last_r = -1.0, last_side = 0.0, last_rod = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double r = state_.radius[i];
            if (r != last_r) {
                last_r = r;
                last_side =
                    eo.shape == EnclosureShape::cylinder
                        ? hertz_equivalent_radius(r, 1.0 / (1.0 / r - 2.0 / eo.inner_diameter_m))
                        : r;
                last_rod = eo.rods.enabled ? hertz_equivalent_radius(
                                                 r, 1.0 / (1.0 / r + 2.0 / eo.rods.rod_diameter_m))
                                           : r;
            }
            hertz_r_side_[i] = last_side;
            hertz_r_rod_[i] = last_rod;
        }
    }
    local_x_.resize(n);
    lock_local_.resize(n);
    if (options_.track_energy) {
        v_old_.resize(n);
        w_old_.resize(n);
    }
    own_.resize(n);
    // Wall slots per particle: every emitter of Enclosure::for_each_contact fires at most once
    // per call (cylinder side/bottom/top or 6 box faces, each plate, the nearest rod per axis).
    wall_cap_ = (eo.shape == EnclosureShape::cylinder ? 3 : 6) + eo.plates.size() +
                (eo.rods.enabled ? 3 : 0);
    wall_count_.assign(n, 0);
    prev_wall_count_.assign(n, 0);
    wall_id_.assign(n * wall_cap_, 0);
    prev_wall_id_.assign(n * wall_cap_, 0);
    if (has_history_) {
        wall_hist_.assign(n * wall_cap_, Eigen::Vector3d::Zero());
        prev_wall_hist_.assign(n * wall_cap_, Eigen::Vector3d::Zero());
    }
    wall_delta_.assign(n * wall_cap_, 0.0);
    wall_kl_.assign(n * wall_cap_, 0.0);
    has_obstacles_ = eo.rods.enabled || !eo.plates.empty();
    track_energy_ = options_.track_energy;
    gravity_ = options_.gravity_m_s2;
    cylinder_radius_ = eo.shape == EnclosureShape::cylinder ? 0.5 * eo.inner_diameter_m : 0.0;
    // deep_inside(): a centre within these bounds keeps the largest sphere off every wall by
    // more than a rounding error (1e-9 of the cavity's size) of the exact tests in
    // Enclosure::for_each_contact; with obstacles every sphere takes the full test.
    {
        const double rmax = state_.radius.empty()
                                ? 0.0
                                : *std::max_element(state_.radius.begin(), state_.radius.end());
        const Eigen::Vector3d size = enclosure_.upper() - enclosure_.lower();
        const double reach = rmax + 1e-9 * size.maxCoeff();
        deep_lo_ = enclosure_.lower() + Eigen::Vector3d::Constant(reach);
        deep_hi_ = enclosure_.upper() - Eigen::Vector3d::Constant(reach);
        const double clear = cylinder_radius_ - reach;
        deep_rho2_ = clear > 0.0 ? clear * clear : -1.0;                    // -1: never deep inside
        if (has_obstacles_) deep_hi_ = deep_lo_ - Eigen::Vector3d::Ones();  // empty
    }

    // Uniform grid in the enclosure frame, cell >= largest diameter.
    double dmax = 0.0;
    for (double r : state_.radius) dmax = std::max(dmax, 2.0 * r);
    skin_ = options_.neighbor_skin_fraction * dmax;
    skin_max_ = skin_;
    const double pad = dmax;
    grid_lo_ = enclosure_.lower() - Eigen::Vector3d::Constant(pad);
    const Eigen::Vector3d ext =
        enclosure_.upper() - enclosure_.lower() + Eigen::Vector3d::Constant(2.0 * pad);
    cell_ = dmax + skin_max_;
    for (int a = 0; a < 3; ++a) {
        dims_[a] = std::max(1, static_cast<int>(std::floor(ext[a] / cell_)));
    }
    cell_ = std::max(cell_, 0.0);
    cell_of_.resize(n);
    cell_start_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    cell_items_.resize(n);

    // Locking (a restored solver takes the lock from its state).
    std::vector<int> ids = lock_from_options ? options_.lock.particle_ids : std::vector<int>{};
    if (lock_from_options && ids.empty() && options_.lock.fraction > 0.0) {
        std::vector<int> order(n);
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
            return particles.positions_m[a].z() < particles.positions_m[b].z();
        });
        const auto k =
            static_cast<std::size_t>(std::llround(options_.lock.fraction * static_cast<double>(n)));
        ids.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k));
    }
    if (!ids.empty()) lock(ids);
    reset_energy();
}

void Solver::build_size_classes() {
    // A bed of a few sizes (often one) has a few distinct masses and inertias: the effective
    // masses and radius of each pair of sizes, computed once with the expressions of the
    // contact loop from the same operands, so that the loop reads what it would have computed.
    std::vector<double> radii;
    const std::size_t n = state_.size();
    size_class_.assign(n, 0);
    class_pair_.clear();
    class_wall_.clear();
    class_count_ = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = state_.radius[i];
        auto it = std::find(radii.begin(), radii.end(), r);
        if (it == radii.end()) {
            if (radii.size() == kMaxSizeClasses) return;  // many sizes: computed per contact
            radii.push_back(r);
            it = radii.end() - 1;
        }
        size_class_[i] = static_cast<std::uint8_t>(it - radii.begin());
    }
    const std::size_t k = radii.size();
    std::vector<std::size_t> first(k, 0);
    for (std::size_t i = n; i-- > 0;) first[size_class_[i]] = i;
    class_pair_.resize(k * k);
    class_wall_.resize(k);
    for (std::size_t a = 0; a < k; ++a) {
        const std::size_t i = first[a];
        const double ri = state_.radius[i], imi = state_.inv_mass[i], iii = state_.inv_inertia[i];
        class_wall_[a] = {1.0 / imi, ri, 1.0 / (3.5 * imi), 1.0 / iii};
        for (std::size_t b = 0; b < k; ++b) {
            const std::size_t j = first[b];
            const double rj = state_.radius[j], imj = state_.inv_mass[j];
            class_pair_[a * k + b] = {1.0 / (imi + imj), ri * rj / (ri + rj),
                                      1.0 / (3.5 * (imi + imj)),
                                      1.0 / (iii + state_.inv_inertia[j])};
        }
    }
    class_count_ = k;
}

int Solver::thread_count() const {
    return options_.threads > 0 ? options_.threads : omp_get_max_threads();
}

void Solver::set_enclosure_state(const EnclosureState& state) {
    if (!state.finite()) {  // else every particle would look outside the enclosure
        std::ostringstream msg;
        msg << kind_name(SimulationError::Kind::not_finite)
            << ": enclosure pose or velocity at step " << step_ << ", t = " << time_ << " s";
        throw SimulationError(SimulationError::Kind::not_finite, step_, time_, -1, msg.str());
    }
    enclosure_state_ = state;
}

void Solver::lock(const std::vector<int>& ids) {
    if (!ids.empty()) released_ = false;
    for (int id : ids) {
        const auto i = static_cast<std::size_t>(id);
        state_.locked[i] = 1;
        lock_local_[i] = enclosure_state_.to_local(state_.x[i]);
    }
    locked_count_ = static_cast<int>(std::count(state_.locked.begin(), state_.locked.end(), 1));
}

void Solver::release() {
    if (locked_count_ > 0) released_ = true;
    std::fill(state_.locked.begin(), state_.locked.end(), 0);
    locked_count_ = 0;
}

void Solver::release(int count) {
    if (count >= locked_count_) {
        release();
        return;
    }
    if (count <= 0) return;
    std::vector<int> ids;
    ids.reserve(static_cast<std::size_t>(locked_count_));
    for (std::size_t i = 0; i < state_.locked.size(); ++i) {
        if (state_.locked[i]) ids.push_back(static_cast<int>(i));
    }
    // Ties (a flat layer) go to the lower id: the order does not depend on the sort.
    std::stable_sort(ids.begin(), ids.end(), [&](int a, int b) {
        return lock_local_[static_cast<std::size_t>(a)].z() >
               lock_local_[static_cast<std::size_t>(b)].z();
    });
    for (int k = 0; k < count; ++k) state_.locked[static_cast<std::size_t>(ids[k])] = 0;
    locked_count_ -= count;
    released_ = true;
}

int Solver::locked_count() const { return locked_count_; }

void Solver::snap_locked(double dt) {
    lock_force_.setZero();
    lock_moment_.setZero();
    const auto& e = enclosure_state_;
    const Eigen::Vector3d g = options_.gravity_m_s2;
    for (std::size_t i = 0; i < state_.size(); ++i) {
        if (!state_.locked[i]) continue;
        const double m = 1.0 / state_.inv_mass[i], inertia = 1.0 / state_.inv_inertia[i];
        const Eigen::Vector3d x = e.to_world(lock_local_[i]);
        const Eigen::Vector3d v = e.velocity_at(x);
        const Eigen::Vector3d w = e.angular_velocity_rad_s;
        if (!locked_inertia_external_) {
            // The held particle's inertia, m (v_e(t) - v_e(t - dt)) / dt with the velocity the
            // last snap set: the contacts and the weight were balanced after the last sweep
            // (add_held_reaction). Carried by the structure's mass instead, it is not a load.
            const Eigen::Vector3d before =
                snap_enclosure_.velocity_at(snap_enclosure_.to_world(lock_local_[i]));
            const Eigen::Vector3d inertia_force = m * (v - before) / dt;
            lock_force_ -= inertia_force;
            lock_moment_ -= (x - e.position_m).cross(inertia_force) +
                            inertia * (w - snap_enclosure_.angular_velocity_rad_s) / dt;
        }
        // the enclosure does the work of the snap
        ledger_.wall_work += 0.5 * m * (v.squaredNorm() - state_.v[i].squaredNorm()) +
                             0.5 * inertia * (w.squaredNorm() - state_.w[i].squaredNorm()) -
                             m * g.dot(x - state_.x[i]);
        state_.x[i] = x;
        state_.v[i] = v;
        state_.w[i] = w;
    }
    snap_enclosure_ = e;
}

void Solver::add_held_reaction(double dt) {
    // What holds a particle to its enclosure balances, in the same step, the contacts and
    // the weight its sweep just gave it: m (v - v_e) / dt over the velocity the snap had set,
    // v_e. Its walls take the contact forces in this step, so the held bed's wall contacts
    // cancel here and the structure is handed its weight and the contacts of free particles
    // on it. (Balanced at the next step's snap instead, a settled bed whose contacts do not
    // carry its weight exactly when the hold begins would hand the structure the difference
    // as an impulse in the first step, which no snap precedes.)
    const auto& e = enclosure_state_;
    for (std::size_t i = 0; i < state_.size(); ++i) {
        if (!state_.locked[i]) continue;
        const double m = 1.0 / state_.inv_mass[i], inertia = 1.0 / state_.inv_inertia[i];
        const Eigen::Vector3d x = e.to_world(lock_local_[i]);
        const Eigen::Vector3d force = m * (state_.v[i] - e.velocity_at(x)) / dt;
        wall_force_ += force;
        wall_moment_ += (x - e.position_m).cross(force) +
                        inertia * (state_.w[i] - e.angular_velocity_rad_s) / dt;
    }
}

Solver::LockedBody Solver::locked_body() const {
    LockedBody body;
    Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < state_.size(); ++i) {
        if (!state_.locked[i]) continue;
        const double m = 1.0 / state_.inv_mass[i];
        body.mass_kg += m;
        first_moment += m * lock_local_[i];
    }
    if (body.mass_kg == 0.0) return body;
    body.centre_m = first_moment / body.mass_kg;
    // Each sphere's own inertia plus the parallel-axis term m (|d|^2 I - d d^T).
    for (std::size_t i = 0; i < state_.size(); ++i) {
        if (!state_.locked[i]) continue;
        const Eigen::Vector3d d = lock_local_[i] - body.centre_m;
        body.inertia_kg_m2 += Eigen::Matrix3d::Identity() / state_.inv_inertia[i] +
                              (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()) /
                                  state_.inv_mass[i];
    }
    return body;
}

namespace {

#if defined(__SSE2__)
/// Two consecutive 3-vectors (six doubles from p) as three registers of their x, y and z.
struct TwoVectors {
    __m128d x, y, z;
};
inline TwoVectors load_two(const Eigen::Vector3d* v) {
    const double* p = v->data();
    const __m128d a = _mm_loadu_pd(p), b = _mm_loadu_pd(p + 2), c = _mm_loadu_pd(p + 4);
    return {_mm_shuffle_pd(a, b, 2), _mm_shuffle_pd(a, c, 1), _mm_shuffle_pd(b, c, 2)};
}
inline void store_two(Eigen::Vector3d* v, const TwoVectors& t) {
    double* p = v->data();
    _mm_storeu_pd(p, _mm_unpacklo_pd(t.x, t.y));
    _mm_storeu_pd(p + 2, _mm_shuffle_pd(t.z, t.x, 2));
    _mm_storeu_pd(p + 4, _mm_unpackhi_pd(t.y, t.z));
}
/// (a.x^2 + a.y^2) + a.z^2 per lane: Eigen's squaredNorm of a 3-vector, in its order.
inline __m128d squared_norm(const TwoVectors& a) {
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(a.x, a.x), _mm_mul_pd(a.y, a.y)), _mm_mul_pd(a.z, a.z));
}
#endif

/// to_local_frame over particles [lo, hi). Two particles at a time in SSE2 (the baseline of
/// x86-64) where available: each lane does the scalar code's operations in its order (the
/// three dot products of EnclosureState::to_local, Eigen's squaredNorm), and a maximum is
/// exact whatever the order, so the results are bitwise those of the scalar loop (kept for
/// the last odd particle and other targets). About 40 % fewer instructions for this pass,
/// which every step runs over every particle (docs/performance.md).
double local_frame_range(const EnclosureState& es, const Eigen::Vector3d* x,
                         const Eigen::Vector3d* xb, Eigen::Vector3d* xl, std::size_t lo,
                         std::size_t hi, bool rotated, bool measure_displacement) {
    double max_disp2 = 0.0;
#if defined(__SSE2__)
    if (measure_displacement && hi - lo >= 2) {
        const __m128d px = _mm_set1_pd(es.position_m.x()), py = _mm_set1_pd(es.position_m.y()),
                      pz = _mm_set1_pd(es.position_m.z());
        // The rotation's columns, broadcast once (the stores to xl could alias it, so the
        // compiler would reload them every iteration).
        TwoVectors column[3];
        for (int k = 0; k < 3; ++k) {
            column[k] = {_mm_set1_pd(es.rotation(0, k)), _mm_set1_pd(es.rotation(1, k)),
                         _mm_set1_pd(es.rotation(2, k))};
        }
        // max(acc, v) as std::max(acc, v) takes it: v only when acc < v (a NaN v is skipped)
        __m128d acc = _mm_setzero_pd();
        std::size_t i = lo;
        for (; i + 2 <= hi; i += 2) {
            const TwoVectors xi = load_two(x + i);
            const TwoVectors d{_mm_sub_pd(xi.x, px), _mm_sub_pd(xi.y, py), _mm_sub_pd(xi.z, pz)};
            TwoVectors l = d;
            if (rotated) {
                auto dot = [&](const TwoVectors& c) {  // as Eigen's: (c0 d0 + c1 d1) + c2 d2
                    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(c.x, d.x), _mm_mul_pd(c.y, d.y)),
                                      _mm_mul_pd(c.z, d.z));
                };
                l = {dot(column[0]), dot(column[1]), dot(column[2])};
                store_two(xl + i, l);
            }
            const TwoVectors b = load_two(xb + i);
            const __m128d s =
                squared_norm({_mm_sub_pd(l.x, b.x), _mm_sub_pd(l.y, b.y), _mm_sub_pd(l.z, b.z)});
            acc = _mm_max_pd(s, acc);
        }
        double lanes[2];
        _mm_storeu_pd(lanes, acc);
        max_disp2 = std::max(lanes[0], lanes[1]);
        lo = i;
    }
#endif
    if (rotated && measure_displacement) {
        for (std::size_t i = lo; i < hi; ++i) {
            const Eigen::Vector3d l = es.to_local(x[i]);
            xl[i] = l;
            max_disp2 = std::max(max_disp2, (l - xb[i]).squaredNorm());
        }
    } else if (rotated) {
        for (std::size_t i = lo; i < hi; ++i) xl[i] = es.to_local(x[i]);
    } else if (measure_displacement) {
        for (std::size_t i = lo; i < hi; ++i) {
            max_disp2 = std::max(max_disp2, (x[i] - es.position_m - xb[i]).squaredNorm());
        }
    }
    return max_disp2;
}

}  // namespace

double Solver::to_local_frame(bool measure_displacement) {
    // With the enclosure turned, the frame change is stored for the sweep's wall tests;
    // axis-aligned, they subtract the origin themselves and nothing is stored unless the
    // list is rebuilt. The largest displacement does not depend on the threads' shares.
    const std::size_t n = state_.size();
    const int used = threads_for(thread_count(), n, grain());
    if (used == 1) {
        return local_frame_range(enclosure_state_, state_.x.data(), x_at_build_.data(),
                                 local_x_.data(), 0, n, rotated_, measure_displacement);
    }
    double max_disp2 = 0.0;
#pragma omp parallel num_threads(used) reduction(max : max_disp2)
    {
        const auto t = static_cast<std::size_t>(omp_get_thread_num());
        const auto u = static_cast<std::size_t>(used);
        max_disp2 = local_frame_range(enclosure_state_, state_.x.data(), x_at_build_.data(),
                                      local_x_.data(), n * t / u, n * (t + 1) / u, rotated_,
                                      measure_displacement);
    }
    return max_disp2;
}

void Solver::fill_local_x() {
    if (rotated_) return;  // to_local_frame stored it
    const auto& es = enclosure_state_;
    for (std::size_t i = 0; i < state_.size(); ++i) local_x_[i] = state_.x[i] - es.position_m;
}

void Solver::adapt_skin() {
    // A step costs, besides its contacts, the candidate tests of the pairs the skin adds,
    // c(s), and a share of the rebuilds, b / s (n particles every L steps, L proportional to
    // s: the fastest particle crosses half the skin). The sum is least where s c'(s) = b / s.
    // s c'(s) is taken as twice the candidates of the list just used that lay in the outer
    // half of its skin (a bed resting in contact has many pairs just apart, which every skin
    // holds: counting the whole shell would shrink the skin too far), b / s as the rebuild
    // cost over the steps that list lasted; one Newton step on s gives
    // s* = s sqrt(rebuild cost / (s c'(s))). The factor is bounded so that one odd interval
    // (an impact, a release) moves the skin by at most a factor of two.
    const double steps = static_cast<double>(std::max<std::int64_t>(1, step_ - step_at_build_));
    const double shell = 2.0 * static_cast<double>(outer_half_);
    const double rebuild = kRebuildCostPerParticle * static_cast<double>(state_.size()) / steps;
    const double factor = shell > 0.0 ? std::clamp(std::sqrt(rebuild / shell), 0.5, 2.0) : 2.0;
    skin_ = std::clamp(skin_ * factor, kMinSkinShare * skin_max_, skin_max_);
}

void Solver::build_neighbors() {
    // Uniform grid in the enclosure frame (cell >= largest diameter + skin), counting sort,
    // then per particle the candidates j > i within r_i + r_j + skin, sorted by j.
    if (options_.adapt_neighbor_skin && !x_at_build_.empty()) adapt_skin();
    const std::size_t n = state_.size();
    const auto ncell = cell_start_.size() - 1;
    const double inv_cell = 1.0 / cell_;
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d& xl = local_x_[i];
        int idx[3];
        for (int a = 0; a < 3; ++a) {
            // truncation = floor for the non-negative values; outside values are clamped
            const int c = static_cast<int>((xl[a] - grid_lo_[a]) * inv_cell);
            idx[a] = std::clamp(c, 0, dims_[a] - 1);
        }
        cell_of_[i] = static_cast<std::uint32_t>((idx[2] * dims_[1] + idx[1]) * dims_[0] + idx[0]);
    }
    std::fill(cell_start_.begin(), cell_start_.end(), 0u);
    for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
    for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
    cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
        cell_items_[cursor_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
    }
    const int used = threads_for(thread_count(), n, grain());
    nbr_buffers_.resize(static_cast<std::size_t>(used));
    count_.resize(n);
    // Returns the candidates of its particles that lie in the outer half of the skin.
    auto scan = [&](int t) {
        auto& buf = nbr_buffers_[static_cast<std::size_t>(t)];
        buf.clear();
        std::size_t outer = 0;
        const std::size_t lo = n * static_cast<std::size_t>(t) / static_cast<std::size_t>(used);
        const std::size_t hi = n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(used);
        for (std::size_t i = lo; i < hi; ++i) {
            const std::size_t first = buf.size();
            const Eigen::Vector3d& xi = local_x_[i];
            const double ri = state_.radius[i] + skin_;
            const std::uint32_t c = cell_of_[i];
            const auto d0 = static_cast<std::uint32_t>(dims_[0]);
            const auto d1 = static_cast<std::uint32_t>(dims_[1]);
            const int cx = static_cast<int>(c % d0), cy = static_cast<int>((c / d0) % d1);
            const int cz = static_cast<int>(c / (d0 * d1));
            // 9 rows of 3 cells: cells adjacent in x are contiguous in cell_items_
            const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, dims_[0] - 1);
            for (int z = std::max(cz - 1, 0); z <= std::min(cz + 1, dims_[2] - 1); ++z) {
                for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, dims_[1] - 1); ++y) {
                    const auto row = static_cast<std::size_t>((z * dims_[1] + y) * dims_[0]);
                    const std::uint32_t k0 = cell_start_[row + static_cast<std::size_t>(x0)];
                    const std::uint32_t k1 = cell_start_[row + static_cast<std::size_t>(x1) + 1];
                    for (std::uint32_t k = k0; k < k1; ++k) {
                        const std::uint32_t j = cell_items_[k];
                        if (j <= i) continue;
                        const double rs = ri + state_.radius[j];
                        const double d2 = (xi - local_x_[j]).squaredNorm();
                        if (d2 < rs * rs) {
                            buf.push_back(j);
                            const double inner = rs - 0.5 * skin_;
                            if (d2 >= inner * inner) ++outer;
                        }
                    }
                }
            }
            std::sort(buf.begin() + static_cast<std::ptrdiff_t>(first), buf.end());
            count_[i] = static_cast<std::uint32_t>(buf.size() - first);
        }
        return outer;
    };
    std::size_t outer_half = 0;  // an integer sum: the same for any thread count
    if (used == 1) {
        outer_half = scan(0);
    } else {
#pragma omp parallel num_threads(used) reduction(+ : outer_half)
        outer_half += scan(omp_get_thread_num());
    }
    // New list; the pair slots (contact flag and tangential history) follow their pairs.
    std::swap(nbr_begin_, old_nbr_begin_);
    std::swap(nbr_list_, old_nbr_list_);
    std::swap(pair_active_, old_pair_active_);
    std::swap(pair_hist_, old_pair_hist_);
    nbr_begin_.resize(n + 1);
    nbr_begin_[0] = 0;
    for (std::size_t i = 0; i < n; ++i) nbr_begin_[i + 1] = nbr_begin_[i] + count_[i];
    nbr_list_.clear();
    for (const auto& buf : nbr_buffers_) nbr_list_.insert(nbr_list_.end(), buf.begin(), buf.end());
    const std::size_t slots = nbr_list_.size();
    pair_active_.assign(slots, PairFlag::apart);
    if (has_history_) pair_hist_.assign(slots, Eigen::Vector3d::Zero());
    pair_share_.resize(slots);
    pair_delta_.resize(slots);
    pair_kl_.resize(slots);
    if (!old_nbr_begin_.empty()) {
        for (std::size_t i = 0; i < n; ++i) {  // both segments sorted by j: merge walk
            std::uint32_t q = old_nbr_begin_[i];
            const std::uint32_t qe = old_nbr_begin_[i + 1];
            for (std::uint32_t k = nbr_begin_[i]; k < nbr_begin_[i + 1] && q < qe; ++k) {
                while (q < qe && old_nbr_list_[q] < nbr_list_[k]) ++q;
                if (q < qe && old_nbr_list_[q] == nbr_list_[k] &&
                    old_pair_active_[q] == PairFlag::touching) {
                    pair_active_[k] = PairFlag::touching;
                    if (has_history_) pair_hist_[k] = old_pair_hist_[q];
                }
            }
        }
    }
    // Reverse index: the slots where each particle is the partner j, in slot order (= the
    // order of i), for the fixed-order gather.
    rev_begin_.assign(n + 1, 0);
    for (const std::uint32_t j : nbr_list_) ++rev_begin_[j + 1];
    for (std::size_t i = 0; i < n; ++i) rev_begin_[i + 1] += rev_begin_[i];
    rev_slot_.resize(slots);
    recv_slot_.resize(slots);
    recv_count_.assign(n, 0);
    cursor_.assign(rev_begin_.begin(), rev_begin_.end() - 1);
    for (std::size_t q = 0; q < slots; ++q) {
        rev_slot_[cursor_[nbr_list_[q]]++] = static_cast<std::uint32_t>(q);
    }
    // Thread chunks of about equal work (candidates + a per-particle share); the results do
    // not depend on where they fall.
    const int sweep_threads = threads_for(thread_count(), n, grain());
    chunk_.assign(static_cast<std::size_t>(sweep_threads) + 1, 0);
    chunk_.back() = static_cast<std::uint32_t>(n);
    if (sweep_threads > 1) {
        constexpr double kParticleWork = 4.0;  // walls and integration, in candidate units
        const double total = static_cast<double>(slots) + kParticleWork * static_cast<double>(n);
        std::size_t t = 1;
        for (std::size_t i = 0; i < n && t < chunk_.size() - 1; ++i) {
            const double done =
                static_cast<double>(nbr_begin_[i]) + kParticleWork * static_cast<double>(i);
            if (done >= total * static_cast<double>(t) / sweep_threads) {
                chunk_[t++] = static_cast<std::uint32_t>(i);
            }
        }
        for (; t < chunk_.size() - 1; ++t) chunk_[t] = static_cast<std::uint32_t>(n);
    }
    x_at_build_ = local_x_;
    step_at_build_ = step_;
    outer_half_ = outer_half;
    ++neighbor_builds_;
}

SB_ALWAYS_INLINE bool Solver::deep_inside(const Eigen::Vector3d& xl) const {
    // Conservative: true only if Enclosure::for_each_contact would emit nothing, so skipping
    // it changes no result. The bounds are the largest sphere's with a margin (constructor):
    // one comparison per wall holds for every radius; every comparison is false for NaN.
    if (!(xl.z() >= deep_lo_.z() && xl.z() <= deep_hi_.z())) return false;
    if (cylinder_radius_ > 0.0) return xl.x() * xl.x() + xl.y() * xl.y() < deep_rho2_;
    return xl.x() >= deep_lo_.x() && xl.x() <= deep_hi_.x() && xl.y() >= deep_lo_.y() &&
           xl.y() <= deep_hi_.y();
}

template <class Law>
SB_ALWAYS_INLINE Solver::Accumulated Solver::own_contacts(const Law& law, std::size_t i, double dt,
                                                          SweepLocal& loc) {
    const auto& es = enclosure_state_;
    const double frac = options_.max_overlap_fraction;
    Accumulated a;
    const Eigen::Vector3d xi = state_.x[i], vi = state_.v[i], wi = state_.w[i];
    const double ri = state_.radius[i];
    bool overlap = false;
    // Pairs: slots of i's Verlet list (j > i); the partner's share goes to the slot.
    {
        const PairCoefficients& p = coeff_[0];
        const std::uint32_t q_end = nbr_begin_[i + 1];
        const Eigen::Vector3d* x = state_.x.data();
        const double* radius = state_.radius.data();
        PairFlag* active = pair_active_.data();
        const std::uint32_t* list = nbr_list_.data();
        const Eigen::Vector3d* v = state_.v.data();
        const Eigen::Vector3d* w = state_.w.data();
        for (std::uint32_t q = nbr_begin_[i]; q < q_end; ++q) {
            const std::uint32_t j = list[q];
            const Eigen::Vector3d d = xi - x[j];
            const double rj = radius[j];
            const double rs = ri + rj;
            const double d2 = d.squaredNorm();
            if (d2 >= rs * rs) {
                active[q] = PairFlag::apart;
                continue;
            }
            const double dist = std::sqrt(d2);
            const double delta = rs - dist;
            const Eigen::Vector3d n =
                dist > 0.0 ? Eigen::Vector3d(d / dist) : Eigen::Vector3d(0.0, 0.0, 1.0);
            Eigen::Vector3d no_hist = Eigen::Vector3d::Zero();
            Eigen::Vector3d& hist = Law::kHasHistory ? pair_hist_[q] : no_hist;
            if (Law::kHasHistory && active[q] == PairFlag::apart) hist.setZero();
            active[q] = PairFlag::touching;
            ContactKinematics k;
            k.delta = delta;
            k.n = n;
            k.dt = dt;
            // Branch vectors b_i = -a_i n and b_j = a_j n to the contact point: the spins'
            // share of the relative velocity, w_i x b_i - w_j x b_j, is n x (a_i w_i + a_j w_j),
            // and the torques b_i x F_t and b_j x (-F_t) are -a_i and -a_j times n x F_t: two
            // cross products instead of four.
            const double ai = ri - 0.5 * delta, aj = rj - 0.5 * delta;
            const Eigen::Vector3d vrel = vi - v[j] + n.cross(ai * wi + aj * w[j]);
            if (class_count_ > 0) {  // no division per contact
                const MassConstants& mc =
                    class_pair_[size_class_[i] * class_count_ + size_class_[j]];
                k.m_eff = mc.m_eff;
                k.r_eff = mc.r_eff;
                k.m_t = mc.m_t;
                k.i_eff = mc.i_eff;
            } else {
                // without size classes (polydisperse beds) only; read here, not per particle
                const double* inv_mass = state_.inv_mass.data();
                const double* inv_inertia = state_.inv_inertia.data();
                const double imi = inv_mass[i], iii = inv_inertia[i], imj = inv_mass[j];
                k.m_eff = 1.0 / (imi + imj);
                k.r_eff = ri * rj / (ri + rj);
                k.m_t = 1.0 / (3.5 * (imi + imj));
                k.i_eff = 1.0 / (iii + inv_inertia[j]);
            }
            k.r_hertz = k.r_eff;
            k.omega_rel = wi - w[j];
            if (delta > frac * std::min(ri, rj)) overlap = true;
            const double vn = vrel.dot(n);
            k.delta_dot = -vn;
            k.v_t = vrel - vn * n;
            const LawForce r = law.evaluate(k, p, hist);
            const Eigen::Vector3d f = r.fn * n + r.ft;
            const Eigen::Vector3d nxft = n.cross(r.ft);
            const Eigen::Vector3d ti = r.mr - ai * nxft;
            PairShare& share = pair_share_[q];
            share.f = f;
            share.tj = -aj * nxft - r.mr;
            if (serial_sweep_) {
                // j > i is integrated later in this sweep: it gathers its touching slots from
                // this list, filled in increasing i, the order of its reverse index.
                recv_slot_[rev_begin_[j] + recv_count_[j]++] = q;
            }
            pair_delta_[q] = delta;
            pair_kl_[q] = r.k_law;
            a.f += f;
            a.t += ti;
            ++loc.contacts;
            if (loc.log != nullptr) {
                loc.log->push_back({static_cast<std::uint32_t>(i), j, delta, n, f, ti,
                                    Eigen::Vector3d(xi - ai * n), r.f_spring, r.fn - r.f_spring});
            }
        }
    }
    // Walls and obstacles in the enclosure frame, matched by id with the previous step's for
    // the history.
    std::uint32_t count = 0;
    // A sphere deep inside is inside (deep_inside is false for a non-finite xl), so the
    // outside guard and the wall tests only run near the walls. The centre in this step's
    // frame: stored by step() for a turned enclosure, else the shift by the origin.
    if (rotated_ ? !deep_inside(local_x_[i]) : !deep_inside(xi - es.position_m)) {
        const Eigen::Vector3d xl = rotated_ ? local_x_[i] : Eigen::Vector3d(xi - es.position_m);
        a.wf.setZero();
        a.wm.setZero();
        const std::size_t base = i * wall_cap_;
        const PairCoefficients& wall_coefficients = coeff_[1];
        const PairCoefficients& rod_coefficients = coeff_[2];
        const PairCoefficients& side_coefficients = coeff_[3];
        const std::uint32_t lateral_walls = enclosure_.lateral_wall_ids();
        const std::uint32_t prev_count = prev_wall_count_[i];
        std::uint32_t prev = 0;
        auto contact = [&](std::uint32_t wall, const Eigen::Vector3d& nl, double delta) {
            const std::size_t s = base + count++;
            wall_id_[s] = wall;
            Eigen::Vector3d no_hist = Eigen::Vector3d::Zero();
            Eigen::Vector3d& hist = Law::kHasHistory ? wall_hist_[s] : no_hist;
            if constexpr (Law::kHasHistory) {
                while (prev < prev_count && prev_wall_id_[base + prev] < wall) ++prev;
                hist = prev < prev_count && prev_wall_id_[base + prev] == wall
                           ? prev_wall_hist_[base + prev]
                           : Eigen::Vector3d::Zero();
            }
            const Eigen::Vector3d n = rotated_ ? es.rotate(nl) : nl;
            ContactKinematics k;
            k.delta = delta;
            k.n = n;
            k.dt = dt;
            const Eigen::Vector3d bi = -(ri - 0.5 * delta) * n;
            const Eigen::Vector3d xc = xi + bi;
            const Eigen::Vector3d vrel = vi + wi.cross(bi) - es.velocity_at(xc);
            if (class_count_ > 0) {
                const MassConstants& mc = class_wall_[size_class_[i]];
                k.m_eff = mc.m_eff;
                k.m_t = mc.m_t;
                k.i_eff = mc.i_eff;
            } else {
                const double imi = state_.inv_mass[i], iii = state_.inv_inertia[i];
                k.m_eff = 1.0 / imi;
                k.m_t = 1.0 / (3.5 * imi);
                k.i_eff = 1.0 / iii;
            }
            k.r_eff = ri;
            k.r_hertz = wall >= kRodBase ? hertz_r_rod_[i]
                        : wall == 0      ? hertz_r_side_[i]  // cylinder side (box: = ri)
                                         : ri;
            k.omega_rel = wi - es.angular_velocity_rad_s;
            if (delta > frac * ri) overlap = true;
            const double vn = vrel.dot(n);
            k.delta_dot = -vn;
            k.v_t = vrel - vn * n;
            const LawForce r = law.evaluate(k,
                                            wall >= kRodBase       ? rod_coefficients
                                            : wall < lateral_walls ? side_coefficients
                                                                   : wall_coefficients,
                                            hist);
            const Eigen::Vector3d f = r.fn * n + r.ft;
            const Eigen::Vector3d ti = bi.cross(r.ft) + r.mr;
            wall_delta_[s] = delta;
            wall_kl_[s] = r.k_law;
            a.f += f;
            a.t += ti;
            a.wf -= f;
            a.wm += Eigen::Vector3d((xc - es.position_m).cross(-f) - r.mr);
            ++loc.contacts;
            if (loc.log != nullptr) {
                loc.log->push_back({static_cast<std::uint32_t>(i),
                                    static_cast<std::uint32_t>(state_.size()) + wall, delta, n, f,
                                    ti, xc, r.f_spring, r.fn - r.f_spring});
            }
        };
        // The outside guard: among rods, the lattice's nearest nodes serve both queries.
        bool inside;
        if (has_obstacles_) {
            inside = enclosure_.contacts_and_contains(xl, ri, contact);
        } else {
            inside = enclosure_.inside_walls(xl);
            enclosure_.for_each_contact(xl, ri, contact);
        }
        if (!inside && loc.outside == kNoParticle) loc.outside = static_cast<int>(i);
    }
    wall_count_[i] = count;
    if (overlap && loc.overlap == kNoParticle) loc.overlap = static_cast<int>(i);
    return a;
}

SB_ALWAYS_INLINE void Solver::finish_particle(std::size_t i, const Accumulated& a, double dt,
                                              SweepLocal& loc) {
    // Partner shares in slot order (fixed, whatever the thread count), then semi-implicit
    // Euler (paper 000).
    Eigen::Vector3d f = a.f, t = a.t;
    const PairShare* share = pair_share_.data();
    if (serial_sweep_) {  // the touching slots only, listed by the partners' own_contacts
        const std::uint32_t* slots = recv_slot_.data() + rev_begin_[i];
        for (std::uint32_t k = 0, ke = recv_count_[i]; k < ke; ++k) {
            f -= share[slots[k]].f;
            t += share[slots[k]].tj;
        }
        recv_count_[i] = 0;
    } else {
        const std::uint32_t* slots = rev_slot_.data();
        const PairFlag* active = pair_active_.data();
        for (std::uint32_t q = rev_begin_[i], qe = rev_begin_[i + 1]; q < qe; ++q) {
            const std::uint32_t slot = slots[q];
            if (active[slot] == PairFlag::apart) continue;
            f -= share[slot].f;
            t += share[slot].tj;
        }
    }
    Eigen::Vector3d& v = state_.v[i];
    Eigen::Vector3d& w = state_.w[i];
    Eigen::Vector3d& x = state_.x[i];
    if (track_energy_) {
        v_old_[i] = v;
        w_old_[i] = w;
    }
    v += dt * (state_.inv_mass[i] * f + gravity_);
    w += (dt * state_.inv_inertia[i]) * t;
    x += dt * v;
    // One NaN or infinity anywhere makes the sum non-finite (cheaper than allFinite). v needs
    // no term of its own: x was finite (else the last step stopped), so a non-finite v makes
    // x = x + dt v non-finite in this same step.
    if (!std::isfinite(x.sum() + w.sum()) && loc.not_finite == kNoParticle) {
        loc.not_finite = static_cast<int>(i);
    }
}

template <class Law>
void Solver::sweep(const Law& law, double dt) {
    const std::size_t n = state_.size();
    const int used = static_cast<int>(chunk_.size()) - 1;
    std::swap(wall_count_, prev_wall_count_);
    std::swap(wall_id_, prev_wall_id_);
    if (has_history_) std::swap(wall_hist_, prev_wall_hist_);
    // Only the threads' own entries are reset (64 default-constructed entries cost more than
    // the free-flight work of ten particles).
    sweep_local_.resize(static_cast<std::size_t>(used));
    std::fill(sweep_local_.begin(), sweep_local_.end(), SweepLocal{});
    SweepLocal* loc = sweep_local_.data();
    if (track_energy_) {
        logs_.resize(static_cast<std::size_t>(used));
        for (int t = 0; t < used; ++t) {
            logs_[static_cast<std::size_t>(t)].clear();
            loc[t].log = &logs_[static_cast<std::size_t>(t)];
        }
    }
    Eigen::Vector3d wall_force = lock_force_, wall_moment = lock_moment_;
    serial_sweep_ = used == 1;
    if (used == 1) {
        // One pass: the pairs of i reach only j > i and the shares i receives come from
        // i' < i, already swept, so i is integrated in place right away.
        for (std::size_t i = 0; i < n; ++i) {
            const Accumulated a = own_contacts<Law>(law, i, dt, loc[0]);
            finish_particle(i, a, dt, loc[0]);
            if (wall_count_[i] != 0) {  // a sphere off the walls adds exact zeros
                wall_force += a.wf;
                wall_moment += a.wm;
            }
        }
    } else {
        // Same arithmetic per particle in two phases: every particle's own contacts (reading
        // the start-of-step state only), a barrier, then the gather and the update.
#pragma omp parallel num_threads(used)
        {
            const int t = omp_get_thread_num();
            const std::size_t lo = chunk_[static_cast<std::size_t>(t)];
            const std::size_t hi = chunk_[static_cast<std::size_t>(t) + 1];
            for (std::size_t i = lo; i < hi; ++i) {
                own_[i] = own_contacts<Law>(law, i, dt, loc[t]);
            }
#pragma omp barrier
            for (std::size_t i = lo; i < hi; ++i) finish_particle(i, own_[i], dt, loc[t]);
        }
        for (std::size_t i = 0; i < n; ++i) {
            if (wall_count_[i] == 0) continue;  // a sphere off the walls adds exact zeros
            wall_force += own_[i].wf;
            wall_moment += own_[i].wm;
        }
    }
    wall_force_ = wall_force;
    wall_moment_ = wall_moment;
    contact_count_ = 0;
    int outside = kNoParticle, overlap = kNoParticle, not_finite = kNoParticle;
    for (int t = 0; t < used; ++t) {
        contact_count_ += loc[t].contacts;
        outside = std::min(outside, loc[t].outside);
        overlap = std::min(overlap, loc[t].overlap);
        not_finite = std::min(not_finite, loc[t].not_finite);
    }
    if (outside != kNoParticle) {
        std::ostringstream msg;
        msg << kind_name(SimulationError::Kind::outside) << ": particle " << outside << " at step "
            << step_ << ", t = " << time_ << " s";
        throw SimulationError(SimulationError::Kind::outside, step_, time_, outside, msg.str());
    }
    if (overlap != kNoParticle) {
        std::ostringstream msg;
        msg << kind_name(SimulationError::Kind::overlap) << " (" << options_.max_overlap_fraction
            << " of the radius): particle " << overlap << " at step " << step_ << ", t = " << time_
            << " s";
        throw SimulationError(SimulationError::Kind::overlap, step_, time_, overlap, msg.str());
    }
    if (not_finite != kNoParticle) {
        std::ostringstream msg;
        msg << kind_name(SimulationError::Kind::not_finite) << ": particle " << not_finite
            << " at step " << step_ << ", t = " << time_ << " s";
        throw SimulationError(SimulationError::Kind::not_finite, step_, time_, not_finite,
                              msg.str());
    }
}

void Solver::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt)) {
        throw std::invalid_argument("Solver::step: dt must be > 0, got " + format_value(dt));
    }
    // Once: a partial release leaves some locked, and released_ keeps them so.
    if (locked_count_ > 0 && !released_ && options_.lock.release_time_s > 0 &&
        time_ >= options_.lock.release_time_s) {
        release(static_cast<int>(
            std::llround(options_.lock.release_fraction * static_cast<double>(state_.x.size()))));
    }
    if (locked_count_ > 0) {
        snap_locked(dt);
    } else {
        lock_force_.setZero();
        lock_moment_.setZero();
    }
    // axis-aligned enclosure (the usual shaker set-up): local = world - origin
    rotated_ = enclosure_state_.rotation != Eigen::Matrix3d::Identity();
    // Every centre in this step's enclosure frame, once: the sweep's wall tests read it, and
    // so does the Verlet criterion. Pair distances are the same in any rigidly moving frame,
    // so the displacement since the build, measured in this frame, bounds how much closer
    // two spheres came; the lists are sorted by partner, so when they are rebuilt changes no
    // result as long as they hold every touching pair.
    const bool built = !x_at_build_.empty();
    const double max_disp2 = to_local_frame(built);
    if (!built || 4.0 * max_disp2 >= skin_ * skin_) {
        fill_local_x();
        build_neighbors();
    }
    std::visit(
        [&](const auto& nm, const auto& dm, const auto& tg, const auto& rl) {
            using L = ComposedLaw<std::decay_t<decltype(nm)>, std::decay_t<decltype(dm)>,
                                  std::decay_t<decltype(tg)>, std::decay_t<decltype(rl)>>;
            const L law{nm, dm, tg, rl};
            sweep(law, dt);
        },
        law_.normal, law_.damping, law_.tangential, law_.rolling);
    if (locked_count_ > 0) add_held_reaction(dt);
    stepped_ = true;
    if (track_energy_) account_energy(dt);
    time_ += dt;
    ++step_;
}

void Solver::account_energy(double dt) {
    // Per contact with the mid-step velocities (after the update), then summed in contact
    // order (the thread logs are in particle order).
    const auto nn = static_cast<std::uint32_t>(state_.size());
    const auto& es = enclosure_state_;
    auto work = [&](std::vector<EnergyRecord>& log) {
        for (EnergyRecord& r : log) {
            const std::size_t i = r.i;
            const bool wall = r.j >= nn;
            const Eigen::Vector3d vi = 0.5 * (v_old_[i] + state_.v[i]);
            const Eigen::Vector3d wi = 0.5 * (w_old_[i] + state_.w[i]);
            const Eigen::Vector3d bi = r.xc - (state_.x[i] - dt * state_.v[i]);
            Eigen::Vector3d vrel, wrel;
            double wall_work = 0.0;
            const double fn = r.fs + r.fd;
            const Eigen::Vector3d ft = r.f - fn * r.n;
            const Eigen::Vector3d mr = r.ti - bi.cross(ft);
            if (!wall) {
                const std::size_t j = r.j;
                const Eigen::Vector3d vj = 0.5 * (v_old_[j] + state_.v[j]);
                const Eigen::Vector3d wj = 0.5 * (w_old_[j] + state_.w[j]);
                const Eigen::Vector3d bj = (state_.radius[j] - 0.5 * r.delta) * r.n;
                vrel = vi + wi.cross(bi) - vj - wj.cross(bj);
                wrel = wi - wj;
            } else {
                const Eigen::Vector3d vw = es.velocity_at(r.xc);
                vrel = vi + wi.cross(bi) - vw;
                wrel = wi - es.angular_velocity_rad_s;
                wall_work = (r.f.dot(vw) + mr.dot(es.angular_velocity_rad_s)) * dt;
            }
            const double vn = vrel.dot(r.n);
            r.e[0] = wall_work;
            r.e[1] = r.fd * (-vn) * dt;
            r.e[2] = -ft.dot(vrel - vn * r.n) * dt;
            r.e[3] = -mr.dot(wrel) * dt;
        }
    };
    const int used = static_cast<int>(logs_.size());
    if (used == 1) {
        work(logs_[0]);
    } else {
#pragma omp parallel num_threads(used)
        work(logs_[static_cast<std::size_t>(omp_get_thread_num())]);
    }
    // Layers along gravity (not along the enclosure axis): for a tilted or lying enclosure
    // the bed stacks along g, and paper 002's Fig. 13 counts its layers upwards from the floor.
    const bool layered = layers_.count() > 0;
    for (const auto& log : logs_) {
        for (const EnergyRecord& r : log) {
            ledger_.wall_work += r.e[0];
            ledger_.normal_damping += r.e[1];
            ledger_.friction += r.e[2];
            ledger_.rolling += r.e[3];
            if (layered) {
                const int l = layers_.index(es.to_local(r.xc));
                ledger_.layer_dissipation[static_cast<std::size_t>(l)] += r.e[1] + r.e[2] + r.e[3];
            }
        }
    }
    // The layers' agitation: each particle's kinetic energy relative to the walls after the
    // step, in the layer of its centre, in particle order (the same for any thread count).
    if (layered) {
        for (std::size_t i = 0; i < state_.size(); ++i) {
            const int l = layers_.index(es.to_local(state_.x[i]));
            ledger_.layer_kinetic_time[static_cast<std::size_t>(l)] +=
                relative_kinetic_energy(i) * dt;
        }
    }
}

double Solver::relative_kinetic_energy(std::size_t i) const {
    const EnclosureState& e = enclosure_state_;
    const Eigen::Vector3d spin = state_.w[i] - e.angular_velocity_rad_s;
    return 0.5 * (state_.v[i] - e.velocity_at(state_.x[i])).squaredNorm() / state_.inv_mass[i] +
           0.5 * spin.squaredNorm() / state_.inv_inertia[i];
}

double Solver::relative_kinetic_energy() const {
    double energy = 0.0;
    for (std::size_t i = 0; i < state_.size(); ++i) energy += relative_kinetic_energy(i);
    return energy;
}

EnergyLedger Solver::energy() const {
    EnergyLedger e = ledger_;
    e.kinetic_translational = e.kinetic_rotational = e.potential = e.elastic = 0.0;
    const Eigen::Vector3d g = options_.gravity_m_s2;
    for (std::size_t i = 0; i < state_.size(); ++i) {
        const double m = 1.0 / state_.inv_mass[i];
        e.kinetic_translational += 0.5 * m * state_.v[i].squaredNorm();
        e.kinetic_rotational += 0.5 / state_.inv_inertia[i] * state_.w[i].squaredNorm();
        e.potential -= m * g.dot(state_.x[i]);
    }
    // Springs of the last step's contacts, in contact order (per particle: pairs, walls).
    const bool hertz = std::holds_alternative<Hertz>(law_.normal);
    auto spring = [hertz](double kl, double d) {
        return hertz ? Hertz::energy(kl, d) : Hooke::energy(kl, d);
    };
    if (stepped_) {
        for (std::size_t i = 0; i < state_.size(); ++i) {
            for (std::uint32_t q = nbr_begin_[i]; q < nbr_begin_[i + 1]; ++q) {
                if (pair_active_[q] == PairFlag::touching)
                    e.elastic += spring(pair_kl_[q], pair_delta_[q]);
            }
            for (std::uint32_t s = 0; s < wall_count_[i]; ++s) {
                const std::size_t k = i * wall_cap_ + s;
                e.elastic += spring(wall_kl_[k], wall_delta_[k]);
            }
        }
    }
    return e;
}

void Solver::reset_energy() {
    ledger_ = EnergyLedger{};
    ledger_.layer_dissipation.assign(static_cast<std::size_t>(options_.energy_layers), 0.0);
    ledger_.layer_kinetic_time.assign(static_cast<std::size_t>(options_.energy_layers), 0.0);
    ledger_.initial_total = energy().mechanical();
}

void Solver::continue_energy(const EnergyLedger& saved) {
    const auto layers = static_cast<std::size_t>(options_.energy_layers);
    if (saved.layer_dissipation.size() != layers || saved.layer_kinetic_time.size() != layers) {
        throw std::invalid_argument("energy ledger of " +
                                    std::to_string(saved.layer_dissipation.size()) +
                                    " layers for a solver of " + std::to_string(layers));
    }
    ledger_.wall_work = saved.wall_work;
    ledger_.normal_damping = saved.normal_damping;
    ledger_.friction = saved.friction;
    ledger_.rolling = saved.rolling;
    ledger_.initial_total = saved.initial_total;
    ledger_.layer_dissipation = saved.layer_dissipation;
    ledger_.layer_kinetic_time = saved.layer_kinetic_time;
}

namespace {

/// The enclosure-frame particles of world-frame arrays at pose e (the one formula of
/// local_snapshot() and local_particles()).
ParticleSet to_enclosure_frame(const EnclosureState& e, const std::vector<Eigen::Vector3d>& x,
                               const std::vector<Eigen::Vector3d>& v,
                               const std::vector<Eigen::Vector3d>& w,
                               const std::vector<double>& radius) {
    ParticleSet s;
    const std::size_t n = x.size();
    s.positions_m.reserve(n);
    s.velocities_m_s.reserve(n);
    s.angular_velocities_rad_s.reserve(n);
    s.radii_m = radius;
    for (std::size_t i = 0; i < n; ++i) {
        s.positions_m.push_back(e.to_local(x[i]));
        s.velocities_m_s.push_back(e.rotation.transpose() * (v[i] - e.velocity_at(x[i])));
        s.angular_velocities_rad_s.push_back(e.rotation.transpose() * w[i]);
    }
    return s;
}

}  // namespace

ParticleSet Solver::local_snapshot() const {
    return to_enclosure_frame(enclosure_state_, state_.x, state_.v, state_.w, state_.radius);
}

ParticleSet local_particles(const SolverState& state) {
    const std::size_t n = state.positions_m.size();
    if (state.velocities_m_s.size() != n || state.angular_velocities_rad_s.size() != n ||
        state.radii_m.size() != n) {
        throw std::invalid_argument("solver state: " + std::to_string(n) + " positions but " +
                                    std::to_string(state.velocities_m_s.size()) + " velocities, " +
                                    std::to_string(state.angular_velocities_rad_s.size()) +
                                    " angular velocities and " +
                                    std::to_string(state.radii_m.size()) + " radii");
    }
    return to_enclosure_frame(state.enclosure, state.positions_m, state.velocities_m_s,
                              state.angular_velocities_rad_s, state.radii_m);
}

SolverState Solver::state() const {
    SolverState s;
    s.enclosure = enclosure_state_;
    s.positions_m = state_.x;
    s.velocities_m_s = state_.v;
    s.angular_velocities_rad_s = state_.w;
    s.radii_m = state_.radius;
    const std::size_t n = state_.size();
    // The springs of the last step's contacts (touching pairs, in slot order = sorted by j;
    // walls in emission order = ascending id): the next step continues exactly these.
    if (has_history_) {
        if (!nbr_begin_.empty()) {
            for (std::size_t i = 0; i < n; ++i) {
                for (std::uint32_t q = nbr_begin_[i]; q < nbr_begin_[i + 1]; ++q) {
                    if (pair_active_[q] == PairFlag::touching) {
                        s.pair_histories.push_back(
                            {static_cast<std::uint32_t>(i), nbr_list_[q], pair_hist_[q]});
                    }
                }
            }
        }
        for (std::size_t i = 0; i < n; ++i) {
            for (std::uint32_t k = 0; k < wall_count_[i]; ++k) {
                const std::size_t slot = i * wall_cap_ + k;
                s.wall_histories.push_back(
                    {static_cast<std::uint32_t>(i), wall_id_[slot], wall_hist_[slot]});
            }
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (state_.locked[i]) s.locked.push_back({static_cast<std::uint32_t>(i), lock_local_[i]});
    }
    s.released = released_;
    s.time_s = time_;
    s.step = step_;
    s.layers_up = layers_up_;
    return s;
}

void Solver::restore(const SolverState& s) {
    const std::size_t n = state_.size();
    std::vector<std::string> errors;
    auto finite = [](const Eigen::Vector3d& v) { return v.allFinite(); };
    if (!s.enclosure.finite()) errors.push_back("enclosure: not finite");
    for (std::size_t i = 0; i < n; ++i) {
        if (!finite(s.positions_m[i]) || !finite(s.velocities_m_s[i]) ||
            !finite(s.angular_velocities_rad_s[i])) {
            errors.push_back("particle " + std::to_string(i) + ": not finite");
            break;
        }
    }
    if (!(std::isfinite(s.time_s) && s.time_s >= 0.0)) {
        errors.push_back("time_s = " + format_value(s.time_s) + ": must be finite and >= 0");
    }
    if (s.step < 0) errors.push_back("step = " + std::to_string(s.step) + ": must be >= 0");
    if (!finite(s.layers_up)) errors.push_back("layers_up: not finite");
    // The springs sorted as the solver keeps them (pairs by i then j, walls by particle then
    // id), each contact once.
    std::vector<PairHistory> pairs = s.pair_histories;
    std::vector<WallHistory> walls = s.wall_histories;
    std::sort(pairs.begin(), pairs.end(), [](const PairHistory& a, const PairHistory& b) {
        return a.i != b.i ? a.i < b.i : a.j < b.j;
    });
    std::sort(walls.begin(), walls.end(), [](const WallHistory& a, const WallHistory& b) {
        return a.particle != b.particle ? a.particle < b.particle : a.wall < b.wall;
    });
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const PairHistory& p = pairs[k];
        const std::string name =
            "pair history (" + std::to_string(p.i) + ", " + std::to_string(p.j) + ")";
        if (!(p.i < p.j && p.j < n))
            errors.push_back(name + ": needs i < j < " + std::to_string(n));
        if (k > 0 && pairs[k - 1].i == p.i && pairs[k - 1].j == p.j) {
            errors.push_back(name + ": given twice");
        }
        if (!finite(p.history_m)) errors.push_back(name + ": not finite");
    }
    for (std::size_t k = 0, run = 0; k < walls.size(); ++k) {
        const WallHistory& w = walls[k];
        const std::string name = "wall history (particle " + std::to_string(w.particle) +
                                 ", wall " + std::to_string(w.wall) + ")";
        if (w.particle >= n) errors.push_back(name + ": no such particle");
        const bool same_particle = k > 0 && walls[k - 1].particle == w.particle;
        if (same_particle && walls[k - 1].wall == w.wall) errors.push_back(name + ": given twice");
        run = same_particle ? run + 1 : 1;
        if (run == wall_cap_ + 1) {
            errors.push_back(name + ": more than " + std::to_string(wall_cap_) +
                             " walls for one particle");
        }
        if (!finite(w.history_m)) errors.push_back(name + ": not finite");
    }
    std::vector<std::uint8_t> seen(n, 0);
    for (const LockedParticle& l : s.locked) {
        const std::string name = "locked particle " + std::to_string(l.id);
        if (l.id >= n) {
            errors.push_back(name + ": no such particle");
            continue;
        }
        if (seen[l.id]++ > 0) errors.push_back(name + ": given twice");
        if (!finite(l.position_m)) errors.push_back(name + ": not finite");
    }
    if (!errors.empty()) {
        std::ostringstream msg;
        msg << "invalid solver state:";
        for (const auto& e : errors) msg << "\n  " << e;
        throw std::invalid_argument(msg.str());
    }

    // At the state's own pose the world values are taken as they are (bitwise); elsewhere the
    // delegated constructor has placed the particles from local_particles(s), and the springs
    // turn with the enclosure: xi_new = R_new R_old^T xi.
    const EnclosureState& e0 = s.enclosure;
    const EnclosureState& e1 = enclosure_state_;
    const bool same_rotation = e0.rotation == e1.rotation;
    const bool same_place = same_rotation && e0.position_m == e1.position_m;
    const bool same_motion = same_place && e0.velocity_m_s == e1.velocity_m_s &&
                             e0.angular_velocity_rad_s == e1.angular_velocity_rad_s;
    if (same_place) state_.x = s.positions_m;
    if (same_motion) state_.v = s.velocities_m_s;
    if (same_rotation) state_.w = s.angular_velocities_rad_s;
    auto turned = [&](const Eigen::Vector3d& xi) -> Eigen::Vector3d {
        return same_rotation ? xi : e1.rotate(e0.rotation.transpose() * xi);
    };

    // Springs: the touching pairs become the current Verlet list (only they), which the first
    // step's neighbour build carries into its list like any previous one; the wall contacts
    // fill the current wall slots, which the first sweep reads as the previous step's.
    if (has_history_) {
        nbr_begin_.assign(n + 1, 0);
        nbr_list_.clear();
        pair_hist_.clear();
        for (const PairHistory& p : pairs) {
            ++nbr_begin_[p.i + 1];
            nbr_list_.push_back(p.j);
            pair_hist_.push_back(turned(p.history_m));
        }
        for (std::size_t i = 0; i < n; ++i) nbr_begin_[i + 1] += nbr_begin_[i];
        pair_active_.assign(pairs.size(), PairFlag::touching);
        std::fill(wall_count_.begin(), wall_count_.end(), 0u);
        for (const WallHistory& w : walls) {
            const std::size_t slot = w.particle * wall_cap_ + wall_count_[w.particle]++;
            wall_id_[slot] = w.wall;
            wall_hist_[slot] = turned(w.history_m);
        }
    }
    std::fill(state_.locked.begin(), state_.locked.end(), 0);
    for (const LockedParticle& l : s.locked) {
        state_.locked[l.id] = 1;
        lock_local_[l.id] = l.position_m;
    }
    locked_count_ = static_cast<int>(s.locked.size());
    released_ = s.released;
    time_ = s.time_s;
    step_ = s.step;
    if (s.layers_up != Eigen::Vector3d::Zero()) {
        layers_up_ = s.layers_up;
        layers_ = HorizontalLayers(enclosure_, layers_up_, options_.energy_layers);
    }
    reset_energy();
}

}  // namespace sb::dem

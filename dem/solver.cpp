// Solver: broad phase, per-contact forces (law visited once per step), deterministic gather,
// semi-implicit Euler (paper 000), guards, wall force and moment, energy ledger.
#include "dem/solver.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

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

/// f(i) for i in [0, n): a plain loop for one thread (no OpenMP region at all: its fixed cost
/// dominates small dampers), else a static OpenMP loop. f must not throw.
template <class F>
void for_range(int threads, std::size_t n, F&& f) {
    if (threads <= 1) {
        for (std::size_t i = 0; i < n; ++i) f(i);
        return;
    }
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t>(n); ++s) {
        f(static_cast<std::size_t>(s));
    }
}

/// Lowest offending particle id, safe to call from several threads.
void flag_min(std::atomic<int>& flag, int id) {
    int cur = flag.load(std::memory_order_relaxed);
    while (id < cur && !flag.compare_exchange_weak(cur, id, std::memory_order_relaxed)) {
    }
}

/// Threads worth using for a loop of n items.
int threads_for(int nt, std::size_t n, std::size_t grain) {
    return std::max(1, std::min(nt, static_cast<int>(n / grain)));
}

}  // namespace

SimulationError::SimulationError(Kind k, std::int64_t s, double t, int id, const std::string& what)
    : std::runtime_error(what), kind(k), step(s), time_s(t), particle_id(id) {}

Solver::Solver(const SolverOptions& options, const ParticleSet& particles,
               const EnclosureState& enclosure)
    : options_(options), enclosure_(options.enclosure), enclosure_state_(enclosure) {
    Violations v = options_.validate();
    law_ = make_contact_law(options_.contact, v);
    const std::size_t n = particles.positions_m.size();
    if (n != static_cast<std::size_t>(options_.particles.count) || particles.radii_m.size() != n) {
        v.push_back(
            {"particles.count", std::to_string(options_.particles.count),
             "must equal the number of positions and radii given (" + std::to_string(n) + ")",
             "number of particles"});
    }
    if (!v.empty()) throw std::invalid_argument(join(v));

    // Pair coefficients: [0] particle-particle, [1] particle-wall.
    const auto& c = options_.contact;
    const Material& pm = options_.particles.material;
    const Material& wm = c.wall_material;
    auto e_star = [](const Material& a, const Material& b) {
        return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus_pa +
                      (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus_pa);
    };
    const PairProperties* props[2] = {&c.particle_particle, &c.particle_wall};
    const Material* other[2] = {&pm, &wm};
    for (int k = 0; k < 2; ++k) {
        PairCoefficients& p = coeff_[k];
        p.mu = props[k]->sliding_friction;
        p.mu_r = props[k]->rolling_friction;
        p.kt_ratio = c.tangential_stiffness_ratio;
        p.slip_reg = c.slip_regularisation_m_s;
        p.e_star_sqrt_factor = 4.0 / 3.0 * e_star(pm, *other[k]);
        p.k_n = c.normal_stiffness;
        if (k == 1 && c.normal == NormalLaw::hooke && c.wall_normal_stiffness > 0.0) {
            p.k_n = c.wall_normal_stiffness;
        }
        p.damping = std::holds_alternative<LinearDashpot>(law_.damping)
                        ? linear_zeta_from_restitution(props[k]->restitution)
                    : std::holds_alternative<HertzDashpot>(law_.damping)
                        ? hertz_alpha_from_restitution(props[k]->restitution)
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
    // Hertz radii of curvature against the curved walls (elliptical contacts, computed once
    // per distinct radius): rods are convex, the cylinder side concave, the rest flat.
    hertz_r_side_ = state_.radius;
    hertz_r_rod_ = state_.radius;
    if (std::holds_alternative<Hertz>(law_.normal)) {
        const auto& eo = options_.enclosure;
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
    v_old_.resize(n);
    w_old_.resize(n);
    pw_f_.resize(n);
    pw_m_.resize(n);
    begin_.assign(n + 1, 0);
    prev_begin_.assign(n + 1, 0);
    count_.assign(n, 0);

    // Uniform grid in the enclosure frame, cell >= largest diameter.
    double dmax = 0.0;
    for (double r : state_.radius) dmax = std::max(dmax, 2.0 * r);
    skin_ = options_.neighbor_skin_fraction * dmax;
    const double pad = dmax;
    grid_lo_ = enclosure_.lower() - Eigen::Vector3d::Constant(pad);
    const Eigen::Vector3d ext =
        enclosure_.upper() - enclosure_.lower() + Eigen::Vector3d::Constant(2.0 * pad);
    cell_ = dmax + skin_;
    for (int a = 0; a < 3; ++a) {
        dims_[a] = std::max(1, static_cast<int>(std::floor(ext[a] / cell_)));
    }
    cell_ = std::max(cell_, 0.0);
    cell_of_.resize(n);
    cell_start_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    cell_items_.resize(n);

    // Locking.
    std::vector<int> ids = options_.lock.particle_ids;
    if (ids.empty() && options_.lock.fraction > 0.0) {
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

int Solver::thread_count() const {
    return options_.threads > 0 ? options_.threads : omp_get_max_threads();
}

void Solver::set_enclosure_state(const EnclosureState& state) { enclosure_state_ = state; }

void Solver::lock(const std::vector<int>& ids) {
    for (int id : ids) {
        const auto i = static_cast<std::size_t>(id);
        state_.locked[i] = 1;
        lock_local_[i] = enclosure_state_.to_local(state_.x[i]);
    }
}

void Solver::release() { std::fill(state_.locked.begin(), state_.locked.end(), 0); }

int Solver::locked_count() const {
    return static_cast<int>(std::count(state_.locked.begin(), state_.locked.end(), 1));
}

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
        const Eigen::Vector3d imp = m * (v - state_.v[i]);
        const Eigen::Vector3d ang = inertia * (w - state_.w[i]);
        lock_force_ -= imp / dt;
        lock_moment_ -= (x - e.position_m).cross(imp / dt) + ang / dt;
        // the enclosure does the work of the snap
        ledger_.wall_work += 0.5 * m * (v.squaredNorm() - state_.v[i].squaredNorm()) +
                             0.5 * inertia * (w.squaredNorm() - state_.w[i].squaredNorm()) -
                             m * g.dot(x - state_.x[i]);
        state_.x[i] = x;
        state_.v[i] = v;
        state_.w[i] = w;
    }
}

void Solver::build_neighbors() {
    // Uniform grid in the enclosure frame (cell >= largest diameter + skin), counting sort,
    // then per particle the candidates j > i within r_i + r_j + skin, sorted by j.
    const std::size_t n = state_.size();
    const auto ncell = cell_start_.size() - 1;
    const int nt = thread_count();
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
    const int used = threads_for(nt, n, grain());
    nbr_buffers_.resize(static_cast<std::size_t>(used));
    auto scan = [&](int t) {
        auto& buf = nbr_buffers_[static_cast<std::size_t>(t)];
        buf.clear();
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
                        if ((xi - local_x_[j]).squaredNorm() < rs * rs) buf.push_back(j);
                    }
                }
            }
            std::sort(buf.begin() + static_cast<std::ptrdiff_t>(first), buf.end());
            count_[i] = static_cast<std::uint32_t>(buf.size() - first);
        }
    };
    if (used == 1) {
        scan(0);
    } else {
#pragma omp parallel num_threads(used)
        scan(omp_get_thread_num());
    }
    nbr_begin_.resize(n + 1);
    nbr_begin_[0] = 0;
    for (std::size_t i = 0; i < n; ++i) nbr_begin_[i + 1] = nbr_begin_[i] + count_[i];
    nbr_list_.clear();
    for (const auto& buf : nbr_buffers_) nbr_list_.insert(nbr_list_.end(), buf.begin(), buf.end());
    x_at_build_ = local_x_;
    ++neighbor_builds_;
}

void Solver::build_contacts() {
    const std::size_t n = state_.size();
    const auto& es = enclosure_state_;
    const int nt = thread_count();
    std::atomic<int> outside{kNoParticle};

    // Local positions (the pair distances do not change under the rigid frame motion, so the
    // skin is measured in the enclosure frame), guard, largest displacement since the build.
    double max_disp2 = 0.0;
    const bool have_list = !x_at_build_.empty();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d xl = es.to_local(state_.x[i]);
        local_x_[i] = xl;
        if (!enclosure_.contains(xl)) flag_min(outside, static_cast<int>(i));
        if (have_list) max_disp2 = std::max(max_disp2, (xl - x_at_build_[i]).squaredNorm());
    }
    if (const int bad_outside = outside.load(); bad_outside != kNoParticle) {
        std::ostringstream msg;
        msg << kind_name(SimulationError::Kind::outside) << ": particle " << bad_outside
            << " at step " << step_ << ", t = " << time_ << " s";
        throw SimulationError(SimulationError::Kind::outside, step_, time_, bad_outside, msg.str());
    }
    if (!have_list || 4.0 * max_disp2 >= skin_ * skin_) build_neighbors();

    std::swap(contacts_, prev_contacts_);
    std::swap(begin_, prev_begin_);
    const int used = threads_for(nt, n, grain());
    thread_buffers_.resize(static_cast<std::size_t>(used));
    const auto nn = static_cast<std::uint32_t>(n);

    auto scan = [&](int t) {
        auto& buf = thread_buffers_[static_cast<std::size_t>(t)];
        buf.clear();
        const std::size_t lo = n * static_cast<std::size_t>(t) / static_cast<std::size_t>(used);
        const std::size_t hi = n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(used);
        for (std::size_t i = lo; i < hi; ++i) {
            const std::size_t first = buf.size();
            const Eigen::Vector3d& xi = state_.x[i];
            const double ri = state_.radius[i];
            for (std::uint32_t q = nbr_begin_[i]; q < nbr_begin_[i + 1]; ++q) {
                const std::uint32_t j = nbr_list_[q];
                const Eigen::Vector3d d = xi - state_.x[j];
                const double rs = ri + state_.radius[j];
                const double d2 = d.squaredNorm();
                if (d2 >= rs * rs) continue;
                const double dist = std::sqrt(d2);
                Contact ct;
                ct.i = static_cast<std::uint32_t>(i);
                ct.j = j;
                ct.delta = rs - dist;
                ct.n = dist > 0.0 ? Eigen::Vector3d(d / dist) : Eigen::Vector3d(0.0, 0.0, 1.0);
                buf.push_back(ct);
            }
            enclosure_.for_each_contact(
                local_x_[i], ri, [&](std::uint32_t wall, const Eigen::Vector3d& nl, double dl) {
                    Contact ct;
                    ct.i = static_cast<std::uint32_t>(i);
                    ct.j = nn + wall;
                    ct.delta = dl;
                    ct.n = es.rotate(nl);
                    buf.push_back(ct);
                });
            count_[i] = static_cast<std::uint32_t>(buf.size() - first);
        }
    };
    if (used == 1) {
        scan(0);
    } else {
#pragma omp parallel num_threads(used)
        scan(omp_get_thread_num());
    }
    // Concatenate in thread order = particle order.
    begin_[0] = 0;
    for (std::size_t i = 0; i < n; ++i) begin_[i + 1] = begin_[i] + count_[i];
    contacts_.resize(begin_[n]);
    {
        std::size_t pos = 0;
        for (auto& buf : thread_buffers_) {
            std::copy(buf.begin(), buf.end(), contacts_.begin() + static_cast<std::ptrdiff_t>(pos));
            pos += buf.size();
        }
    }
    // Carry the tangential history over from the previous step.
    if (has_history_ && !prev_contacts_.empty()) {
        const std::size_t pn = prev_begin_.size() - 1;
        for_range(threads_for(nt, n, 2 * grain()), std::min(n, pn), [&](std::size_t i) {
            // both segments are sorted by j: merge walk
            std::uint32_t q = prev_begin_[i];
            const std::uint32_t qe = prev_begin_[i + 1];
            for (std::uint32_t k = begin_[i]; k < begin_[i + 1] && q < qe; ++k) {
                while (q < qe && prev_contacts_[q].j < contacts_[k].j) ++q;
                if (q < qe && prev_contacts_[q].j == contacts_[k].j) {
                    contacts_[k].hist = prev_contacts_[q].hist;
                }
            }
        });
    }
    // Reverse index: contacts where the particle is j (pairs only), in contact order.
    rev_begin_.assign(n + 1, 0);
    for (const auto& ct : contacts_) {
        if (ct.j < nn) ++rev_begin_[ct.j + 1];
    }
    for (std::size_t i = 0; i < n; ++i) rev_begin_[i + 1] += rev_begin_[i];
    rev_list_.resize(rev_begin_[n]);
    cursor_.assign(rev_begin_.begin(), rev_begin_.end() - 1);
    for (std::size_t k = 0; k < contacts_.size(); ++k) {
        const auto j = contacts_[k].j;
        if (j < nn) rev_list_[cursor_[j]++] = static_cast<std::uint32_t>(k);
    }
}

template <class N, class D, class T, class R>
void Solver::compute_forces(const N& normal, const D& damping, const T& tangential,
                            const R& rolling, double dt) {
    const std::size_t nc = contacts_.size();
    results_.resize(nc);
    const auto nn = static_cast<std::uint32_t>(state_.size());
    const auto& es = enclosure_state_;
    const double frac = options_.max_overlap_fraction;
    const int nt = thread_count();
    std::atomic<int> overlap{kNoParticle};

    for_range(threads_for(nt, nc, grain()), nc, [&](std::size_t s) {
        Contact& ct = contacts_[s];
        ContactResult& res = results_[s];
        const std::size_t i = ct.i;
        const bool wall = ct.j >= nn;
        const PairCoefficients& p = coeff_[wall ? 1 : 0];
        const double ri = state_.radius[i];
        ContactKinematics k;
        k.delta = ct.delta;
        k.n = ct.n;
        k.dt = dt;
        const Eigen::Vector3d bi = -(ri - 0.5 * ct.delta) * ct.n;  // branch vector of i
        Eigen::Vector3d vrel, bj = Eigen::Vector3d::Zero();
        const Eigen::Vector3d xc = state_.x[i] + bi;
        if (!wall) {
            const std::size_t j = ct.j;
            const double rj = state_.radius[j];
            bj = (rj - 0.5 * ct.delta) * ct.n;
            vrel = state_.v[i] + state_.w[i].cross(bi) - state_.v[j] - state_.w[j].cross(bj);
            const double imi = state_.inv_mass[i], imj = state_.inv_mass[j];
            k.m_eff = 1.0 / (imi + imj);
            k.r_eff = ri * rj / (ri + rj);
            k.r_hertz = k.r_eff;
            k.m_t = 1.0 / (3.5 * (imi + imj));
            k.i_eff = 1.0 / (state_.inv_inertia[i] + state_.inv_inertia[j]);
            k.omega_rel = state_.w[i] - state_.w[j];
            if (ct.delta > frac * std::min(ri, rj)) flag_min(overlap, static_cast<int>(i));
        } else {
            vrel = state_.v[i] + state_.w[i].cross(bi) - es.velocity_at(xc);
            k.m_eff = 1.0 / state_.inv_mass[i];
            k.r_eff = ri;
            const std::uint32_t wall_id = ct.j - nn;
            k.r_hertz = wall_id >= kRodBase ? hertz_r_rod_[i]
                        : wall_id == 0      ? hertz_r_side_[i]  // cylinder side (box: = ri)
                                            : ri;
            k.m_t = 1.0 / (3.5 * state_.inv_mass[i]);
            k.i_eff = 1.0 / state_.inv_inertia[i];
            k.omega_rel = state_.w[i] - es.angular_velocity_rad_s;
            if (ct.delta > frac * ri) flag_min(overlap, static_cast<int>(i));
        }
        const double vn = vrel.dot(ct.n);
        k.delta_dot = -vn;
        k.v_t = vrel - vn * ct.n;
        const NormalResult nr = normal.evaluate(k, p);
        const double fd = damping.evaluate(k, p, nr);
        const double fn = std::max(0.0, nr.f_spring + fd);  // no tensile force
        const Eigen::Vector3d ft = tangential.evaluate(k, p, fn, nr, ct.hist);
        const Eigen::Vector3d mr = rolling.evaluate(k, p, fn);
        res.f = fn * ct.n + ft;
        res.ti = bi.cross(ft) + mr;
        res.tj = wall ? Eigen::Vector3d((xc - es.position_m).cross(-res.f) - mr)
                      : Eigen::Vector3d(bj.cross(-ft) - mr);
        res.xc = xc;
        res.fs = nr.f_spring;
        res.fd = fn - nr.f_spring;
        res.kl = nr.k_law;
    });
    if (const int bad_overlap = overlap.load(); bad_overlap != kNoParticle) {
        std::ostringstream msg;
        msg << kind_name(SimulationError::Kind::overlap) << " (" << frac
            << " of the radius): particle " << bad_overlap << " at step " << step_
            << ", t = " << time_ << " s";
        throw SimulationError(SimulationError::Kind::overlap, step_, time_, bad_overlap, msg.str());
    }
}

void Solver::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt)) {
        throw std::invalid_argument("Solver::step: dt must be > 0, got " + format_value(dt));
    }
    const bool any_locked = std::any_of(state_.locked.begin(), state_.locked.end(),
                                        [](std::uint8_t l) { return l != 0; });
    if (any_locked && time_ >= options_.lock.release_time_s && options_.lock.release_time_s > 0) {
        release();
    }
    if (any_locked) {
        snap_locked(dt);
    } else {
        lock_force_.setZero();
        lock_moment_.setZero();
    }
    build_contacts();
    std::visit([&](const auto& nm, const auto& dm, const auto& tg,
                   const auto& rl) { compute_forces(nm, dm, tg, rl, dt); },
               law_.normal, law_.damping, law_.tangential, law_.rolling);

    // Gather per particle in a fixed order and integrate (semi-implicit Euler).
    const std::size_t n = state_.size();
    const auto nn = static_cast<std::uint32_t>(n);
    const Eigen::Vector3d g = options_.gravity_m_s2;
    const int nt = thread_count();
    const bool track = options_.track_energy;
    std::atomic<int> not_finite{kNoParticle};
    for_range(threads_for(nt, n, 2 * grain()), n, [&](std::size_t i) {
        Eigen::Vector3d f = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
        Eigen::Vector3d wf = Eigen::Vector3d::Zero(), wm = Eigen::Vector3d::Zero();
        for (std::uint32_t k = begin_[i]; k < begin_[i + 1]; ++k) {
            const ContactResult& r = results_[k];
            f += r.f;
            t += r.ti;
            if (contacts_[k].j >= nn) {
                wf -= r.f;
                wm += r.tj;
            }
        }
        for (std::uint32_t q = rev_begin_[i]; q < rev_begin_[i + 1]; ++q) {
            const ContactResult& r = results_[rev_list_[q]];
            f -= r.f;
            t += r.tj;
        }
        pw_f_[i] = wf;
        pw_m_[i] = wm;
        if (track) {
            v_old_[i] = state_.v[i];
            w_old_[i] = state_.w[i];
        }
        const double im = state_.inv_mass[i];
        state_.v[i] += dt * (im * f + g);
        state_.w[i] += (dt * state_.inv_inertia[i]) * t;
        state_.x[i] += dt * state_.v[i];
        // one NaN or infinity anywhere makes the sum non-finite (cheaper than allFinite x3)
        if (!std::isfinite(state_.x[i].sum() + state_.v[i].sum() + state_.w[i].sum())) {
            flag_min(not_finite, static_cast<int>(i));
        }
    });
    if (const int bad = not_finite.load(); bad != kNoParticle) {
        std::ostringstream msg;
        msg << kind_name(SimulationError::Kind::not_finite) << ": particle " << bad << " at step "
            << step_ << ", t = " << time_ << " s";
        throw SimulationError(SimulationError::Kind::not_finite, step_, time_, bad, msg.str());
    }
    wall_force_ = lock_force_;
    wall_moment_ = lock_moment_;
    for (std::size_t i = 0; i < n; ++i) {
        wall_force_ += pw_f_[i];
        wall_moment_ += pw_m_[i];
    }

    if (options_.track_energy) {
        const std::size_t nc = contacts_.size();
        e_buf_.resize(4 * nc);
        const auto& es = enclosure_state_;
        for_range(threads_for(nt, nc, grain()), nc, [&](std::size_t k) {
            const Contact& ct = contacts_[k];
            const ContactResult& r = results_[k];
            const std::size_t i = ct.i;
            const bool wall = ct.j >= nn;
            const Eigen::Vector3d vi = 0.5 * (v_old_[i] + state_.v[i]);
            const Eigen::Vector3d wi = 0.5 * (w_old_[i] + state_.w[i]);
            const Eigen::Vector3d bi = r.xc - (state_.x[i] - dt * state_.v[i]);
            Eigen::Vector3d vrel, wrel;
            double wall_work = 0.0;
            const double fn = r.fs + r.fd;
            const Eigen::Vector3d ft = r.f - fn * ct.n;
            const Eigen::Vector3d mr = r.ti - bi.cross(ft);
            if (!wall) {
                const std::size_t j = ct.j;
                const Eigen::Vector3d vj = 0.5 * (v_old_[j] + state_.v[j]);
                const Eigen::Vector3d wj = 0.5 * (w_old_[j] + state_.w[j]);
                const Eigen::Vector3d bj = (state_.radius[j] - 0.5 * ct.delta) * ct.n;
                vrel = vi + wi.cross(bi) - vj - wj.cross(bj);
                wrel = wi - wj;
            } else {
                const Eigen::Vector3d vw = es.velocity_at(r.xc);
                vrel = vi + wi.cross(bi) - vw;
                wrel = wi - es.angular_velocity_rad_s;
                wall_work = (r.f.dot(vw) + mr.dot(es.angular_velocity_rad_s)) * dt;
            }
            const double vn = vrel.dot(ct.n);
            e_buf_[4 * k + 0] = wall_work;
            e_buf_[4 * k + 1] = r.fd * (-vn) * dt;
            e_buf_[4 * k + 2] = -ft.dot(vrel - vn * ct.n) * dt;
            e_buf_[4 * k + 3] = -mr.dot(wrel) * dt;
        });
        const int layers = options_.energy_layers;
        const double lz = enclosure_.lower().z();
        const double hz = enclosure_.upper().z() - lz;
        for (std::size_t k = 0; k < nc; ++k) {
            ledger_.wall_work += e_buf_[4 * k + 0];
            ledger_.normal_damping += e_buf_[4 * k + 1];
            ledger_.friction += e_buf_[4 * k + 2];
            ledger_.rolling += e_buf_[4 * k + 3];
            if (layers > 0) {
                const double z = es.to_local(results_[k].xc).z();
                const int l = std::clamp(static_cast<int>((z - lz) / hz * layers), 0, layers - 1);
                ledger_.layer_dissipation[static_cast<std::size_t>(l)] +=
                    e_buf_[4 * k + 1] + e_buf_[4 * k + 2] + e_buf_[4 * k + 3];
            }
        }
    }
    time_ += dt;
    ++step_;
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
    const bool hertz = std::holds_alternative<Hertz>(law_.normal);
    for (std::size_t k = 0; k < contacts_.size() && k < results_.size(); ++k) {
        const double d = contacts_[k].delta, kl = results_[k].kl;
        e.elastic += hertz ? Hertz::energy(kl, d) : Hooke::energy(kl, d);
    }
    return e;
}

void Solver::reset_energy() {
    ledger_ = EnergyLedger{};
    ledger_.layer_dissipation.assign(static_cast<std::size_t>(options_.energy_layers), 0.0);
    ledger_.initial_total = energy().mechanical();
}

ParticleSet Solver::local_snapshot() const {
    ParticleSet s;
    const auto& e = enclosure_state_;
    for (std::size_t i = 0; i < state_.size(); ++i) {
        s.positions_m.push_back(e.to_local(state_.x[i]));
        s.radii_m.push_back(state_.radius[i]);
        s.velocities_m_s.push_back(e.rotation.transpose() *
                                   (state_.v[i] - e.velocity_at(state_.x[i])));
        s.angular_velocities_rad_s.push_back(e.rotation.transpose() * state_.w[i]);
    }
    return s;
}

}  // namespace sb::dem

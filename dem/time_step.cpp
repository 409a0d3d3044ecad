// Automatic DEM time step: single impacts at the steps of a ladder against the converged step.
#include "dem/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "dem/solver.hpp"

namespace sb::dem {

double head_on_restitution(const SolverOptions& base, double d, bool wall, double v, double dt,
                           double phase) {
    SolverOptions o = base;
    const double r = 0.5 * d;
    o.particles.count = wall ? 1 : 2;
    o.particles.diameter_m = d;
    o.particles.size_distribution.clear();
    o.particles.diameter_scatter = 0.0;
    o.enclosure = EnclosureOptions{};
    o.enclosure.shape = EnclosureShape::box;
    o.enclosure.length_x_m = o.enclosure.length_y_m = o.enclosure.height_m = 10.0 * d;
    o.lock = LockOptions{};
    o.gravity_m_s2 = Eigen::Vector3d::Zero();
    o.max_overlap_fraction = 1.0;  // the bed's guard, not this impact's
    o.threads = 1;
    o.track_energy = false;
    o.energy_layers = 0;
    const double gap = phase * v * dt;
    const double mid = 5.0 * d;
    ParticleSet p;
    if (wall) {
        p.positions_m = {{0.0, 0.0, r + gap}};
        p.velocities_m_s = {{0.0, 0.0, -v}};
    } else {
        p.positions_m = {{0.0, 0.0, mid - r - 0.5 * gap}, {0.0, 0.0, mid + r + 0.5 * gap}};
        p.velocities_m_s = {{0.0, 0.0, 0.5 * v}, {0.0, 0.0, -0.5 * v}};
    }
    p.radii_m.assign(p.positions_m.size(), r);
    p.angular_velocities_rad_s.assign(p.positions_m.size(), Eigen::Vector3d::Zero());
    Solver s(o, p);
    // A contact that never ends (a dashpot too strong to let go) is cut after many contact
    // times; its restitution is then that of the speed it has left.
    const double travel_steps = (2.0 * d) / (v * dt);
    const long max_steps = static_cast<long>(std::min(1e7, 200.0 * travel_steps + 1e4));
    bool touched = false;
    for (long k = 0; k < max_steps; ++k) {
        s.step(dt);
        if (s.contact_count() > 0) {
            touched = true;
        } else if (touched) {
            break;
        }
    }
    const auto& u = s.particles().v;
    return wall ? u[0].z() / v : (u[1].z() - u[0].z()) / v;
}

namespace {

constexpr int kPhases = 8;

/// Two of the smallest spheres (pair) or one (wall): their contacts are the shortest, and the
/// contact time the step is a fraction of is theirs (choose_contact).
double impact_restitution(const SolverOptions& base, bool wall, double v, double dt, double phase) {
    return head_on_restitution(base, base.particles.smallest_diameter_m(), wall, v, dt, phase);
}

struct PhaseStats {
    double mean = 0.0;
    double worst = 0.0;  ///< largest deviation from `reference` [-] (0 without one)
    double mean_deviation = 0.0;
};

PhaseStats over_phases(const SolverOptions& o, bool wall, double v, double dt, double reference) {
    PhaseStats st;
    const double scale = std::max(std::abs(reference), 0.1);  // e near 0: absolute
    for (int k = 0; k < kPhases; ++k) {
        const double e = impact_restitution(o, wall, v, dt, (k + 0.5) / kPhases);
        st.mean += e / kPhases;
        st.worst = std::max(st.worst, std::abs(e - reference) / scale);
    }
    st.mean_deviation = std::abs(st.mean - reference) / scale;
    return st;
}

}  // namespace

std::string TimeStepFraction::describe() const {
    char text[256];
    std::snprintf(text, sizeof text,
                  "time step 1/%.0f of the pair contact time (restitution within %.2f %% "
                  "(pair) and %.2f %% (wall) of the converged %.4g and %.4g on average over "
                  "the start phases, %.2f %% at worst%s)",
                  1.0 / fraction, 100.0 * pair_mean_deviation, 100.0 * wall_mean_deviation,
                  pair_restitution, wall_restitution, 100.0 * worst_deviation,
                  met ? "" : "; the tolerances are not met at the finest step tried");
    return text;
}

TimeStepFraction automatic_time_step_fraction(const SolverOptions& options,
                                              double pair_contact_time_s, double impact_speed_m_s) {
    if (!(pair_contact_time_s > 0.0) || !std::isfinite(pair_contact_time_s) ||
        !(impact_speed_m_s > 0.0) || !std::isfinite(impact_speed_m_s)) {
        throw std::invalid_argument(
            "automatic_time_step_fraction: the contact time and the impact speed must be "
            "positive and finite");
    }
    const double tc = pair_contact_time_s, v = impact_speed_m_s;
    TimeStepFraction out;
    out.pair_restitution =
        over_phases(options, false, v, kConvergedTimeStepFraction * tc, 0.0).mean;
    out.wall_restitution = over_phases(options, true, v, kConvergedTimeStepFraction * tc, 0.0).mean;
    for (const double fraction : kTimeStepLadder) {
        const PhaseStats pair = over_phases(options, false, v, fraction * tc, out.pair_restitution);
        const PhaseStats wall = over_phases(options, true, v, fraction * tc, out.wall_restitution);
        out.fraction = fraction;
        out.pair_mean_deviation = pair.mean_deviation;
        out.wall_mean_deviation = wall.mean_deviation;
        out.worst_deviation = std::max(pair.worst, wall.worst);
        out.met = pair.mean_deviation <= kRestitutionMeanTolerance &&
                  wall.mean_deviation <= kRestitutionMeanTolerance &&
                  out.worst_deviation <= kRestitutionWorstTolerance;
        if (out.met) break;
    }
    return out;
}

ExcitationContact with_automatic_time_step(ExcitationContact chosen, SolverOptions options) {
    options.contact.normal_stiffness = chosen.stiffness;
    const TimeStepFraction step =
        automatic_time_step_fraction(options, chosen.pair_contact_time_s, chosen.impact_speed_m_s);
    chosen.time_step_s = step.fraction * chosen.pair_contact_time_s;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.9g", chosen.time_step_s);
    chosen.log = chosen.stiffness_log + ", automatic " + step.describe() + ": " + seconds + " s";
    return chosen;
}

}  // namespace sb::dem

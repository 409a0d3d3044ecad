// Characterising a particle damper alone under a prescribed harmonic motion.
#include "bench/characterization.hpp"

#include <omp.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "bench/arrangement.hpp"
#include "bench/attachment.hpp"
#include "bench/resolved_config.hpp"
#include "config/errors.hpp"
#include "core/units.hpp"
#include "dem/setup.hpp"

namespace sb::bench {
namespace {

std::string number_text(double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

/// Rotation matrix of a rotation vector (exact exponential map, as the coupled specimen).
Eigen::Matrix3d rotation_of(const Eigen::Vector3d& theta) {
    const double angle = theta.norm();
    if (angle < 1e-300) return Eigen::Matrix3d::Identity();
    return Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
}

/// Kinetic energy of the particles relative to the enclosure's rigid motion [J]: the bed's
/// agitation, without the 1/2 m v_enclosure^2 every particle riding along would carry.
double relative_kinetic_energy(const dem::Solver& solver) {
    const dem::ParticleState& p = solver.particles();
    const dem::EnclosureState& e = solver.enclosure_state();
    double energy = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Eigen::Vector3d wall =
            e.velocity_m_s + e.angular_velocity_rad_s.cross(p.x[i] - e.position_m);
        const Eigen::Vector3d spin = p.w[i] - e.angular_velocity_rad_s;
        energy += 0.5 * (p.v[i] - wall).squaredNorm() / p.inv_mass[i] +
                  0.5 * spin.squaredNorm() / p.inv_inertia[i];
    }
    return energy;
}

/// One period's measurements.
struct Period {
    std::complex<double> q1, q2, q3;  ///< harmonics of the generalised force [N]
    double wall_work_j = 0.0;
    double kinetic_j = 0.0;  ///< mean over the period's samples
};

/// The settled bed of a damper in its mounting: the campaign's procedure (sweep_runner.cpp),
/// so that a seed and a level give the campaign's bed.
dem::ParticleSet settled_bed(const DamperSpec& damper, double stiffness,
                             const Eigen::Matrix3d& rotation, const Eigen::Vector3d& gravity,
                             std::uint64_t seed) {
    dem::SolverOptions local = damper.solver_options(stiffness);
    local.gravity_m_s2 = rotation.transpose() * gravity;
    local.track_energy = false;
    if (damper.fill == DamperSpec::Fill::pour) return dem::pour(local, seed, damper.settle);
    dem::ParticleSet filled;
    try {
        filled = dem::fill_random(local, seed);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error("damper " + damper.name + ": " + e.what() + " (set dampers." +
                                 damper.name + ".settle.fill = \"pour\")");
    }
    return dem::settle(local, filled, damper.settle);
}

double mean_of(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

/// Sample standard deviation (n - 1); 0 for a single value.
double deviation_of(const std::vector<double>& v) {
    if (v.size() < 2) return 0.0;
    const double m = mean_of(v);
    double s = 0.0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
}

config::ConfigError problem(const CampaignConfig& config, std::string key, std::string value,
                            std::string constraint, std::string meaning) {
    return {config.source,     0, 0, std::move(key), std::move(value), std::move(constraint),
            std::move(meaning)};
}

}  // namespace

Violations SteadyStateOptions::validate() const {
    Violations out;
    if (transient_periods < 0) {
        out.push_back({"transient_periods", format_value(transient_periods), "must be >= 0",
                       "periods left out at the start"});
    }
    if (window_periods < 1) {
        out.push_back(
            {"window_periods", format_value(window_periods), "must be >= 1", "periods per window"});
    }
    if (!(tolerance > 0.0)) {
        out.push_back({"tolerance", format_value(tolerance), "must be > 0",
                       "window means agree within tolerance m |a1|"});
    }
    if (max_periods < transient_periods + 2 * window_periods) {
        out.push_back({"max_periods", format_value(max_periods),
                       "must be >= transient_periods + 2 window_periods = " +
                           std::to_string(transient_periods + 2 * window_periods),
                       "budget of periods per point"});
    }
    return out;
}

std::string SteadyStateOptions::describe() const {
    std::ostringstream out;
    out << "after " << transient_periods << " periods, the means of the last two windows of "
        << window_periods << " periods agree within " << tolerance << " m |a1|; at most "
        << max_periods << " periods";
    return out.str();
}

ApparentMassPoint measure_apparent_mass(const EnclosureSetup& setup, const HarmonicDrive& drive,
                                        const SteadyStateOptions& steady) {
    if (const auto v = steady.validate(); !v.empty()) {
        throw std::invalid_argument("steady-state criterion: " + v.front().key + " " +
                                    v.front().constraint);
    }
    if (!(drive.frequency_hz > 0.0) || !(drive.acceleration_m_s2 > 0.0) ||
        !(drive.direction.norm() > 0.0) || !(setup.dt_max_s > 0.0)) {
        throw std::invalid_argument(
            "harmonic drive: frequency, acceleration, direction and time step must be > 0");
    }
    const Eigen::Vector3d d = drive.direction.normalized();
    const Eigen::Vector3d& psi = drive.rotation_per_translation_rad_m;
    const double w = hz_to_rad_s(drive.frequency_hz);
    const double amplitude = drive.acceleration_m_s2;
    const double x_peak = amplitude / (w * w);
    const double period_s = 1.0 / drive.frequency_hz;
    // Whole steps per period, as the coupled specimen splits them: per-period harmonics are
    // then exact DFT bins, and the drive is continuous from one period to the next.
    const int n = std::max(1, static_cast<int>(std::ceil(period_s / setup.dt_max_s - 1e-9)));
    const double dt = period_s / n;

    dem::SolverOptions options = setup.options;
    options.track_energy = true;  // the wall work per period is the dissipated power
    DemDamper damper(options, setup.mount_rotation, setup.offset_m, setup.bed,
                     Eigen::Vector3d::Zero());
    {
        // The bed starts riding with its enclosure at the drive's initial velocity (the
        // campaign's start carries it the same way), not hit by walls that jump to it.
        PointMotion start;
        start.velocity_m_s = -x_peak * w * d;
        start.angular_velocity_rad_s = -x_peak * w * psi;
        damper.restore_at(damper.state_at(PointMotion{}), start);
    }
    ApparentMassPoint out;
    out.steps_per_period = n;
    for (double inv : damper.solver().particles().inv_mass) out.bed_mass_kg += 1.0 / inv;

    std::vector<std::complex<double>> e1(static_cast<std::size_t>(n));
    std::vector<std::complex<double>> e2(e1.size());
    std::vector<std::complex<double>> e3(e1.size());
    for (int k = 0; k < n; ++k) {
        const auto i = static_cast<std::size_t>(k);
        e1[i] = std::polar(1.0, -w * dt * k);
        e2[i] = std::polar(1.0, -2.0 * w * dt * k);
        e3[i] = std::polar(1.0, -3.0 * w * dt * k);
    }
    // The bed's agitation, sampled about 64 times per period (one O(N) pass each).
    const int stride = std::max(1, n / 64);
    // A rigid bed of the same mass exerts m |a1|: the scale of the tolerance.
    const double scale = out.bed_mass_kg * amplitude;

    std::vector<Period> periods;
    const int w_periods = steady.window_periods;
    int window_end = 0;
    for (int p = 0; p < steady.max_periods; ++p) {
        const double work_begin = damper.solver().energy().wall_work;
        Period period;
        double kinetic = 0.0;
        int samples = 0;
        for (int k = 0; k < n; ++k) {
            const auto i = static_cast<std::size_t>(k);
            // a = A sin(w t), so u = -A/w^2 sin(w t) and v = -A/w cos(w t): zero-mean motion.
            const double phase = w * dt * k;
            const double u = -x_peak * std::sin(phase);
            const double v = -x_peak * w * std::cos(phase);
            PointMotion motion;
            motion.position_m = u * d;
            motion.rotation = rotation_of(u * psi);
            motion.velocity_m_s = v * d;
            motion.angular_velocity_rad_s = v * psi;
            const PointLoad load = damper.step(motion, dt);
            const double q = load.force_n.dot(d) + load.moment_nm.dot(psi);
            period.q1 += q * e1[i];
            period.q2 += q * e2[i];
            period.q3 += q * e3[i];
            if (k % stride == 0) {
                kinetic += relative_kinetic_energy(damper.solver());
                ++samples;
            }
        }
        period.q1 *= 2.0 / n;
        period.q2 *= 2.0 / n;
        period.q3 *= 2.0 / n;
        period.wall_work_j = damper.solver().energy().wall_work - work_begin;
        period.kinetic_j = kinetic / samples;
        periods.push_back(period);
        const int count = p + 1;
        window_end = count;
        if (count < steady.transient_periods + 2 * w_periods) continue;
        std::complex<double> a = 0.0;
        std::complex<double> b = 0.0;
        for (int k = count - 2 * w_periods; k < count - w_periods; ++k) {
            a += periods[static_cast<std::size_t>(k)].q1;
        }
        for (int k = count - w_periods; k < count; ++k) {
            b += periods[static_cast<std::size_t>(k)].q1;
        }
        if (std::abs(b - a) / w_periods <= steady.tolerance * scale) {
            out.settled = true;
            break;
        }
    }
    out.periods = window_end;
    const int begin = window_end - 2 * w_periods;
    const double count = 2.0 * w_periods;
    std::complex<double> q1 = 0.0;
    std::complex<double> q2 = 0.0;
    std::complex<double> q3 = 0.0;
    double work = 0.0;
    for (int k = begin; k < window_end; ++k) {
        const Period& period = periods[static_cast<std::size_t>(k)];
        q1 += period.q1 / count;
        q2 += period.q2 / count;
        q3 += period.q3 / count;
        work += period.wall_work_j / count;
        out.kinetic_j += period.kinetic_j / count;
    }
    // M = -Q1 / a1 with a1 = -i A (the fundamental of A sin(w t)).
    out.apparent_mass_kg = -q1 / std::complex<double>(0.0, -amplitude);
    out.power_w = work / period_s;
    const double first = std::abs(q1);
    out.h2_ratio = first > 0.0 ? std::abs(q2) / first : 0.0;
    out.h3_ratio = first > 0.0 ? std::abs(q3) / first : 0.0;
    return out;
}

Eigen::Vector3d rotation_per_translation(const PreparedArrangement& prepared,
                                         const std::string& point,
                                         const Eigen::Vector3d& direction) {
    const auto& basis = prepared.estimate_basis;
    for (std::size_t r = 0; r < basis.modes.size(); ++r) {
        if (basis.modes[r].frequency_hz != prepared.first_mode_hz) continue;
        const Eigen::Matrix<double, 6, 1> motion = prepared.estimate_model.point(point).op *
                                                   basis.shapes.col(static_cast<Eigen::Index>(r));
        const double translation = motion.head<3>().dot(direction.normalized());
        // A node of the mode (no translation at the point) has no rotation per translation.
        if (std::abs(translation) <= 1e-12 * motion.norm()) return Eigen::Vector3d::Zero();
        return motion.tail<3>() / translation;
    }
    return Eigen::Vector3d::Zero();
}

CharacterizeResult characterize(const CampaignConfig& config, const CharacterizeOptions& options) {
    const auto started = std::chrono::steady_clock::now();
    const CampaignSpec& campaign = config.campaign;
    const std::vector<double> levels =
        options.levels_g.empty() ? campaign.levels_g : options.levels_g;
    std::vector<const DamperSpec*> dampers;
    for (const auto& d : campaign.dampers) {
        if (d.model != DamperSpec::Model::rigid) dampers.push_back(&d);
    }
    std::vector<config::ConfigError> problems;
    if (levels.empty()) {
        problems.push_back(problem(config, "campaign.levels_g", "", "is required",
                                   "levels to characterise [g] (or --levels-g)"));
    }
    for (double l : levels) {
        if (!(l > 0.0 && std::isfinite(l))) {
            problems.push_back(problem(config, "levels_g", number_text(l), "must be > 0",
                                       "level to characterise [g]"));
        }
    }
    for (double f : options.frequencies_hz) {
        if (!(f > 0.0 && std::isfinite(f))) {
            problems.push_back(problem(config, "frequencies_hz", number_text(f), "must be > 0",
                                       "frequency to characterise [Hz]"));
        }
    }
    if (dampers.empty()) {
        problems.push_back(problem(config, "dampers", "", "needs a damper whose model is not rigid",
                                   "the dampers to characterise"));
    }
    if (options.seeds < 1) {
        problems.push_back(problem(config, "seeds", std::to_string(options.seeds), "must be >= 1",
                                   "fillings per grid point"));
    }
    for (const auto& v : options.steady.validate()) {
        problems.push_back(problem(config, v.key, v.value, v.constraint, v.meaning));
    }
    if (!problems.empty()) throw config::ConfigException(problems);

    const CampaignPlan plan = plan_campaign(config, Selection::of(config, {}, {levels.front()}));
    const Eigen::Vector3d direction = config.structure.excitation.direction.normalized();

    // One bed per arrangement, damper, level and seed (the contact stiffness follows the level,
    // as in the campaign); one run per grid point and seed.
    struct Bed {
        std::size_t arrangement = 0;
        const DamperSpec* damper = nullptr;
        double level_g = 0.0;
        std::uint64_t seed = 0;
        dem::ExcitationContact contact;
        dem::ParticleSet particles;
    };
    struct Run {
        std::size_t bed = 0;
        double frequency_hz = 0.0;
        ApparentMassPoint result;
    };
    std::vector<Bed> beds;
    std::vector<std::vector<double>> grids;  // per arrangement
    std::vector<Eigen::Vector3d> rotations;  // per arrangement and damper
    for (std::size_t a = 0; a < plan.arrangements.size(); ++a) {
        const PreparedArrangement& prepared = plan.arrangements[a];
        std::vector<double> grid = options.frequencies_hz;
        if (grid.empty()) {
            const auto [lo, hi] =
                std::minmax_element(prepared.frequencies_hz.begin(), prepared.frequencies_hz.end());
            if (options.frequency_count > 1) {
                for (int k = 0; k < options.frequency_count; ++k) {
                    grid.push_back(*lo + (*hi - *lo) * k / (options.frequency_count - 1));
                }
            } else if (options.frequency_count == 1) {
                grid.push_back(prepared.first_mode_hz);
            } else {
                grid = prepared.frequencies_hz;
            }
        }
        std::sort(grid.begin(), grid.end());
        grids.push_back(grid);
        for (const DamperSpec* damper : dampers) {
            rotations.push_back(options.rotation
                                    ? rotation_per_translation(prepared, damper->point, direction)
                                    : Eigen::Vector3d::Zero());
            for (double level : levels) {
                for (int s = 0; s < options.seeds; ++s) {
                    Bed bed;
                    bed.arrangement = a;
                    bed.damper = damper;
                    bed.level_g = level;
                    bed.seed = campaign.seed + static_cast<std::uint64_t>(s);
                    bed.contact = dem::choose_contact(
                        damper->particles, damper->enclosure, damper->contact.normal,
                        damper->contact.particle_particle.restitution,
                        damper->contact.normal_stiffness, damper->contact.max_overlap_fraction,
                        damper->contact.time_step_fraction, std::sqrt(2.0) * g_to_m_s2(level),
                        prepared.first_mode_hz);
                    beds.push_back(std::move(bed));
                }
            }
        }
    }
    std::vector<Run> runs;
    for (std::size_t b = 0; b < beds.size(); ++b) {
        for (double f : grids[beds[b].arrangement]) runs.push_back({b, f, {}});
    }

    const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
    std::mutex progress_mutex;
    int done = 0;
    const auto damper_index = [&](const DamperSpec* d) {
        return static_cast<std::size_t>(std::find(dampers.begin(), dampers.end(), d) -
                                        dampers.begin());
    };
    // Every bed and every run is independent of the others: the numbers do not depend on the
    // thread count or the order they finish in. No exception leaves a parallel region.
    std::vector<std::exception_ptr> errors(std::max(beds.size(), runs.size()));
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (std::size_t b = 0; b < beds.size(); ++b) {
        try {
            Bed& bed = beds[b];
            const auto& arrangement = plan.arrangements[bed.arrangement].arrangement;
            const DamperMounting mounting = damper_mounting(arrangement, *bed.damper);
            bed.particles = settled_bed(*bed.damper, bed.contact.stiffness, mounting.rotation,
                                        arrangement_gravity(arrangement), bed.seed);
        } catch (...) {
            errors[b] = std::current_exception();
        }
    }
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);
    }
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (std::size_t r = 0; r < runs.size(); ++r) {
        try {
            Run& run = runs[r];
            const Bed& bed = beds[run.bed];
            const PreparedArrangement& prepared = plan.arrangements[bed.arrangement];
            const DamperMounting mounting = damper_mounting(prepared.arrangement, *bed.damper);
            EnclosureSetup setup;
            setup.options = bed.damper->solver_options(bed.contact.stiffness);
            setup.options.gravity_m_s2 = arrangement_gravity(prepared.arrangement);
            if (bed.damper->locked) setup.options.lock.fraction = 1.0;
            setup.mount_rotation = mounting.rotation;
            setup.offset_m = mounting.origin_m;
            setup.bed = bed.particles;
            const auto& grid = grids[bed.arrangement];
            setup.dt_max_s = std::min(bed.contact.time_step_s, 1.0 / (256.0 * grid.front()));
            HarmonicDrive drive;
            drive.direction = direction;
            drive.rotation_per_translation_rad_m =
                rotations[bed.arrangement * dampers.size() + damper_index(bed.damper)];
            drive.acceleration_m_s2 = std::sqrt(2.0) * g_to_m_s2(bed.level_g);
            drive.frequency_hz = run.frequency_hz;
            run.result = measure_apparent_mass(setup, drive, options.steady);
            if (options.progress) {
                std::ostringstream line;
                const auto m = run.result.apparent_mass_kg;
                std::lock_guard<std::mutex> lock(progress_mutex);
                line << '[' << ++done << '/' << runs.size() << "] " << prepared.arrangement.name
                     << ' ' << bed.damper->name << ' ' << number_text(bed.level_g) << " g "
                     << number_text(run.frequency_hz) << " Hz seed " << bed.seed
                     << ": M = " << number_text(m.real()) << (m.imag() < 0 ? " - " : " + ")
                     << number_text(std::abs(m.imag()))
                     << "i kg, P = " << number_text(run.result.power_w) << " W, "
                     << run.result.periods << " periods"
                     << (run.result.settled ? "" : " (not settled)");
                options.progress(line.str());
            }
        } catch (...) {
            errors[r] = std::current_exception();
        }
    }
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);
    }

    CharacterizeResult result;
    CharacterizationTable& table = result.table;
    table.config = config.source;
    table.config_hash = config_hash(config);
    for (const DamperSpec* d : dampers)
        table.damper_hashes.emplace_back(d->name, damper_hash(config, d->name));
    table.command = options.command_line;
    table.criterion = options.steady.describe();
    for (std::size_t a = 0; a < plan.arrangements.size(); ++a) {
        const PreparedArrangement& prepared = plan.arrangements[a];
        for (const DamperSpec* damper : dampers) {
            for (double level : levels) {
                for (double f : grids[a]) {
                    std::vector<double> re, im, power, h2, h3, kinetic, periods, mass;
                    bool settled = true;
                    for (const Run& run : runs) {
                        const Bed& bed = beds[run.bed];
                        if (bed.arrangement != a || bed.damper != damper || bed.level_g != level ||
                            run.frequency_hz != f) {
                            continue;
                        }
                        const ApparentMassPoint& m = run.result;
                        re.push_back(m.apparent_mass_kg.real());
                        im.push_back(m.apparent_mass_kg.imag());
                        power.push_back(m.power_w);
                        h2.push_back(m.h2_ratio);
                        h3.push_back(m.h3_ratio);
                        kinetic.push_back(m.kinetic_j);
                        periods.push_back(m.periods);
                        mass.push_back(m.bed_mass_kg);
                        settled = settled && m.settled;
                        result.periods += m.periods;
                        result.unsettled_runs += m.settled ? 0 : 1;
                        ++result.runs;
                    }
                    CharacterizationRow row;
                    row.damper = damper->name;
                    row.arrangement = prepared.arrangement.name;
                    row.level_g = level;
                    row.acceleration_m_s2 = std::sqrt(2.0) * g_to_m_s2(level);
                    row.frequency_hz = f;
                    row.bed_mass_kg = mean_of(mass);
                    row.rotation_per_translation_rad_m =
                        rotations[a * dampers.size() + damper_index(damper)];
                    row.seeds = static_cast<int>(re.size());
                    row.apparent_mass_kg = {mean_of(re), mean_of(im)};
                    row.apparent_mass_re_std_kg = deviation_of(re);
                    row.apparent_mass_im_std_kg = deviation_of(im);
                    row.power_w = mean_of(power);
                    row.power_std_w = deviation_of(power);
                    row.h2_ratio = mean_of(h2);
                    row.h3_ratio = mean_of(h3);
                    row.kinetic_j = mean_of(kinetic);
                    row.kinetic_std_j = deviation_of(kinetic);
                    row.periods = mean_of(periods);
                    row.settled = settled;
                    table.rows.push_back(row);
                }
            }
        }
    }
    result.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

}  // namespace sb::bench

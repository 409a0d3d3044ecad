// Characterising a particle damper alone under a prescribed harmonic motion.
#include "bench/characterization.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <sstream>
#include <stdexcept>

#include "bench/arrangement.hpp"
#include "bench/attachment.hpp"
#include "bench/characterization_progress.hpp"
#include "bench/resolved_config.hpp"
#include "config/errors.hpp"
#include "core/units.hpp"
#include "dem/energy_periods.hpp"
#include "dem/setup.hpp"
#include "identification/spectrum.hpp"

namespace sb::bench {
namespace {

/// Rotation matrix of a rotation vector (exact exponential map, as the coupled specimen).
Eigen::Matrix3d rotation_of(const Eigen::Vector3d& theta) {
    const double angle = theta.norm();
    if (angle < 1e-300) return Eigen::Matrix3d::Identity();
    return Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
}

/// Kinetic energy of the particles in the laboratory frame [J].
double laboratory_kinetic_energy(const dem::ParticleState& p) {
    double energy = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        energy += 0.5 * p.v[i].squaredNorm() / p.inv_mass[i] +
                  0.5 * p.w[i].squaredNorm() / p.inv_inertia[i];
    }
    return energy;
}

/// One-sided amplitudes 2 |X_k| / N, k = 1..bins, of `x` with its mean removed.
std::vector<double> amplitude_spectrum(std::vector<double> x, std::size_t bins) {
    double mean = 0.0;
    for (double v : x) mean += v;
    mean /= static_cast<double>(x.size());
    for (double& v : x) v -= mean;
    const auto spectrum = identification::real_spectrum(x);
    std::vector<double> out;
    const double scale = 2.0 / static_cast<double>(x.size());
    for (std::size_t k = 1; k <= bins && k < spectrum.size(); ++k) {
        out.push_back(scale * std::abs(spectrum[k]));
    }
    return out;
}

/// A progress that does not fit the run it is to continue (another bed or step, more periods
/// than the budget, energy samples that do not add up) is refused, not continued.
void check_fits(const RunProgress& p, int steps_per_period, int particles, bool bed_energy,
                int max_periods) {
    const auto periods = p.periods.size();
    const auto steps = periods * static_cast<std::size_t>(steps_per_period);
    const auto& e = p.energy;
    std::string problem;
    if (p.steps_per_period != steps_per_period) {
        problem = std::to_string(p.steps_per_period) + " steps per period, the run takes " +
                  std::to_string(steps_per_period);
    } else if (!p.damper.dem ||
               p.damper.dem->positions_m.size() != static_cast<std::size_t>(particles)) {
        problem = "its bed is not the run's bed of " + std::to_string(particles) + " particles";
    } else if (periods < 1 || periods >= static_cast<std::size_t>(max_periods)) {
        problem = std::to_string(periods) + " periods done, the run's budget is " +
                  std::to_string(max_periods);
    } else if (bed_energy ? (e.kinetic_j.size() != steps || e.dissipated_j.size() != steps + 1 ||
                             e.at.size() != periods)
                          : !(e.kinetic_j.empty() && e.dissipated_j.empty() && e.at.empty())) {
        problem = bed_energy ? "its energy samples do not cover its periods"
                             : "it holds energy samples the run does not take";
    }
    if (!problem.empty())
        throw std::invalid_argument("the progress does not fit the run: " + problem);
}

}  // namespace

BedEnergy EnergySamples::over(int begin, int end, int n, double dt) const {
    BedEnergy out;
    const double duration = (end - begin) * n * dt;
    const dem::EnergyInterval interval = dem::energy_between(
        at[static_cast<std::size_t>(begin)], at[static_cast<std::size_t>(end)], duration);
    out.normal_damping_w = interval.normal_damping / duration;
    out.friction_w = interval.friction / duration;
    out.rolling_w = interval.rolling / duration;
    out.mechanical_change_w = interval.mechanical_change / duration;
    for (double layer : interval.layer_dissipation) out.layer_power_w.push_back(layer / duration);
    out.layer_kinetic_j = interval.layer_kinetic_mean;
    const auto first = static_cast<std::size_t>(begin) * static_cast<std::size_t>(n);
    const auto last = static_cast<std::size_t>(end) * static_cast<std::size_t>(n);
    std::vector<double> kinetic(kinetic_j.begin() + static_cast<std::ptrdiff_t>(first),
                                kinetic_j.begin() + static_cast<std::ptrdiff_t>(last));
    std::vector<double> power;
    for (std::size_t j = first; j < last; ++j) {
        power.push_back((dissipated_j[j + 1] - dissipated_j[j]) / dt);
    }
    for (double k : kinetic) out.kinetic_lab_j += k / static_cast<double>(kinetic.size());
    out.bin_hz = 1.0 / duration;
    const auto bins = static_cast<std::size_t>(BedEnergy::kSpectrumHarmonics * (end - begin));
    out.kinetic_amplitude_j = amplitude_spectrum(std::move(kinetic), bins);
    out.dissipation_amplitude_w = amplitude_spectrum(std::move(power), bins);
    return out;
}

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
    if (!(energy_tolerance >= 0.0) || !std::isfinite(energy_tolerance)) {
        out.push_back({"energy_tolerance", format_value(energy_tolerance),
                       "must be >= 0 and finite",
                       "the bed's stored energy changes over the windows by at most this share "
                       "of the walls' work (0: off)"});
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
    if (energy_tolerance > 0.0) {
        out << "; and the bed's stored energy changes over the windows by at most "
            << energy_tolerance << " of the walls' work";
    }
    return out.str();
}

ApparentMassPoint measure_apparent_mass(const EnclosureSetup& setup, const HarmonicDrive& drive,
                                        const SteadyStateOptions& steady,
                                        const std::function<void(int)>& after_period,
                                        const RunCheckpoints& checkpoints) {
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
    // The walls' work comes from the load on the point (below), O(1) per step; the solver's
    // per-contact ledger only to say where the energy goes.
    options.track_energy = setup.bed_energy;
    DemDamper damper(options, setup.mount_rotation, setup.offset_m, setup.bed,
                     Eigen::Vector3d::Zero());
    ApparentMassPoint out;
    out.steps_per_period = n;
    for (double inv : damper.solver().particles().inv_mass) out.bed_mass_kg += 1.0 / inv;

    std::vector<PeriodMeasurement> periods;
    EnergySamples samples_of_energy;
    // The ledger at the latest period boundary: one O(N + contacts) snapshot per period, the
    // end of one period being the start of the next.
    dem::EnergyLedger boundary;
    if (const RunProgress* resume = checkpoints.resume) {
        check_fits(*resume, n, static_cast<int>(setup.bed.positions_m.size()), setup.bed_energy,
                   steady.max_periods);
        damper.restore(resume->damper);  // at its own pose: bitwise where it was
        damper.continue_energy(resume->boundary);
        periods = resume->periods;
        samples_of_energy = resume->energy;
        boundary = resume->boundary;
    } else {
        // The bed starts riding with its enclosure at the drive's initial velocity (the
        // campaign's start carries it the same way), not hit by walls that jump to it.
        PointMotion start;
        start.velocity_m_s = -x_peak * w * d;
        start.angular_velocity_rad_s = -x_peak * w * psi;
        damper.restore_at(damper.state_at(PointMotion{}), start);
        if (setup.bed_energy)
            samples_of_energy.dissipated_j.push_back(damper.solver().dissipated_j());
        boundary = damper.solver().energy();
    }

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
    // The kinetic energy a rigid bed carries riding its enclosure, 1/2 m (A/w)^2: the scale of
    // the stored energy's change when the walls hardly work on the bed (a held bed).
    const double riding_j = 0.5 * out.bed_mass_kg * std::pow(amplitude / w, 2);
    const int w_periods = steady.window_periods;
    // Whether the run is steady after `count` periods (SteadyStateOptions).
    const auto steady_after = [&](int count) {
        if (count < steady.transient_periods + 2 * w_periods) return false;
        if (steady.energy_tolerance > 0.0) {
            const auto first = static_cast<std::size_t>(count - 2 * w_periods);
            double work = 0.0;
            for (std::size_t k = first; k < periods.size(); ++k) work += periods[k].wall_work_j;
            const double change = boundary.mechanical() - periods[first].stored_at_start_j;
            if (std::abs(change) > steady.energy_tolerance * std::max(std::abs(work), riding_j)) {
                return false;
            }
        }
        std::complex<double> a = 0.0;
        std::complex<double> b = 0.0;
        for (int k = count - 2 * w_periods; k < count - w_periods; ++k) {
            a += periods[static_cast<std::size_t>(k)].q1;
        }
        for (int k = count - w_periods; k < count; ++k) {
            b += periods[static_cast<std::size_t>(k)].q1;
        }
        return std::abs(b - a) / w_periods <= steady.tolerance * scale;
    };

    int window_end = static_cast<int>(periods.size());
    for (int p = window_end; p < steady.max_periods; ++p) {
        if (setup.bed_energy) samples_of_energy.at.push_back(boundary);
        PeriodMeasurement period;
        period.stored_at_start_j = boundary.mechanical();
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
            // The walls move rigidly with the point, so their work on the particles is minus
            // the load's power at the point, F.v + M.omega: the sum over the wall contacts of
            // f.v_wall(x_c) + m_r.omega that the solver's ledger adds up, in one product.
            period.wall_work_j -= (load.force_n.dot(motion.velocity_m_s) +
                                   load.moment_nm.dot(motion.angular_velocity_rad_s)) *
                                  dt;
            period.q1 += q * e1[i];
            period.q2 += q * e2[i];
            period.q3 += q * e3[i];
            if (k % stride == 0) {
                kinetic += damper.solver().relative_kinetic_energy();
                ++samples;
            }
            if (setup.bed_energy) {
                samples_of_energy.kinetic_j.push_back(
                    laboratory_kinetic_energy(damper.solver().particles()));
                samples_of_energy.dissipated_j.push_back(damper.solver().dissipated_j());
            }
        }
        period.q1 *= 2.0 / n;
        period.q2 *= 2.0 / n;
        period.q3 *= 2.0 / n;
        boundary = damper.solver().energy();  // this period's end
        period.kinetic_j = kinetic / samples;
        periods.push_back(period);
        const int count = p + 1;
        window_end = count;
        if (after_period) after_period(count);
        if (steady_after(count)) {
            out.settled = true;
            break;
        }
        if (count < steady.max_periods && checkpoints.save && checkpoints.due &&
            checkpoints.due()) {
            checkpoints.save({n, damper.state(), boundary, periods, samples_of_energy});
        }
    }
    out.periods = window_end;
    const int begin = window_end - 2 * w_periods;
    if (setup.bed_energy) {
        samples_of_energy.at.push_back(boundary);  // the last period's end
        out.energy = samples_of_energy.over(begin, window_end, n, dt);
    }
    const double count = 2.0 * w_periods;
    std::complex<double> q1 = 0.0;
    std::complex<double> q2 = 0.0;
    std::complex<double> q3 = 0.0;
    double work = 0.0;
    for (int k = begin; k < window_end; ++k) {
        const PeriodMeasurement& period = periods[static_cast<std::size_t>(k)];
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

}  // namespace sb::bench

// A campaign predicted by harmonic balance with describing functions.
#include "bench/prediction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "bench/arrangement.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/physics_attachments.hpp"
#include "bench/resolved_config.hpp"
#include "bench/shaker.hpp"
#include "config/dotted_path.hpp"
#include "config/errors.hpp"
#include "config/value.hpp"
#include "core/significant_text.hpp"
#include "core/units.hpp"
#include "identification/file_error.hpp"
#include "structure/frf.hpp"

namespace sb::bench {
namespace {

namespace id = identification;
using Complex = std::complex<double>;

std::string file_key(const DamperSpec& damper) {
    return config::join_path(config::join_path("dampers", damper.name), "characterization_file");
}

/// The characterisation table of a damper, read once per file.
const CharacterizationTable& table_of(const CampaignConfig& config, const DamperSpec& damper,
                                      std::map<std::string, CharacterizationTable>& cache) {
    const std::string file = damper.characterization_file.string();
    auto it = cache.find(file);
    if (it != cache.end()) return it->second;
    try {
        return cache.emplace(file, read_characterization_csv(damper.characterization_file))
            .first->second;
    } catch (const id::FileError& e) {
        throw config::ConfigException({config_problem(
            config, file_key(damper), config::quoted(file),
            std::string("cannot be read: ") + e.what(), "characterization.csv of this damper")});
    }
}

std::shared_ptr<const DescribingFunction> function_of(const CampaignConfig& config,
                                                      const DamperSpec& damper,
                                                      const std::string& arrangement,
                                                      const CharacterizationTable& table) {
    const std::string file = damper.characterization_file.string();
    try {
        return std::make_shared<const DescribingFunction>(describing_function_for(
            table, file, damper.name, arrangement, damper.characterization_scale));
    } catch (const id::FileError& e) {
        throw config::ConfigException(
            {config_problem(config, file_key(damper), config::quoted(file),
                            std::string("has no describing function to use: ") + e.what(),
                            "characterization.csv of this damper")});
    }
}

/// A warning when the characterised bed, times the damper's characterization_scale, is not
/// the damper's own bed (within 2 %: the size distribution's draw): a describing function
/// of a part of the bed used for the whole without the scale, or with the wrong one.
std::optional<std::string> bed_mass_mismatch(const DamperSpec& damper,
                                             const CharacterizationTable& table,
                                             std::uint64_t seed) {
    double characterised = 0.0;
    int rows = 0;
    for (const auto& r : table.rows) {
        if (r.damper != damper.name) continue;
        characterised += r.bed_mass_kg;
        ++rows;
    }
    if (rows == 0) return std::nullopt;
    characterised /= rows;
    const double own = particle_mass_kg(damper, seed);
    const double stands_for = damper.characterization_scale * characterised;
    if (!(own > 0.0) || std::abs(stands_for - own) <= 0.02 * own) return std::nullopt;
    std::ostringstream line;
    line << std::setprecision(4) << "warning: damper " << damper.name << ": the bed characterised ("
         << characterised * 1e3 << " g) times characterization_scale "
         << damper.characterization_scale << " is " << stands_for * 1e3 << " g, this damper's bed "
         << own * 1e3 << " g (a scale of " << own / characterised << " would make them equal)";
    return line.str();
}

/// The bed's weight as a load on the point: its mass at the centre of a bed at the
/// packing of a settled one (0.6) on the enclosure floor, as the rigid model places it.
PointLoad bed_weight(const PreparedArrangement& prepared, const DamperSpec& damper,
                     double mass_kg) {
    const ArrangementSpec& arrangement = prepared.arrangement;
    const auto& e = damper.enclosure;
    const double floor_m2 = e.shape == dem::EnclosureShape::cylinder
                                ? kPi * e.inner_diameter_m * e.inner_diameter_m / 4.0
                                : e.length_x_m * e.length_y_m;
    constexpr double kPackingFraction = 0.6;
    const double depth = std::min(e.height_m, mass_kg / damper.particles.material.density_kg_m3 /
                                                  kPackingFraction / floor_m2);
    const DamperMounting mounting = damper_mounting(arrangement, damper);
    const Eigen::Vector3d arm = mounting.from_enclosure(Eigen::Vector3d(0.0, 0.0, 0.5 * depth));
    const Eigen::Vector3d w = mass_kg * prepared.structure.gravity_m_s2;
    return {w, arm.cross(w)};
}

/// A describing function at a point of one sweep: a damper's, characterised, or a catalogue
/// physics' in closed form (an air-drag strip).
struct Described {
    std::string name;  ///< the damper's (or physics attachment's) name
    std::string point;
    std::function<DescribingFunction::Value(double acceleration_m_s2, double frequency_hz)>
        evaluate;
};

/// One predicted point.
struct Solution {
    double drive_amplitude =
        0.0;  ///< F0 of the drive F0 sin(w t) [N, or m/s^2 of base acceleration]
    std::vector<Complex> channels;       ///< phasors per channel [channel unit]
    std::vector<double> h2, h3;          ///< estimated harmonic ratios per channel [-]
    std::vector<double> amplitudes;      ///< |a1| per damper [m/s^2]
    std::vector<Complex> accelerations;  ///< a1 phasor per damper point [m/s^2]
    std::vector<Complex> masses;         ///< apparent mass per damper [kg]
    std::vector<double> drives_tried;    ///< F0 of every iteration [N]
    int iterations = 0;
    bool converged = false;
    bool inside = true;
    bool settled = true;
    double damper_harmonics = 0.0;  ///< largest (|a2| + |a3|) / |a1| at a damper point [-]
    /// Stable steady states found at this frequency (one damper under a fixed drive: every
    /// root of the amplitude balance; otherwise 1, the one the iteration reached).
    int stable_states = 1;
};

/// Every stable steady amplitude of one damper point under a fixed drive, ascending: the
/// roots of g(a) = Phi(a) - a where Phi crosses the diagonal from above (Phi'(a) < 1), with Phi(a)
/// = F0 |h_pd| / |1 + h_pp M(a)|. An apparent mass that changes with the amplitude bends the
/// resonance, and near its peak a fixed drive has up to three steady states (the jump of a stepped
/// sine, as of a Duffing oscillator: the middle one unstable); a fixed point iterated from one
/// start finds one of them at best and oscillates between them at worst. Every root lies in Phi's
/// range, found first on a coarse scan over twelve decades; the roots are then bracketed on a fine
/// logarithmic scan of that range and bisected. M is continuous (docs/characterisation.md), so is
/// g.
std::vector<double> stable_steady_amplitudes(const std::function<double(double)>& phi) {
    constexpr int kCoarsePerDecade = 24;
    double low = std::numeric_limits<double>::infinity();
    double high = 0.0;
    for (int k = -6 * kCoarsePerDecade; k <= 6 * kCoarsePerDecade; ++k) {
        const double v = phi(std::pow(10.0, static_cast<double>(k) / kCoarsePerDecade));
        low = std::min(low, v);
        high = std::max(high, v);
    }
    std::vector<double> roots;
    if (!(low > 0.0) || !std::isfinite(high)) return roots;
    if (high <= low * (1.0 + 1e-12)) return {low};  // a linear damper: Phi constant
    low /= 1.01;
    high *= 1.01;
    constexpr int kFine = 2000;
    const double step = std::log(high / low) / kFine;
    const auto g = [&phi](double log_a) { return phi(std::exp(log_a)) - std::exp(log_a); };
    double x0 = std::log(low);
    double g0 = g(x0);  // > 0: Phi(low) >= low * 1.01
    for (int k = 1; k <= kFine; ++k) {
        const double x1 = std::log(low) + k * step;
        const double g1 = g(x1);
        if (g0 > 0.0 && g1 <= 0.0) {  // the middle, unstable roots cross from below
            double a = x0;
            double b = x1;
            for (int it = 0; it < 60; ++it) {
                const double m = 0.5 * (a + b);
                if (g(m) > 0.0) {
                    a = m;
                } else {
                    b = m;
                }
            }
            roots.push_back(std::exp(0.5 * (a + b)));
        }
        x0 = x1;
        g0 = g1;
    }
    return roots;
}

/// A motion channel's phasor per unit acceleration phasor at angular frequency w: 1,
/// 1 / (i w) for a velocity, -1 / w^2 for a displacement.
Complex per_acceleration(RecordedChannel::Quantity quantity, double w) {
    switch (quantity) {
        case RecordedChannel::Quantity::velocity:
            return 1.0 / Complex(0.0, w);
        case RecordedChannel::Quantity::displacement:
            return -1.0 / (w * w);
        default:
            return 1.0;
    }
}

/// Harmonic balance at one frequency: the structure's accelerances between the drive, the
/// damper points and the channel points, the dampers as Q_j = -M_j(|a_j|, f) a_j along the
/// excitation direction d. For a unit force phasor the damper points' accelerations solve
///   (I + H_pp diag(M)) a_p = H_pd,
/// the channels' accelerations (each along its own direction) follow as
/// a_c = H_cd - H_cp diag(M) a_p, a velocity or displacement channel as a_c / (i w) or
/// -a_c / w^2, a damper-force channel as Q_j projected on its direction; F0 scales them to
/// the control target, or is `fixed_drive` (a fixed drive's excitation amplitude at this
/// frequency). M depends on |a_p|: a fixed point on the amplitudes, exact in one step when
/// the control point is the only damper's point (its amplitude is the target's).
Solution solve_point(const PreparedArrangement& prepared, const std::vector<Described>& dampers,
                     const std::vector<RecordedChannel>& channels, double level_g,
                     double frequency_hz, std::optional<double> fixed_drive,
                     const std::vector<double>& previous) {
    const auto& model = prepared.model;
    const auto& basis = prepared.basis;
    const auto& excitation = prepared.structure.excitation;
    const Eigen::Vector3d d = excitation.direction.normalized();
    const auto accelerance = [&](const std::string& out, const std::string& in, double f) {
        return structure::modal_accelerance(model, basis, out, d, in, d, f);
    };
    const auto channel_accelerance = [&](const RecordedChannel& c, const std::string& in,
                                         double f) {
        return structure::modal_accelerance(model, basis, c.point, c.direction, in, d, f);
    };
    // The response to a unit drive: the accelerance from the drive point, or under base
    // excitation the absolute acceleration per unit base acceleration (the dampers' loads
    // act on the structure relative to its base, through the same accelerances h_pp).
    const bool base = excitation.kind == structure::ExcitationSpec::Kind::base;
    const auto drive_response = [&](const std::string& out, const Eigen::Vector3d& along,
                                    double f) {
        return base
                   ? structure::modal_base_transmissibility(model, basis, out, along, f)
                   : structure::modal_accelerance(model, basis, out, along, excitation.point, d, f);
    };
    const std::size_t nd = dampers.size();
    const std::size_t nc = channels.size();
    // Per channel: the damper whose force it reads (damper-force channels), found once.
    std::vector<std::optional<std::size_t>> force_of(nc);
    for (std::size_t c = 0; c < nc; ++c) {
        if (channels[c].quantity != RecordedChannel::Quantity::damper_force) continue;
        for (std::size_t j = 0; j < nd; ++j) {
            if (dampers[j].name == channels[c].damper) force_of[c] = j;
        }
        if (!force_of[c]) {
            throw std::invalid_argument("prediction: channel " + channels[c].name +
                                        " reads the force of \"" + channels[c].damper +
                                        "\", which is not predicted");
        }
    }
    Eigen::VectorXcd h_pd(static_cast<Eigen::Index>(nd));
    Eigen::MatrixXcd h_pp(static_cast<Eigen::Index>(nd), static_cast<Eigen::Index>(nd));
    Eigen::VectorXcd h_cd = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(nc));
    Eigen::MatrixXcd h_cp =
        Eigen::MatrixXcd::Zero(static_cast<Eigen::Index>(nc), static_cast<Eigen::Index>(nd));
    for (std::size_t j = 0; j < nd; ++j) {
        const auto jj = static_cast<Eigen::Index>(j);
        h_pd(jj) = drive_response(dampers[j].point, d, frequency_hz);
        for (std::size_t k = 0; k < nd; ++k) {
            h_pp(jj, static_cast<Eigen::Index>(k)) =
                accelerance(dampers[j].point, dampers[k].point, frequency_hz);
        }
    }
    const double w = hz_to_rad_s(frequency_hz);
    for (std::size_t c = 0; c < nc; ++c) {
        const auto cc = static_cast<Eigen::Index>(c);
        if (const auto j = force_of[c]) {
            // Q_j = -M_j a_j along d, read along the channel's direction.
            h_cp(cc, static_cast<Eigen::Index>(*j)) = d.dot(channels[c].direction);
            continue;
        }
        const Complex per = per_acceleration(channels[c].quantity, w);
        h_cd(cc) = per * drive_response(channels[c].point, channels[c].direction, frequency_hz);
        for (std::size_t k = 0; k < nd; ++k) {
            h_cp(cc, static_cast<Eigen::Index>(k)) =
                per * channel_accelerance(channels[c], dampers[k].point, frequency_hz);
        }
    }
    const double target_peak = std::sqrt(2.0) * g_to_m_s2(level_g);

    Solution s;
    // Start: the amplitudes the structure without the dampers would give at the target (or
    // at the fixed drive).
    std::vector<double> amplitude(nd);
    for (std::size_t j = 0; j < nd; ++j) {
        const double h = std::abs(h_pd(static_cast<Eigen::Index>(j)));
        amplitude[j] = fixed_drive ? *fixed_drive * h
                       : channels.front().point == dampers[j].point
                           ? target_peak
                           : target_peak * h / std::abs(h_cd(0));
    }
    // Along a sweep, from the previous point's amplitudes: a stepped sine stays on the
    // branch it is on.
    if (previous.size() == nd) amplitude = previous;
    if (fixed_drive && nd == 1) {
        const auto phi = [&](double a) {
            const Complex m = dampers[0].evaluate(a, frequency_hz).apparent_mass_kg;
            return *fixed_drive * std::abs(h_pd(0)) / std::abs(1.0 + h_pp(0, 0) * m);
        };
        const std::vector<double> stable = stable_steady_amplitudes(phi);
        if (!stable.empty()) {
            // The branch the sweep is on (the nearest in ln a); the first point from rest,
            // the lowest.
            double chosen = stable.front();
            if (previous.size() == 1) {
                for (double a : stable) {
                    if (std::abs(std::log(a / previous[0])) <
                        std::abs(std::log(chosen / previous[0]))) {
                        chosen = a;
                    }
                }
            }
            amplitude[0] = chosen;
            s.stable_states = static_cast<int>(stable.size());
        }
    }
    Eigen::VectorXcd mass(static_cast<Eigen::Index>(nd));
    Eigen::VectorXcd a_p;
    Eigen::VectorXcd a_c;
    std::vector<DescribingFunction::Value> values(nd);
    for (int it = 1; it <= kPredictIterations; ++it) {
        for (std::size_t j = 0; j < nd; ++j) {
            values[j] = dampers[j].evaluate(amplitude[j], frequency_hz);
            mass(static_cast<Eigen::Index>(j)) = values[j].apparent_mass_kg;
        }
        const Eigen::MatrixXcd system = Eigen::MatrixXcd::Identity(static_cast<Eigen::Index>(nd),
                                                                   static_cast<Eigen::Index>(nd)) +
                                        h_pp * mass.asDiagonal();
        a_p = nd == 0 ? Eigen::VectorXcd() : Eigen::VectorXcd(system.partialPivLu().solve(h_pd));
        a_c = h_cd - h_cp * (mass.asDiagonal() * a_p);
        s.drive_amplitude = fixed_drive ? *fixed_drive : target_peak / std::abs(a_c(0));
        s.drives_tried.push_back(s.drive_amplitude);
        s.iterations = it;
        double change = 0.0;
        std::vector<double> next(nd);
        for (std::size_t j = 0; j < nd; ++j) {
            next[j] = s.drive_amplitude * std::abs(a_p(static_cast<Eigen::Index>(j)));
            change = std::max(change, std::abs(next[j] - amplitude[j]) / amplitude[j]);
        }
        if (change <= kPredictConvergence) {
            s.converged = true;
            break;
        }
        // Relaxed after the first steps, in case a stiffening bed makes the plain fixed point
        // oscillate between two amplitudes.
        const double relax = it <= 10 ? 1.0 : 0.5;
        for (std::size_t j = 0; j < nd; ++j) {
            amplitude[j] += relax * (next[j] - amplitude[j]);
        }
    }
    // The force phasor of F0 sin(w t) is -i F0: every response scales by it.
    const Complex drive(0.0, -s.drive_amplitude);
    s.amplitudes = amplitude;
    for (std::size_t j = 0; j < nd; ++j) {
        s.accelerations.push_back(a_p(static_cast<Eigen::Index>(j)) * drive);
        s.masses.push_back(mass(static_cast<Eigen::Index>(j)));
    }
    for (std::size_t c = 0; c < nc; ++c)
        s.channels.push_back(a_c(static_cast<Eigen::Index>(c)) * drive);
    // Harmonics: the dampers' force harmonics |Q_k| = h_k |Q1| (characterised) reach every
    // channel through the accelerance at k w (a velocity over k w, a displacement over
    // (k w)^2; a damper-force channel is its damper's own); their phases are unknown, so the
    // magnitudes add (an upper bound when several dampers load the structure).
    s.h2.assign(nc, 0.0);
    s.h3.assign(nc, 0.0);
    for (std::size_t j = 0; j < nd; ++j) {
        const double q1 =
            std::abs(mass(static_cast<Eigen::Index>(j)) * a_p(static_cast<Eigen::Index>(j))) *
            s.drive_amplitude;
        for (std::size_t c = 0; c < nc; ++c) {
            const double a1 = std::abs(s.channels[c]);
            if (!(a1 > 0.0)) continue;
            if (const auto k = force_of[c]) {
                if (*k == j) {
                    s.h2[c] = values[j].h2_ratio;
                    s.h3[c] = values[j].h3_ratio;
                }
                continue;
            }
            const auto at = [&](int harmonic) {
                const double f = harmonic * frequency_hz;
                return std::abs(per_acceleration(channels[c].quantity, harmonic * w) *
                                channel_accelerance(channels[c], dampers[j].point, f));
            };
            s.h2[c] += at(2) * values[j].h2_ratio * q1 / a1;
            s.h3[c] += at(3) * values[j].h3_ratio * q1 / a1;
        }
        s.inside = s.inside && values[j].inside;
        s.settled = s.settled && values[j].settled;
    }
    // The same at every damper point: what the characterisation's pure sine did not have.
    std::vector<double> q1(nd);
    for (std::size_t k = 0; k < nd; ++k) {
        const auto kk = static_cast<Eigen::Index>(k);
        q1[k] = std::abs(mass(kk) * a_p(kk)) * s.drive_amplitude;
    }
    for (std::size_t j = 0; j < nd; ++j) {
        const double a1 = s.drive_amplitude * std::abs(a_p(static_cast<Eigen::Index>(j)));
        double harmonics = 0.0;
        for (std::size_t k = 0; k < nd; ++k) {
            const auto& out = dampers[j].point;
            const auto& in = dampers[k].point;
            harmonics +=
                std::abs(accelerance(out, in, 2.0 * frequency_hz)) * values[k].h2_ratio * q1[k] +
                std::abs(accelerance(out, in, 3.0 * frequency_hz)) * values[k].h3_ratio * q1[k];
        }
        if (a1 > 0.0) s.damper_harmonics = std::max(s.damper_harmonics, harmonics / a1);
    }
    return s;
}

std::string status_of(const Solution& s) {
    if (!s.converged || !s.settled || s.damper_harmonics > kHarmonicTrustLimit) return "uncertain";
    if (!s.inside) return "extrapolated";
    return "predicted";
}

}  // namespace

Attachment describing_function_attachment(const CampaignConfig& config, const DamperSpec& damper,
                                          const PreparedArrangement& prepared) {
    std::map<std::string, CharacterizationTable> cache;
    const CharacterizationTable& table = table_of(config, damper, cache);
    auto function = function_of(config, damper, prepared.arrangement.name, table);
    const PointLoad weight = bed_weight(prepared, damper, function->bed_mass_kg());
    DescribingFunctionDamper model(function, prepared.structure.excitation.direction,
                                   prepared.model.point(damper.point).position_m, weight);
    return {damper.name, damper.point, std::move(model)};
}

CampaignConfig with_describing_functions(const CampaignConfig& config,
                                         const std::filesystem::path& file, double scale) {
    CampaignConfig out = config;
    const std::filesystem::path absolute = std::filesystem::absolute(file).lexically_normal();
    for (auto& d : out.campaign.dampers) {
        if (d.model != DamperSpec::Model::dem) continue;
        d.model = DamperSpec::Model::describing_function;
        d.characterization_file = absolute;
        d.characterization_scale = scale;
    }
    return out;
}

CampaignResult predict_campaign(const CampaignConfig& config, const PredictContext& context) {
    const auto started = std::chrono::steady_clock::now();
    const CampaignSpec& campaign = config.campaign;
    std::vector<config::ConfigError> problems;
    for (const auto& d : campaign.dampers) {
        if (d.model == DamperSpec::Model::dem) {
            problems.push_back(config_problem(
                config, config::join_path(config::join_path("dampers", d.name), "model"), "\"dem\"",
                "cannot be predicted: needs model = \"describing-function\"",
                "predict solves the structure with describing functions (or give "
                "--characterization FILE)"));
        }
    }
    if (config.physics.air_drag.on() &&
        !config.structure.excitation.direction.normalized().isApprox(Eigen::Vector3d::UnitZ())) {
        problems.push_back(
            config_problem(config, "physics.air_drag.drag_coefficient",
                           config::number_text(config.physics.air_drag.drag_coefficient),
                           "cannot be predicted with the drive off the beam's z axis",
                           "predict balances the drag along the excitation direction, "
                           "the drag acts along the wide face's normal z"));
    }
    if (!problems.empty()) throw config::ConfigException(problems);
    const CampaignPlan plan = plan_campaign(config, context.selection);

    CampaignResult result;
    result.config_hash = config_hash(config);
    result.threads = 1;
    result.channels = recorded_channels(campaign, config.structure.excitation);
    std::map<std::string, CharacterizationTable> tables;
    std::vector<std::string> warned;
    for (const auto& d : campaign.dampers) {
        if (d.model != DamperSpec::Model::describing_function) continue;
        const CharacterizationTable& table = table_of(config, d, tables);
        const std::string mine = damper_hash(config, d.name);
        for (const auto& [name, hash] : table.damper_hashes) {
            if (name == d.name && hash != mine && context.progress) {
                context.progress("warning: damper " + d.name + " of this config (" + mine +
                                 ") is not the damper characterised in " +
                                 d.characterization_file.string() + " (" + hash + ")");
            }
        }
        if (context.progress) {
            if (const auto line = bed_mass_mismatch(d, table, campaign.seed)) {
                context.progress(*line);
            }
        }
    }
    if (context.progress) {
        context.progress("prediction " + config.name + ": " + std::to_string(plan.tasks.size()) +
                         " sweeps, " + std::to_string(plan.points()) + " points");
    }
    for (const SweepTask& task : plan.tasks) {
        const PreparedArrangement& prepared = *task.prepared;
        std::vector<Described> dampers;
        SweepResult sweep;
        sweep.key = task.key;
        sweep.arrangement = prepared.arrangement.name;
        sweep.level_g = task.level_g;
        sweep.first_mode_hz = prepared.first_mode_hz;
        sweep.frequencies_hz = task.frequencies_hz;
        for (const auto& d : campaign.dampers) {
            if (d.model != DamperSpec::Model::describing_function) continue;
            const auto& table = table_of(config, d, tables);
            auto function = function_of(config, d, prepared.arrangement.name, table);
            dampers.push_back({d.name, d.point, [function](double a, double f) {
                                   return function->evaluate(a, f);
                               }});
            sweep.settings.push_back(d.name + ": describing function of " +
                                     d.characterization_file.string() + " (characterised config " +
                                     table.config_hash + ")");
        }
        std::optional<std::size_t> coil;  // the shaker's coil among them
        for (auto& a : physics_attachments(config, prepared)) {
            if (std::holds_alternative<ShakerCoil>(a.model)) coil = dampers.size();
            auto shared = std::make_shared<const Attachment>(std::move(a));
            dampers.push_back(
                {shared->name, shared->point, [shared](double acceleration, double f) {
                     return physics_describing(*shared, acceleration, f);
                 }});
        }
        const ShakerSpec& shaker = config.physics.shaker;
        std::vector<double> previous;  // the amplitudes of the sweep's previous point
        std::vector<double> several;   // frequencies with more than one stable steady state
        for (double f : task.frequencies_hz) {
            // Through a shaker the drive is a voltage: its blocked force per volt.
            const Complex per_volt = shaker.on() ? blocked_force_per_volt(shaker, f) : 1.0;
            // A fixed drive's force (through a shaker, the blocked force of its voltage).
            std::optional<double> fixed;
            if (campaign.drive.fixed()) {
                fixed = campaign.drive.excitation_amplitude(task.level_g, f) * std::abs(per_volt);
            }
            const Solution s =
                solve_point(prepared, dampers, result.channels, task.level_g, f, fixed, previous);
            if (s.converged) previous = s.amplitudes;
            if (s.stable_states > 1) several.push_back(f);
            id::PointRow row;
            row.arrangement = prepared.arrangement.name;
            row.level_g = task.level_g;
            row.frequency_hz = f;
            row.status = status_of(s);
            // The drive: the force F0 sin(w t), phasor -i F0, or through a shaker the voltage
            // whose blocked force it is, V = -i F0 / G.
            const Complex blocked(0.0, -s.drive_amplitude);
            id::ChannelValue drive;
            drive.amplitude = blocked / per_volt;
            drive.rms = std::abs(drive.amplitude) / std::sqrt(2.0);
            drive.h2_ratio = 0.0;  // the drive is a pure sine
            drive.h3_ratio = 0.0;
            row.values.push_back(drive);
            for (std::size_t c = 0; c < s.channels.size(); ++c) {
                id::ChannelValue v;
                // The fundamental only: the RMS the harmonics would add is below
                // kHarmonicTrustLimit^2 / 2 of it wherever a point is trusted.
                v.rms = std::abs(s.channels[c]) / std::sqrt(2.0);
                v.amplitude = s.channels[c];
                v.h2_ratio = s.h2[c];
                v.h3_ratio = s.h3[c];
                row.values.push_back(v);
            }
            if (shaker.on()) {
                // The transducer: the blocked force less what the coil, the suspension and
                // the armature's inertia take back at the drive point.
                // (a shaker on brings its coil: physics_attachments adds it at the drive point)
                const std::size_t k = coil.value();
                id::ChannelValue transducer;
                transducer.amplitude =
                    blocked - (s.masses[k] + shaker.armature_mass_kg) * s.accelerations[k];
                transducer.rms = std::abs(transducer.amplitude) / std::sqrt(2.0);
                row.values.push_back(transducer);
            }
            sweep.rows.push_back(row);
            std::string tried;
            for (double a : s.drives_tried) {
                tried += (tried.empty() ? "" : ";") + significant_text(a / std::abs(per_volt));
            }
            sweep.control_log.push_back(
                prepared.arrangement.name + "," + significant_text(task.level_g) + "," +
                significant_text(f) + "," + row.status + ",0," + std::to_string(s.iterations) +
                "," + significant_text(std::abs(row.values[0].amplitude)) + "," +
                significant_text(row.values[1].rms) + "," + tried + ",");
        }
        if (!several.empty()) {
            const std::string where = several.size() == 1
                                          ? significant_text(several.front()) + " Hz"
                                          : std::to_string(several.size()) + " frequencies (" +
                                                significant_text(several.front()) + " to " +
                                                significant_text(several.back()) + " Hz)";
            const std::string line = sweep.key + ": more than one stable steady state at " + where +
                                     ": the branch the sweep was on followed, as a stepped sine "
                                     "would (campaign.frequencies.direction)";
            sweep.settings.push_back(line);
            if (context.progress) context.progress(line);
        }
        result.sweeps.push_back(std::move(sweep));
    }

    result.recording = campaign_recording(config, result.channels);
    CampaignSummary& summary = result.summary;
    summary.points = plan.points();
    for (const auto& sweep : result.sweeps) {
        result.recording.points.insert(result.recording.points.end(), sweep.rows.begin(),
                                       sweep.rows.end());
    }
    identify_campaign(config, context.progress, result);
    summary.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

}  // namespace sb::bench

// The stepped-sine campaign orchestrator.
#include "bench/campaign.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>
#include <iomanip>
#include <mutex>
#include <optional>
#include <sstream>

#include "bench/arrangement.hpp"
#include "bench/campaign_output.hpp"
#include "bench/coupled_specimen.hpp"
#include "bench/driven_mode.hpp"
#include "bench/frequency_grid.hpp"
#include "bench/linear_estimate.hpp"
#include "bench/resolved_config.hpp"
#include "bench/specimen_plant.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "config/errors.hpp"
#include "control/controller.hpp"
#include "core/text_file.hpp"
#include "core/units.hpp"
#include "dem/setup.hpp"
#include "structure/frf.hpp"

namespace sb::bench {
namespace {

namespace fs = std::filesystem;

/// One arrangement's structure: masses added for it, model, modes and grid.
struct PreparedArrangement {
    ArrangementSpec arrangement;
    structure::StructureSpec structure;  ///< with blocks (and rigid particles)
    structure::LinearModel model;
    structure::ModalBasis basis;
    /// Every damper's particles as rigid mass: the linear reference for amplitude guesses.
    structure::LinearModel estimate_model;
    structure::ModalBasis estimate_basis;
    double first_mode_hz = 0.0;
    std::vector<double> frequencies_hz;
};

struct Sweep {
    const PreparedArrangement* prepared = nullptr;
    double level_g = 0.0;
    std::string key;  ///< file-name friendly, e.g. "H-0_1g"
};

std::string number_text(double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.9g", v);
    return buffer;
}

double particle_mass_kg(const DamperSpec& damper, std::uint64_t seed) {
    double mass = 0.0;
    for (double r : dem::make_radii(damper.particles, seed)) {
        mass += damper.particles.material.density_kg_m3 * 4.0 / 3.0 * kPi * r * r * r;
    }
    return mass;
}

/// Depth of a settled bed (random close packing about 0.6) on the enclosure floor [m].
double bed_depth_m(const DamperSpec& damper, double mass_kg) {
    const auto& e = damper.enclosure;
    const double floor_m2 = e.shape == dem::EnclosureShape::cylinder
                                ? kPi * e.inner_diameter_m * e.inner_diameter_m / 4.0
                                : e.length_x_m * e.length_y_m;
    constexpr double kPackingFraction = 0.6;
    return std::min(e.height_m, mass_kg / damper.particles.material.density_kg_m3 /
                                    kPackingFraction / floor_m2);
}

double point_position_m(const structure::StructureSpec& spec, const std::string& point) {
    for (const auto& p : spec.beam.points) {
        if (p.name == point) return p.x_m;
    }
    for (const auto& m : spec.beam.masses) {
        if (m.name == point) return m.x_m;
    }
    throw std::runtime_error("no beam point named '" + point + "'");
}

/// Adds a rigid mass at a damper's point (beam: a lumped mass with its centre offset;
/// lumped model: added to the named mass).
void add_mass(structure::StructureSpec& spec, const std::string& point, const std::string& name,
              double mass_kg, const Eigen::Vector3d& offset_m) {
    using Kind = structure::StructureSpec::Kind;
    if (spec.kind == Kind::beam) {
        structure::LumpedMass m;
        m.name = name;
        m.x_m = point_position_m(spec, point);
        m.mass_kg = mass_kg;
        m.offset_m = offset_m;
        spec.beam.masses.push_back(m);
    } else if (spec.kind == Kind::lumped) {
        for (auto& m : spec.lumped.masses) {
            if (m.name == point) m.mass_kg += mass_kg;
        }
    } else {
        throw std::runtime_error(
            "rigid dampers and mounting blocks need a beam or lumped structure, not imported "
            "matrices (add their mass to the matrices instead)");
    }
}

PreparedArrangement prepare(const CampaignConfig& config, const ArrangementSpec& arrangement) {
    PreparedArrangement p;
    p.arrangement = arrangement;
    p.structure = arrangement_structure(config, arrangement, false);
    const structure::StructureSpec estimate = arrangement_structure(config, arrangement, true);
    p.model = structure::build_linear_model(p.structure, config.base_dir);
    p.basis = structure::compute_modes(p.model, p.structure.damping, p.structure.modes);
    p.estimate_model = structure::build_linear_model(estimate, config.base_dir);
    p.estimate_basis = structure::compute_modes(p.estimate_model, estimate.damping, estimate.modes);
    p.first_mode_hz = first_driven_mode_hz(p.estimate_basis, p.structure.excitation.direction);
    p.frequencies_hz = frequency_grid(config.campaign.frequencies, p.first_mode_hz);
    return p;
}

/// The contact stiffness and DEM time step of a damper in one sweep, and a line saying so.
struct SweepStiffness {
    double stiffness = 0.0;  ///< Hooke [N/m] or Hertz [N/m^1.5]
    double dt_s = 0.0;       ///< DEM time step [s]
    std::string log;
};

/// The given stiffness, or one chosen for the sweep's level (automatic), and the time step
/// from the contact time.
SweepStiffness choose_stiffness(const DamperSpec& damper, double level_g, double first_mode_hz) {
    const ContactSpec& contact = damper.contact;
    const auto& particles = damper.particles;
    const double d = particles.largest_diameter_m();
    const double mass = particles.material.density_kg_m3 * kPi * d * d * d / 6.0;
    dem::AutoStiffnessInput in;
    in.law = contact.normal;
    in.particle_diameter_m = d;
    in.density_kg_m3 = particles.material.density_kg_m3;
    in.max_overlap_fraction = contact.max_overlap_fraction;
    in.level_m_s2 = std::sqrt(2.0) * g_to_m_s2(level_g);  // peak of the RMS target
    in.frequency_hz = first_mode_hz;
    in.gap_m = damper.enclosure.height_m;
    in.restitution = contact.particle_particle.restitution;
    in.time_step_fraction = contact.time_step_fraction;
    SweepStiffness out;
    if (!contact.normal_stiffness) {
        const auto chosen = dem::auto_stiffness(in);
        out.stiffness = chosen.stiffness;
        out.dt_s = chosen.time_step_s;
        out.log = "automatic: " + dem::describe(chosen, contact.normal);
    } else {
        out.stiffness = *contact.normal_stiffness;
        const double contact_time =
            contact.normal == dem::NormalLaw::hooke
                ? dem::hooke_contact_time(0.5 * mass, out.stiffness,
                                          contact.particle_particle.restitution)
                : dem::hertz_contact_time(0.5 * mass, out.stiffness,
                                          dem::auto_stiffness(in).impact_speed_m_s);
        out.dt_s = contact.time_step_fraction * contact_time;
        out.log = "stiffness " + number_text(out.stiffness) + " (given), contact time " +
                  number_text(contact_time) + " s, time step " + number_text(out.dt_s) + " s";
    }
    return out;
}

/// The settled bed of a damper in its mounting (gravity in the enclosure frame), from the
/// out_dir/settled cache when present; written there with exact round-trip digits either way
/// and read back, so a fresh and a resumed run start from the same numbers.
dem::ParticleSet settled_particles(const DamperSpec& damper, double stiffness,
                                   const Eigen::Matrix3d& rotation, const Eigen::Vector3d& gravity,
                                   std::uint64_t seed, const fs::path& cache) {
    if (!fs::exists(cache)) {
        dem::SolverOptions local = damper.solver_options(stiffness);
        local.gravity_m_s2 = rotation.transpose() * gravity;
        local.track_energy = false;
        dem::ParticleSet settled;
        if (damper.fill == DamperSpec::Fill::pour) {
            settled = dem::pour(local, seed, damper.settle);
        } else {
            dem::ParticleSet filled;
            try {
                filled = dem::fill_random(local, seed);
            } catch (const std::runtime_error& e) {
                throw std::runtime_error("damper " + damper.name + ": " + e.what() +
                                         " (set dampers." + damper.name +
                                         ".settle.fill = \"pour\")");
            }
            settled = dem::settle(local, filled, damper.settle);
        }
        fs::create_directories(cache.parent_path());
        const fs::path partial = cache.string() + ".partial";
        dem::save_particles(partial.string(), settled);
        fs::rename(partial, cache);
    }
    return dem::load_particles(cache.string());
}

struct Shared {
    const CampaignConfig* config = nullptr;
    const CampaignRunOptions* options = nullptr;
    std::mutex progress_mutex;
    std::atomic<int> points_done{0};
    std::atomic<int> points_simulated{0};
    std::atomic<long long> periods{0};
    int points_total = 0;
    std::chrono::steady_clock::time_point start;
    std::string config_hash;  ///< of the resolved config: every checkpoint and bed carries it
};

std::string format_duration(double seconds) {
    const long s = std::lround(seconds);
    std::ostringstream out;
    if (s >= 3600) out << s / 3600 << "h";
    if (s >= 60) out << (s % 3600) / 60 << "m";
    out << s % 60 << "s";
    return out.str();
}

/// A point starts: says which, so a long point is not mistaken for a hang.
void report_start(Shared& shared, const Sweep& sweep, int index, double frequency_hz) {
    if (shared.options->progress == nullptr) {
        return;
    }
    std::lock_guard<std::mutex> lock(shared.progress_mutex);
    auto& out = *shared.options->progress;
    out << "  start " << sweep.prepared->arrangement.name << ' ' << number_text(sweep.level_g)
        << " g " << std::fixed << std::setprecision(3) << frequency_hz << " Hz (frequency "
        << index + 1 << " of " << sweep.prepared->frequencies_hz.size() << ")\n"
        << std::defaultfloat << std::flush;
}

void report_progress(Shared& shared, const Sweep& sweep, double frequency_hz,
                     const control::PointResult& result) {
    const int done = ++shared.points_done;
    const int simulated = ++shared.points_simulated;
    shared.periods += result.periods_simulated;
    if (shared.options->progress == nullptr) {
        return;
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - shared.start).count();
    const double eta = elapsed / simulated * (shared.points_total - done);
    std::lock_guard<std::mutex> lock(shared.progress_mutex);
    auto& out = *shared.options->progress;
    out << '[' << done << '/' << shared.points_total << "] " << sweep.prepared->arrangement.name
        << ' ' << number_text(sweep.level_g) << " g " << std::fixed << std::setprecision(3)
        << frequency_hz << " Hz: " << control::to_string(result.status) << " after "
        << result.periods_simulated << " periods (" << result.updates << " updates), "
        << std::setprecision(1)
        << static_cast<double>(shared.periods.load()) / std::max(elapsed, 1e-9)
        << " periods/s, ETA " << format_duration(eta) << '\n'
        << std::defaultfloat << std::flush;
}

std::string control_log_line(const Sweep& sweep, const control::PointResult& r) {
    std::string amplitudes;
    for (double a : r.amplitudes_tried) {
        amplitudes += (amplitudes.empty() ? "" : ";") + number_text(a);
    }
    std::string rms;
    for (double v : r.rms_per_period) {
        rms += (rms.empty() ? "" : ";") + number_text(v);
    }
    return sweep.prepared->arrangement.name + "," + number_text(sweep.level_g) + "," +
           number_text(r.frequency_hz) + "," + std::string(control::to_string(r.status)) + "," +
           std::to_string(r.periods_simulated) + "," + std::to_string(r.updates) + "," +
           number_text(r.amplitude_final) + "," + number_text(r.rms_final) + "," + amplitudes +
           "," + rms;
}

/// Runs (or resumes) one sweep; returns its checkpoint with every row.
SweepCheckpoint run_sweep(const Sweep& sweep, Shared& shared, std::vector<std::string>& log) {
    const CampaignConfig& config = *shared.config;
    const CampaignSpec& campaign = config.campaign;
    const PreparedArrangement& prepared = *sweep.prepared;
    const fs::path out_dir = shared.options->out_dir;
    const fs::path checkpoint_file = out_dir / "checkpoints" / (sweep.key + ".txt");
    const Eigen::Vector3d gravity = arrangement_gravity(prepared.arrangement);

    std::vector<MountedDamper> dampers;
    double dt_max = 1.0 / (256.0 * prepared.frequencies_hz.front());
    for (const DamperSpec& damper : campaign.dampers) {
        const DamperMounting mounting = damper_mounting(prepared.arrangement, damper);
        const Eigen::Matrix3d& rotation = mounting.rotation;
        MountedDamper mounted;
        mounted.name = damper.name;
        mounted.point = damper.point;
        mounted.mount_rotation = rotation;
        mounted.offset_m = mounting.origin_m;
        if (damper.model == DamperSpec::Model::dem) {
            const SweepStiffness chosen =
                choose_stiffness(damper, sweep.level_g, prepared.first_mode_hz);
            dt_max = std::min(dt_max, chosen.dt_s);
            log.push_back(damper.name + ": " + chosen.log);
            // The bed depends on the config: its file carries the config's hash, so another
            // config never starts from it.
            const auto settled = settled_particles(
                damper, chosen.stiffness, rotation, gravity, campaign.seed,
                out_dir / "settled" /
                    (sweep.key + "_" + damper.name + "_" + shared.config_hash + ".csv"));
            dem::SolverOptions options = damper.solver_options(chosen.stiffness);
            options.gravity_m_s2 = gravity;
            options.track_energy = false;  // the campaign measures damping from the FRF
            if (damper.locked) {
                options.lock.fraction = 1.0;  // never released: release_time_s stays 0
            }
            dem::EnclosureState rest;
            rest.position_m = prepared.model.point(damper.point).position_m + mounted.offset_m;
            rest.rotation = rotation;
            mounted.solver = std::make_unique<dem::Solver>(options, settled, rest);
        }
        dampers.push_back(std::move(mounted));
    }

    std::vector<std::string> channel_points{campaign.control_point};
    for (const auto& p : campaign.response_points) {
        if (p != campaign.control_point) channel_points.push_back(p);
    }
    const int series_samples =
        campaign.output.series ? campaign.output.series_samples_per_period : 0;
    CoupledSpecimen specimen(prepared.model, prepared.basis, prepared.structure.excitation,
                             std::move(dampers), channel_points, dt_max,
                             std::max(series_samples, 1));
    specimen.set_start_model(prepared.estimate_model, prepared.estimate_basis);
    SpecimenPlant plant(specimen, series_samples, campaign.scale_response_on_update);
    const double target_rms = g_to_m_s2(sweep.level_g);
    const auto& frequencies = prepared.frequencies_hz;
    const auto linear_gain = [&](double f) {
        return linear_response_per_unit_input(prepared.estimate_model, prepared.estimate_basis,
                                              prepared.structure.excitation, campaign.control_point,
                                              f);
    };

    const Eigen::Vector3d direction = prepared.structure.excitation.direction.normalized();
    const DrivenMode driven_mode(prepared.estimate_model, prepared.estimate_basis,
                                 prepared.structure.excitation, campaign.control_point,
                                 prepared.first_mode_hz);

    SweepCheckpoint checkpoint;
    if (fs::exists(checkpoint_file)) {
        checkpoint = parse_checkpoint(read_text_file(checkpoint_file), checkpoint_file.string());
        shared.points_done += checkpoint.points_done;
    } else {
        // First point: the linear steady state at the first frequency, settled particles.
        const double start = campaign.controller.initial_amplitude
                                 ? *campaign.controller.initial_amplitude
                                 : std::sqrt(2.0) * target_rms / linear_gain(frequencies.front());
        specimen.set_frequency(frequencies.front());
        specimen.start_from_linear_steady_state(start, 0.0);
        checkpoint.config_hash = shared.config_hash;
        checkpoint.next_amplitude = start;
        checkpoint.state = specimen.state();
        const std::string text = serialize_checkpoint(checkpoint);
        fs::create_directories(checkpoint_file.parent_path());
        write_file_atomically(checkpoint_file, text);
        checkpoint = parse_checkpoint(text, checkpoint_file.string());
    }

    // Every point's start is set below (set_start_amplitude).
    const control::ControllerOptions& controller_options = campaign.controller;
    for (int i = checkpoint.points_done; i < static_cast<int>(frequencies.size()); ++i) {
        const double f = frequencies[static_cast<std::size_t>(i)];
        specimen.set_frequency(f);
        specimen.restore(checkpoint.state);
        // Warm start: the previous amplitude scaled by the gain ratio the previous point's
        // equivalent mode predicts (the linear model's ratio when there is none).
        double start = checkpoint.next_amplitude;
        std::optional<std::complex<double>> predicted;
        if (i > 0) {
            const double previous_f = frequencies[static_cast<std::size_t>(i - 1)];
            start *= linear_gain(previous_f) / linear_gain(f);
            const auto& previous = checkpoint.rows.back();
            const std::complex<double> measured =
                previous.values[1].amplitude / previous.values[0].amplitude;
            predicted = driven_mode.predict(measured, previous_f, f);
            if (predicted) {
                start = checkpoint.next_amplitude * std::abs(measured) / std::abs(*predicted);
            }
            using Start = CampaignSpec::PointStart;
            if (campaign.point_start == Start::linear_steady_state) {
                specimen.start_from_linear_steady_state(start, 0.0);
            } else if (campaign.point_start == Start::equivalent_steady_state && predicted) {
                const auto linear = structure::modal_accelerance(
                    prepared.estimate_model, prepared.estimate_basis, campaign.control_point,
                    direction, prepared.structure.excitation.point, direction, f);
                specimen.start_from_linear_steady_state(start, 0.0, *predicted / linear);
            }
        }
        report_start(shared, sweep, i, f);
        control::AmplitudeController controller(controller_options);
        controller.set_start_amplitude(start);
        plant.begin_point();
        const control::PointResult result = controller.run_point(plant, f, target_rms);
        const WindowChannels window = plant.window(result.window_begin, result.window_end);

        identification::PointRow row;
        row.arrangement = prepared.arrangement.name;
        row.level_g = sweep.level_g;
        row.frequency_hz = f;
        row.status = std::string(control::to_string(result.status));
        for (std::size_t c = 0; c < window.rms.size(); ++c) {
            row.values.push_back({window.rms[c], window.fundamental[c]});
        }
        if (series_samples > 0) {
            row.series = write_series(out_dir, sweep.key, i, specimen, plant, result);
        }
        checkpoint.rows.push_back(row);
        checkpoint.control_log.push_back(control_log_line(sweep, result));
        checkpoint.config_hash = shared.config_hash;
        checkpoint.points_done = i + 1;
        checkpoint.next_amplitude = result.amplitude_final;
        checkpoint.state = specimen.state();
        const std::string text = serialize_checkpoint(checkpoint);
        write_file_atomically(checkpoint_file, text);
        checkpoint = parse_checkpoint(text, checkpoint_file.string());
        report_progress(shared, sweep, f, result);
    }
    return checkpoint;
}

/// Refuses to resume from checkpoints another config wrote: they would be taken as this
/// config's results.
void refuse_foreign_checkpoints(const fs::path& out_dir, const std::string& hash) {
    const fs::path dir = out_dir / "checkpoints";
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.is_regular_file() && entry.path().extension() == ".txt") {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    std::vector<config::ConfigError> problems;
    for (const auto& file : files) {
        const std::string found = checkpoint_config_hash(read_text_file(file));
        if (found == hash) continue;
        config::ConfigError e;
        e.file = file.string();
        e.key_path = "config_hash";
        e.value = found.empty() ? "(none: an older checkpoint format)" : "\"" + found + "\"";
        e.constraint = "was written by another config; this config's hash is \"" + hash + "\"";
        e.meaning = "nothing was simulated: run again with --restart to discard " +
                    out_dir.string() + "'s checkpoints and settled beds, or give another --out";
        problems.push_back(std::move(e));
    }
    if (!problems.empty()) throw config::ConfigException(std::move(problems));
}

std::string sweep_key(const std::string& arrangement, double level_g) {
    std::string key = arrangement + "_" + number_text(level_g) + "g";
    std::replace_if(
        key.begin(), key.end(),
        [](char c) { return !(std::isalnum(c) || c == '-' || c == '.' || c == '_'); }, '_');
    return key;
}

}  // namespace

structure::StructureSpec arrangement_structure(const CampaignConfig& config,
                                               const ArrangementSpec& arrangement,
                                               bool all_particles_rigid) {
    structure::StructureSpec spec = config.structure;
    spec.beam = spec.beam.resolved();  // masses at named points placed there
    spec.gravity_m_s2 = arrangement_gravity(arrangement);
    for (const auto& d : config.campaign.dampers) {
        const DamperMounting mounting = damper_mounting(arrangement, d);
        if (!d.enclosure_mass.empty()) {
            // The enclosure's mass turns and moves with the DEM enclosure.
            for (auto& m : spec.beam.masses) {
                if (m.name == d.enclosure_mass &&
                    m.x_m == point_position_m(config.structure, d.point)) {
                    m = mounted_enclosure_mass(m, d, mounting);
                }
            }
        }
        if (arrangement.block_mass_kg > 0.0) {
            add_mass(spec, d.point, d.name + " block", arrangement.block_mass_kg,
                     mounting.block_cg_m);
        }
        if (all_particles_rigid || d.model == DamperSpec::Model::rigid) {
            const double mass = particle_mass_kg(d, config.campaign.seed);
            const Eigen::Vector3d centre =
                mounting.from_enclosure(Eigen::Vector3d(0.0, 0.0, 0.5 * bed_depth_m(d, mass)));
            add_mass(spec, d.point, d.name + " particles (rigid)", mass, centre);
        }
    }
    return spec;
}

CampaignSummary run_campaign(const CampaignConfig& config, const CampaignRunOptions& options) {
    const auto started = std::chrono::steady_clock::now();
    const CampaignSpec& campaign = config.campaign;
    std::vector<config::ConfigError> problems;
    if (campaign.levels_g.empty()) {
        problems.push_back({config.source, 0, 0, "campaign.levels_g", "", "is required",
                            "target RMS levels [g]: a campaign needs at least one"});
    }
    const std::vector<ArrangementSpec> arrangements = campaign.selected_arrangements();
    if (arrangements.empty()) {
        problems.push_back({config.source, 0, 0, "arrangements", "", "is required",
                            "at least one [arrangements.NAME] table"});
    }
    if (!problems.empty()) {
        throw config::ConfigException(problems);
    }
    const std::string hash = config_hash(config);
    if (options.restart) {
        // Everything computed for another config, or for this one from the start.
        for (const char* dir : {"checkpoints", "settled", "series"}) {
            fs::remove_all(options.out_dir / dir);
        }
    } else {
        refuse_foreign_checkpoints(options.out_dir, hash);
    }

    std::vector<PreparedArrangement> prepared;
    for (const auto& a : arrangements) {
        prepared.push_back(prepare(config, a));
    }
    std::vector<Sweep> sweeps;
    for (const auto& p : prepared) {
        for (double level : campaign.levels_g) {
            sweeps.push_back({&p, level, sweep_key(p.arrangement.name, level)});
        }
    }
    fs::create_directories(options.out_dir);

    Shared shared;
    shared.config = &config;
    shared.options = &options;
    shared.start = started;
    shared.config_hash = hash;
    for (const auto& s : sweeps) {
        shared.points_total += static_cast<int>(s.prepared->frequencies_hz.size());
    }
    if (options.progress != nullptr) {
        *options.progress << "campaign " << config.name << ": " << sweeps.size() << " sweeps, "
                          << shared.points_total << " points into " << options.out_dir.string()
                          << '\n';
    }

    std::vector<SweepCheckpoint> results(sweeps.size());
    std::vector<std::vector<std::string>> logs(sweeps.size());
    std::vector<std::exception_ptr> errors(sweeps.size());
    const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
    // Sweeps are independent: each owns its specimen and checkpoint, so the numbers are the
    // same whatever the thread count. Eigen would split large products over OpenMP threads
    // when a sweep runs alone (one thread in the region) and not when it shares the region,
    // changing their blocking and so their rounding: it runs single-threaded here. No
    // exception leaves the parallel region.
    const int eigen_threads = Eigen::nbThreads();
    Eigen::setNbThreads(1);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (std::size_t i = 0; i < sweeps.size(); ++i) {
        try {
            results[i] = run_sweep(sweeps[i], shared, logs[i]);
        } catch (...) {
            errors[i] = std::current_exception();
        }
    }
    Eigen::setNbThreads(eigen_threads);
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);
    }

    CampaignSummary summary;
    summary.points = shared.points_total;
    summary.resumed_points = shared.points_total - shared.points_simulated.load();
    summary.periods_simulated = shared.periods.load();

    CampaignOutput output;
    output.config = &config;
    output.options = &options;
    output.channel_points.push_back(campaign.control_point);
    for (const auto& p : campaign.response_points) {
        if (p != campaign.control_point) output.channel_points.push_back(p);
    }
    for (std::size_t i = 0; i < sweeps.size(); ++i) {
        SweepRecord record;
        record.key = sweeps[i].key;
        record.first_mode_hz = sweeps[i].prepared->first_mode_hz;
        record.frequencies_hz = sweeps[i].prepared->frequencies_hz;
        record.log = logs[i];
        record.rows = results[i].rows;
        record.control_log = results[i].control_log;
        output.sweeps.push_back(std::move(record));
        for (const auto& row : results[i].rows) {
            summary.converged += row.status == "converged";
            summary.limit_cycle += row.status == "limit-cycle-2";
            summary.closest += row.status == "closest";
        }
    }
    output.threads = threads;
    output.config_hash = hash;
    write_campaign_output(output);
    summary.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return summary;
}

}  // namespace sb::bench

// One sweep: the specimen with its attachments, the controller point by point, checkpoints.
#include "bench/sweep_runner.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "bench/arrangement.hpp"
#include "bench/attachment.hpp"
#include "bench/coupled_specimen.hpp"
#include "bench/driven_mode.hpp"
#include "bench/grid_refinement.hpp"
#include "bench/linear_estimate.hpp"
#include "bench/physics_attachments.hpp"
#include "bench/prediction.hpp"
#include "bench/random_sweep.hpp"
#include "bench/settled_bed.hpp"
#include "bench/specimen_plant.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "bench/transient_run.hpp"
#include "control/controller.hpp"
#include "control/fixed_drive.hpp"
#include "control/update.hpp"
#include "core/significant_text.hpp"
#include "core/units.hpp"
#include "identification/recording_io.hpp"
#include "structure/frf.hpp"

namespace sb::bench {
namespace {

std::string format_duration(double seconds) {
    const long s = std::lround(seconds);
    std::ostringstream out;
    if (s >= 3600) out << s / 3600 << "h";
    if (s >= 60) out << (s % 3600) / 60 << "m";
    out << s % 60 << "s";
    return out.str();
}

std::string control_log_line(const SweepTask& task, const control::PointResult& r) {
    std::string amplitudes;
    for (double a : r.amplitudes_tried) {
        amplitudes += (amplitudes.empty() ? "" : ";") + significant_text(a);
    }
    std::string rms;
    for (double v : r.rms_per_period) {
        rms += (rms.empty() ? "" : ";") + significant_text(v);
    }
    return task.prepared->arrangement.name + "," + significant_text(task.level_g) + "," +
           significant_text(r.frequency_hz) + "," + std::string(control::to_string(r.status)) +
           "," + std::to_string(r.periods_simulated) + "," + std::to_string(r.updates) + "," +
           significant_text(r.amplitude_final) + "," + significant_text(r.rms_final) + "," +
           amplitudes + "," + rms;
}

/// energy.csv rows of a point: per DEM damper, the energies per period over the steady
/// window (bench/campaign_output.cpp writes the header).
std::vector<std::string> energy_lines(const SweepTask& task, double frequency_hz,
                                      const std::vector<std::string>& damper_names,
                                      const std::vector<std::optional<PeriodEnergy>>& energy) {
    std::vector<std::string> lines;
    for (std::size_t d = 0; d < energy.size(); ++d) {
        if (!energy[d]) continue;
        const PeriodEnergy& e = *energy[d];
        std::string line = task.prepared->arrangement.name + "," + significant_text(task.level_g) +
                           "," + significant_text(frequency_hz) + "," + damper_names[d] + "," +
                           std::to_string(task.filling);
        for (double v :
             {e.wall_work_j, e.normal_damping_j, e.friction_j, e.rolling_j, e.kinetic_j}) {
            line += "," + significant_text(v);
        }
        for (double v : e.layer_dissipation_j) line += "," + significant_text(v);
        for (double v : e.layer_kinetic_j) line += "," + significant_text(v);
        lines.push_back(std::move(line));
    }
    return lines;
}

/// The steady window of a point as a time history (series/<key>_<index>.csv).
std::string series_text(const CoupledSpecimen& specimen, const SpecimenPlant& plant,
                        const control::PointResult& result) {
    identification::TimeHistory history;
    history.channels = specimen.channel_names();
    history.columns.resize(history.channels.size());
    const double period_s = 1.0 / specimen.frequency_hz();
    for (int p = result.window_begin; p < result.window_end; ++p) {
        const auto& period = plant.periods()[static_cast<std::size_t>(p)];
        const std::size_t samples = period.series.front().size();
        for (std::size_t k = 0; k < samples; ++k) {
            history.time_s.push_back((p - result.window_begin) * period_s +
                                     (static_cast<double>(k) + 1.0) * period_s /
                                         static_cast<double>(samples));
            for (std::size_t c = 0; c < history.channels.size(); ++c) {
                history.columns[c].push_back(period.series[c][k]);
            }
        }
    }
    return identification::time_history_csv_text(history);
}

/// |control / reference| of a row: the accelerance (or transmissibility) magnitude.
double response_ratio(const identification::PointRow& row) {
    return std::abs(row.values[1].amplitude / row.values[0].amplitude);
}

/// `v` with the 17 significant digits that read back as the same double, and legible.
std::string round_trip_text(double v) {
    std::ostringstream out;
    out << std::setprecision(17) << v;
    return out.str();
}

/// A checkpoint continues only under the numbers it was written with: the same config gives
/// other ones when an automatic choice's rule changed between the two builds.
void check_numerics(const SweepCheckpoint& c, const std::string& name,
                    const std::string& numerics) {
    if (c.numerics == numerics) return;
    throw CheckpointError(name, 0,
                          "was written with the numerics '" + c.numerics +
                              "'; for the same config this shakerbench chooses '" + numerics +
                              "' (an automatic choice's rule changed): --restart discards the "
                              "checkpoints and starts over");
}

/// A checkpoint of this sweep's config (its hash and checksum said so) that still does not fit
/// the sweep was edited or written by a faulty build: refused, never resumed from.
/// `refine_budget`: how many frequencies the grid refinement may add after the planned grid
/// (their rows are checked as the refinement adds them again, in run_sweep).
void check_fits(const SweepCheckpoint& c, const std::string& name, const SweepTask& task,
                int refine_budget, CoupledSpecimen& specimen) {
    const auto refuse = [&](const std::string& why) {
        throw CheckpointError(name, 0, "does not fit its sweep: " + why);
    };
    const auto& grid = task.frequencies_hz;
    const std::size_t most = grid.size() + static_cast<std::size_t>(std::max(0, refine_budget));
    if (static_cast<std::size_t>(c.points_done) > most) {
        refuse(std::to_string(c.points_done) + " points done, the sweep has " +
               std::to_string(grid.size()) +
               (refine_budget > 0 ? " and may add " + std::to_string(refine_budget) : ""));
    }
    const std::size_t channels = specimen.channel_names().size();
    for (std::size_t i = 0; i < c.rows.size(); ++i) {
        const auto& row = c.rows[i];
        // Bitwise: the checkpoint's numbers are exact hexadecimal floats of the plan's.
        if ((i < grid.size() && row.frequency_hz != grid[i]) || row.level_g != task.level_g) {
            refuse("row " + std::to_string(i + 1) + " is not at the sweep's level and frequency");
        }
        if (row.values.size() != channels) {
            refuse("row " + std::to_string(i + 1) + " holds " + std::to_string(row.values.size()) +
                   " channels, the sweep records " + std::to_string(channels));
        }
    }
    if (grid.empty()) return;
    const auto next = static_cast<std::size_t>(c.points_done);
    specimen.set_frequency(next < grid.size() ? grid[next] : c.rows.back().frequency_hz);
    try {
        specimen.restore(c.state);
    } catch (const std::invalid_argument& e) {
        refuse(e.what());
    }
}

}  // namespace

CampaignProgress::CampaignProgress(std::function<void(const std::string&)> sink, int points_total)
    : sink_(std::move(sink)),
      points_total_(points_total),
      start_(std::chrono::steady_clock::now()) {}

void CampaignProgress::point_started(const SweepTask& task, int index, double frequency_hz) {
    if (!sink_) return;
    std::ostringstream out;
    out << "  start " << task.prepared->arrangement.name << ' ' << significant_text(task.level_g)
        << ' ' << task.level_unit << ' ' << std::fixed << std::setprecision(3) << frequency_hz
        << " Hz (";
    const auto planned = static_cast<int>(task.frequencies_hz.size());
    if (index < planned) {
        out << "frequency " << index + 1 << " of " << planned << ")";
    } else {  // beyond the planned grid: a frequency the refinement added near the peak
        out << "added frequency " << index - planned + 1 << ")";
    }
    std::lock_guard<std::mutex> lock(mutex_);
    sink_(out.str());
}

void CampaignProgress::points_resumed(int count) { points_done_ += count; }

void CampaignProgress::points_added(int count) { points_total_ += count; }

void CampaignProgress::note(const std::string& line) {
    if (!sink_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    sink_(line);
}

void CampaignProgress::point_finished(const SweepTask& task, double frequency_hz,
                                      const control::PointResult& result) {
    const int done = ++points_done_;
    const int simulated = ++points_simulated_;
    periods_ += result.periods_simulated;
    if (!sink_) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = elapsed / simulated * (points_total_ - done);
    std::ostringstream out;
    out << '[' << done << '/' << points_total_ << "] " << task.prepared->arrangement.name << ' '
        << significant_text(task.level_g) << ' ' << task.level_unit << ' ' << std::fixed
        << std::setprecision(3) << frequency_hz << " Hz: " << control::to_string(result.status)
        << " after " << result.periods_simulated << " periods (" << result.updates << " updates), "
        << std::setprecision(1) << static_cast<double>(periods_.load()) / std::max(elapsed, 1e-9)
        << " periods/s, ETA " << format_duration(eta);
    std::lock_guard<std::mutex> lock(mutex_);
    sink_(out.str());
}

SweepResult run_sweep(const CampaignConfig& config, const SweepTask& task,
                      const std::string& config_hash, CheckpointStore& store,
                      SweepProgress& progress) {
    const CampaignSpec& campaign = config.campaign;
    const PreparedArrangement& prepared = *task.prepared;
    const Eigen::Vector3d gravity = prepared.structure.gravity_m_s2;
    // The planned grid; refinement may add frequencies at the end.
    std::vector<double> frequencies = task.frequencies_hz;

    SweepResult out;
    out.key = task.key;
    out.arrangement = prepared.arrangement.name;
    out.level_g = task.level_g;
    out.first_mode_hz = prepared.first_mode_hz;
    out.frequencies_hz = frequencies;

    // The attachments at their points: DEM dampers with their settled beds, rigid particles.
    std::vector<Attachment> attachments;
    std::vector<std::string> damper_names;
    const double lowest_hz = *std::min_element(frequencies.begin(), frequencies.end());
    double dt_max = 1.0 / (256.0 * lowest_hz);
    // The numbers this build chooses beyond the config (the checkpoint keeps them: a change
    // of an automatic rule must not continue a sweep begun under the old one).
    std::string numerics;
    const bool energy = campaign.output.energy;
    for (const DamperSpec& damper : campaign.dampers) {
        const DamperMounting mounting = damper_mounting(prepared.arrangement, damper);
        damper_names.push_back(damper.name);
        if (damper.model == DamperSpec::Model::rigid) {
            // Its mass is part of the arrangement's structure (arrangement_structure).
            attachments.push_back({damper.name, damper.point, RigidParticles{}});
            continue;
        }
        if (damper.model == DamperSpec::Model::describing_function) {
            attachments.push_back(describing_function_attachment(config, damper, prepared));
            continue;
        }
        const dem::ExcitationContact chosen = damper.excitation_contact(
            std::sqrt(2.0) *
                g_to_m_s2(damper.contact.sized_for_g(task.level_g, task.stiffness_level_g)),
            prepared.first_mode_hz);
        dt_max = std::min(dt_max, chosen.time_step_s);
        numerics += damper.name + ".normal_stiffness=" + round_trip_text(chosen.stiffness) + " " +
                    damper.name + ".time_step_s=" + round_trip_text(chosen.time_step_s) + " ";
        out.settings.push_back(damper.name + ": " + chosen.log);
        const dem::ParticleSet bed =
            settled_bed(damper, chosen.stiffness, mounting.rotation, gravity, task.seed, &store,
                        task.key + "_" + damper.name);
        dem::SolverOptions options = damper.solver_options(chosen.stiffness);
        options.gravity_m_s2 = gravity;
        // The campaign measures damping from the FRF; the ledger is kept when asked for.
        options.track_energy = energy;
        options.energy_layers = energy ? campaign.output.energy_layers : 0;
        attachments.push_back({damper.name, damper.point,
                               DemDamper(options, mounting.rotation, mounting.origin_m, bed,
                                         prepared.model.point(damper.point).position_m)});
    }

    // The catalogue physics at points of their own (after the dampers, whose indices the
    // checkpoints and the energy ledger use).
    for (auto& strip : physics_attachments(config, prepared)) {
        damper_names.push_back(strip.name);
        attachments.push_back(std::move(strip));
    }

    // A run from rest records its time histories always.
    const int series_samples = campaign.output.series || campaign.transient.on()
                                   ? campaign.output.series_samples_per_period
                                   : 0;
    CoupledSpecimen specimen(prepared.model, prepared.basis, prepared.structure.excitation,
                             std::move(attachments),
                             recorded_channels(campaign, prepared.structure.excitation), dt_max,
                             std::max(series_samples, 1));
    specimen.set_start_model(prepared.estimate_model, prepared.estimate_basis);
    // Locked particles are rigid mass of the structure until their release.
    specimen.carry_held_particles();
    const ShakerSpec& shaker = config.physics.shaker;
    if (shaker.on()) specimen.drive_through(shaker);
    // The force per unit drive: 1, or through a shaker its blocked force per volt (the linear
    // models below know forces; the back-EMF they lack is what the driven mode learns).
    const auto force_per_drive = [&](double f) {
        return shaker.on() ? blocked_force_per_volt(shaker, f) : std::complex<double>(1.0);
    };
    numerics += "step_limit_s=" + round_trip_text(dt_max);
    SpecimenPlant plant(specimen, series_samples, campaign.scale_response_on_update, energy);
    // A fixed drive: the sweep's level is its amplitude (no controller, no target).
    const bool fixed = campaign.drive.fixed();
    const auto fixed_amplitude = [&](double f) {
        return campaign.drive.excitation_amplitude(task.level_g, f);
    };
    const double target_rms = g_to_m_s2(task.level_g);
    const auto linear_gain = [&](double f) {
        return linear_response_per_unit_input(prepared.estimate_model, prepared.estimate_basis,
                                              prepared.structure.excitation, campaign.control_point,
                                              f) *
               std::abs(force_per_drive(f));
    };
    const Eigen::Vector3d direction = prepared.structure.excitation.direction.normalized();
    const DrivenMode driven_mode(prepared.estimate_model, prepared.estimate_basis,
                                 prepared.structure.excitation, campaign.control_point,
                                 prepared.first_mode_hz);

    const std::string checkpoint_name = store.checkpoint_name(task.key);
    SweepCheckpoint checkpoint;
    const auto save = [&] {
        checkpoint.config_hash = config_hash;
        checkpoint.numerics = numerics;
        const std::string text = serialize_checkpoint(checkpoint);
        store.save_checkpoint(task.key, text);
        // Every point starts from the text, as a resumed one does.
        checkpoint = parse_checkpoint(text, checkpoint_name);
    };
    if (campaign.transient.on()) {
        if (const auto text = store.load_checkpoint(task.key)) {
            checkpoint = parse_checkpoint(*text, checkpoint_name);
            check_numerics(checkpoint, checkpoint_name, numerics);
            if (!checkpoint.rows.empty()) {
                throw CheckpointError(checkpoint_name, 0,
                                      "holds stepped-sine points, not a run from rest");
            }
            progress.note(task.key + ": run from rest resumed after " +
                          std::to_string(checkpoint.transient_periods) + " periods");
        }
        TransientDrive drive;
        drive.frequency_hz = frequencies.front();
        drive.amplitude = fixed_amplitude(drive.frequency_hz);
        drive.periods =
            static_cast<int>(std::llround(campaign.transient.duration_s * drive.frequency_hz));
        drive.checkpoint_periods = campaign.transient.checkpoint_periods;
        for (auto& line : release_events(campaign)) out.settings.push_back(std::move(line));
        const std::string name = prepared.arrangement.name + " " + significant_text(task.level_g) +
                                 " " + task.level_unit;
        progress.point_started(task, 0, drive.frequency_hz);
        run_transient(specimen, plant, drive, checkpoint, save, [&](int periods) {
            progress.note(name + ": run from rest, " +
                          significant_text(periods / drive.frequency_hz) + " of " +
                          significant_text(drive.periods / drive.frequency_hz) + " s");
        });
        out.periods_simulated = drive.periods;
        out.transient_channels = specimen.channel_names();
        out.transient_series = checkpoint.transient_series;
        out.transient_envelope = checkpoint.transient_envelope;
        return out;
    }
    if (campaign.random.on()) {
        if (const auto text = store.load_checkpoint(task.key)) {
            checkpoint = parse_checkpoint(*text, checkpoint_name);
            check_numerics(checkpoint, checkpoint_name, numerics);
            if (!checkpoint.random) {
                throw CheckpointError(checkpoint_name, 0, "holds no random test");
            }
            progress.note(task.key + ": random test resumed");
        }
        RandomSweep sweep;
        sweep.spec = &campaign.random;
        sweep.task = &task;
        sweep.arrangement = prepared.arrangement.name;
        if (!fixed) sweep.target_rms_m_s2 = target_rms;
        sweep.linear_gain = linear_gain;
        run_random_sweep(specimen, sweep, checkpoint, save, progress, out);
        return out;
    }
    if (const auto text = store.load_checkpoint(task.key)) {
        checkpoint = parse_checkpoint(*text, checkpoint_name);
        check_numerics(checkpoint, checkpoint_name, numerics);
        check_fits(checkpoint, checkpoint_name, task,
                   task.refine ? campaign.frequencies.refine_points : 0, specimen);
        out.resumed_points = checkpoint.points_done;
        progress.points_resumed(checkpoint.points_done);
    } else {
        // First point: the linear steady state at the first frequency, settled particles.
        const double start = fixed ? fixed_amplitude(frequencies.front())
                             : campaign.controller.initial_amplitude
                                 ? *campaign.controller.initial_amplitude
                                 : std::sqrt(2.0) * target_rms / linear_gain(frequencies.front());
        specimen.set_frequency(frequencies.front());
        specimen.start_from_linear_steady_state(start, 0.0);
        checkpoint.next_amplitude = start;
        checkpoint.state = specimen.state();
        save();
    }

    const bool vtk_all = campaign.output.vtk == OutputSpec::Vtk::all;
    const bool vtk_resonance = campaign.output.vtk == OutputSpec::Vtk::resonance;
    double largest_response = 0.0;
    for (const auto& row : checkpoint.rows)
        largest_response = std::max(largest_response, response_ratio(row));

    const bool base = prepared.structure.excitation.kind == structure::ExcitationSpec::Kind::base;
    const int budget = task.refine ? campaign.frequencies.refine_points : 0;
    int added = 0;
    for (;;) {
        for (int i = checkpoint.points_done; i < static_cast<int>(frequencies.size()); ++i) {
            const double f = frequencies[static_cast<std::size_t>(i)];
            specimen.set_frequency(f);
            specimen.restore(checkpoint.state);
            // Warm start: the previous amplitude scaled by the gain ratio the previous point's
            // equivalent mode predicts (the linear model's ratio when there is none).
            double start = checkpoint.next_amplitude;
            if (i > 0) {
                const double previous_f = frequencies[static_cast<std::size_t>(i - 1)];
                start *= linear_gain(previous_f) / linear_gain(f);
                const auto& previous = checkpoint.rows.back();
                // Per unit force: the driven mode is the structure's.
                const std::complex<double> measured = previous.values[1].amplitude /
                                                      previous.values[0].amplitude /
                                                      force_per_drive(previous_f);
                const auto predicted = driven_mode.predict(measured, previous_f, f);
                if (predicted) {
                    start = checkpoint.next_amplitude * std::abs(measured) /
                            std::abs(*predicted * force_per_drive(f)) *
                            std::abs(force_per_drive(previous_f));
                }
                if (fixed) start = fixed_amplitude(f);
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
            progress.point_started(task, i, f);
            plant.begin_point();
            const control::PointResult result = [&] {
                if (fixed) return control::run_fixed_point(plant, f, start, campaign.controller);
                control::AmplitudeController controller(campaign.controller);
                controller.set_start_amplitude(start);
                return controller.run_point(plant, f, target_rms);
            }();
            const WindowChannels window = plant.window(result.window_begin, result.window_end);

            identification::PointRow row;
            row.arrangement = prepared.arrangement.name;
            row.level_g = task.level_g;
            row.frequency_hz = f;
            row.status = std::string(control::to_string(result.status));
            for (std::size_t c = 0; c < window.rms.size(); ++c) {
                identification::ChannelValue v;
                v.rms = window.rms[c];
                v.amplitude = window.fundamental[c];
                v.h2_ratio = window.h2_ratio[c];
                v.h3_ratio = window.h3_ratio[c];
                row.values.push_back(v);
            }
            if (series_samples > 0) {
                row.series = "series/" + task.key + "_" + std::to_string(i) + ".csv";
                store.save_file(row.series, series_text(specimen, plant, result));
            }
            const bool peak = response_ratio(row) > largest_response;
            largest_response = std::max(largest_response, response_ratio(row));
            if (vtk_all || (vtk_resonance && peak)) {
                for (std::size_t d = 0; d < specimen.attachments().size(); ++d) {
                    const auto text = bed_vtk_text(specimen.attachments()[d]);
                    if (!text) continue;
                    store.save_file("vtk/" + task.key + "_" +
                                        (vtk_all ? std::to_string(i) : std::string("resonance")) +
                                        "_" + damper_names[d] + ".vtk",
                                    *text);
                }
            }
            checkpoint.rows.push_back(row);
            checkpoint.control_log.push_back(control_log_line(task, result));
            if (energy) {
                for (auto& line :
                     energy_lines(task, f, damper_names,
                                  plant.window_energy(result.window_begin, result.window_end))) {
                    checkpoint.energy_log.push_back(std::move(line));
                }
            }
            checkpoint.points_done = i + 1;
            // The next point starts from the drive this one would still have needed for the
            // target, as the controller's own warm start does (docs/control.md).
            checkpoint.next_amplitude =
                fixed ? result.amplitude_final
                      : control::warm_start_amplitude(result.amplitude_final, result.rms_final,
                                                      target_rms, campaign.controller);
            checkpoint.state = specimen.state();
            save();
            out.periods_simulated += result.periods_simulated;
            progress.point_finished(task, f, result);
        }
        // Refinement: the points of the grid so far (a resumed sweep has the same rows, so it
        // adds the same frequencies) decide whether and where to add.
        const std::vector<identification::PointRow> so_far(
            checkpoint.rows.begin(),
            checkpoint.rows.begin() + static_cast<std::ptrdiff_t>(frequencies.size()));
        const GridVerdict verdict =
            assess_grid(so_far, base, static_cast<std::size_t>(std::max(0, budget - added)));
        if (verdict.resolved || !task.refine) break;
        if (verdict.add_hz.empty()) {
            const std::string line = prepared.arrangement.name + " " +
                                     significant_text(task.level_g) + " " + task.level_unit +
                                     ": estimates unresolved after " + std::to_string(added) +
                                     " added frequencies (" + verdict.unresolved_reason + ")";
            out.settings.push_back(line);
            progress.note(line);
            break;
        }
        // A resumed sweep holds the rows of the frequencies added before: they must be these.
        for (std::size_t i = frequencies.size(), k = 0;
             k < verdict.add_hz.size() && i < checkpoint.rows.size(); ++i, ++k) {
            if (checkpoint.rows[i].frequency_hz != verdict.add_hz[k]) {
                throw CheckpointError(checkpoint_name, 0,
                                      "does not fit its sweep: row " + std::to_string(i + 1) +
                                          " is not at the frequency the grid refinement adds");
            }
        }
        frequencies.insert(frequencies.end(), verdict.add_hz.begin(), verdict.add_hz.end());
        added += static_cast<int>(verdict.add_hz.size());
        progress.points_added(static_cast<int>(verdict.add_hz.size()));
    }
    if (added > 0) {
        out.settings.push_back("grid refined: " + std::to_string(added) + " frequencies added");
    }
    out.frequencies_hz = frequencies;
    out.rows = checkpoint.rows;
    // The checkpoint holds one filling's rows and does not repeat its number.
    for (auto& row : out.rows) row.filling = task.filling;
    out.control_log = checkpoint.control_log;
    out.energy_log = checkpoint.energy_log;
    return out;
}

}  // namespace sb::bench

// The characterisation of a config's dampers over its grid: planned once, each run (a grid
// point on one filling) independent, run on this process's threads or handed to other
// processes (MPI ranks) one run at a time.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "bench/arrangement.hpp"
#include "bench/attachment.hpp"
#include "bench/characterization.hpp"
#include "bench/characterization_progress.hpp"
#include "bench/resolved_config.hpp"
#include "bench/settled_bed.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "config/errors.hpp"
#include "config/write.hpp"
#include "core/exact_text.hpp"
#include "core/significant_text.hpp"
#include "core/units.hpp"

namespace sb::bench {
namespace {

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

}  // namespace

/// What characterize() runs: one bed per arrangement, damper, level and seed (the contact
/// stiffness chosen as the campaign chooses it; beds with the same stiffness and seed are one
/// bed); one run per grid point and seed. Every
/// process that plans the same config and options gets the same beds and runs in the same
/// order.
struct CharacterizationGrid {
    struct Bed {
        std::size_t arrangement = 0;
        const DamperSpec* damper = nullptr;
        double level_g = 0.0;
        std::uint64_t seed = 0;
        dem::ExcitationContact contact;
        /// The store's key: arrangement, damper, filling and stiffness (not the level: with
        /// one stiffness for the campaign every level shakes the same bed).
        std::string key;
        std::size_t same_as = 0;  ///< the first bed with this key: it is settled once
    };
    struct Run {
        std::size_t bed = 0;
        double frequency_hz = 0.0;
        ApparentMassPoint result;
        std::string key;  ///< the store's key
        /// The key of the same run measured with CharacterizeOptions::stored_energy_layers
        /// (empty when none): a stored one serves, its energy left out.
        std::string key_with_energy;
        bool stored = false;  ///< read back from the store
        /// Where an interrupted run stands, read back from the store (released once the run
        /// has continued it).
        std::optional<RunProgress> progress;
    };
    std::vector<double> levels;
    std::vector<const DamperSpec*> dampers;
    CampaignPlan plan;
    std::vector<Bed> beds;
    std::vector<std::vector<double>> grids;  // per arrangement
    std::vector<Eigen::Vector3d> rotations;  // per arrangement and damper
    std::vector<Run> runs;

    [[nodiscard]] std::size_t damper_index(const DamperSpec* d) const {
        return static_cast<std::size_t>(std::find(dampers.begin(), dampers.end(), d) -
                                        dampers.begin());
    }
};

namespace {

/// The largest time step of the runs of `bed`: the contact's, or a 256th of the period of
/// the grid's lowest frequency (every run of an arrangement takes the same).
double step_limit_s(const CharacterizationGrid& grid, const CharacterizationGrid::Bed& bed) {
    return std::min(bed.contact.time_step_s, 1.0 / (256.0 * grid.grids[bed.arrangement].front()));
}

/// The store's keys: a readable part (where, which level, frequency and filling) and a hash
/// of every number the result depends on beyond the config, which the store's own hash
/// covers. A key names the same numbers whatever else the grid holds, so a characterisation
/// extended by levels, frequencies or fillings finds the runs it shares with an earlier one.
void assign_keys(CharacterizationGrid& grid, const CharacterizeOptions& options) {
    std::map<std::string, std::size_t> first_bed;
    for (std::size_t b = 0; b < grid.beds.size(); ++b) {
        auto& bed = grid.beds[b];
        const std::string where =
            grid.plan.arrangements[bed.arrangement].arrangement.name + "_" + bed.damper->name;
        bed.key = where + "_seed" + std::to_string(bed.seed) + "_" +
                  config::fnv1a_hex(exact_text(bed.contact.stiffness)).substr(0, 8);
        bed.same_as = first_bed.emplace(bed.key, b).first->second;
    }
    const SteadyStateOptions& st = options.steady;
    const auto common = [&](int energy_layers) {
        std::ostringstream out;
        out << st.transient_periods << ' ' << st.window_periods << ' ' << exact_text(st.tolerance)
            << ' ' << st.max_periods << ' ' << exact_text(st.energy_tolerance) << ' '
            << energy_layers << ' ' << (options.rotation ? 1 : 0);
        return out.str();
    };
    const bool other_energy = options.energy_layers == 0 && options.stored_energy_layers > 0;
    for (auto& run : grid.runs) {
        const auto& bed = grid.beds[run.bed];
        const Eigen::Vector3d& turn =
            grid.rotations[bed.arrangement * grid.dampers.size() + grid.damper_index(bed.damper)];
        std::ostringstream numbers;
        numbers << ' ' << exact_text(bed.level_g) << ' ' << exact_text(run.frequency_hz) << ' '
                << exact_text(bed.contact.stiffness) << ' ' << exact_text(step_limit_s(grid, bed))
                << ' ' << exact_text(turn.x()) << ' ' << exact_text(turn.y()) << ' '
                << exact_text(turn.z()) << ' ' << bed.seed;
        const std::string where = grid.plan.arrangements[bed.arrangement].arrangement.name + "_" +
                                  bed.damper->name + "_" + significant_text(bed.level_g, 6) + "g_" +
                                  significant_text(run.frequency_hz, 6) + "Hz_seed" +
                                  std::to_string(bed.seed) + "_";
        run.key = where + config::fnv1a_hex(common(options.energy_layers) + numbers.str());
        if (other_energy) {
            run.key_with_energy =
                where + config::fnv1a_hex(common(options.stored_energy_layers) + numbers.str());
        }
    }
}

CharacterizationGrid plan_grid(const CampaignConfig& config, const CharacterizeOptions& options) {
    CharacterizationGrid grid_plan;
    const CampaignSpec& campaign = config.campaign;
    std::vector<double>& levels = grid_plan.levels;
    levels = options.levels_g.empty() ? campaign.levels_g : options.levels_g;
    std::vector<const DamperSpec*>& dampers = grid_plan.dampers;
    for (const auto& d : campaign.dampers) {
        if (d.model != DamperSpec::Model::rigid) dampers.push_back(&d);
    }
    std::vector<config::ConfigError> problems;
    if (levels.empty()) {
        problems.push_back(config_problem(config, "campaign.levels_g", "", "is required",
                                          "levels to characterise [g] (or --levels-g)"));
    }
    for (double l : levels) {
        if (!(l > 0.0 && std::isfinite(l))) {
            problems.push_back(config_problem(config, "levels_g", significant_text(l, 6),
                                              "must be > 0", "level to characterise [g]"));
        }
    }
    for (double f : options.frequencies_hz) {
        if (!(f > 0.0 && std::isfinite(f))) {
            problems.push_back(config_problem(config, "frequencies_hz", significant_text(f, 6),
                                              "must be > 0", "frequency to characterise [Hz]"));
        }
    }
    // A value given twice would be run twice and its row would average both runs' fillings
    // as if they were twice as many.
    for (std::size_t i = 0; i < levels.size(); ++i) {
        if (std::find(levels.begin(), levels.begin() + static_cast<std::ptrdiff_t>(i), levels[i]) !=
            levels.begin() + static_cast<std::ptrdiff_t>(i)) {
            problems.push_back(config_problem(config, "levels_g", significant_text(levels[i], 6),
                                              "is given twice", "level to characterise [g]"));
        }
    }
    const auto& fs = options.frequencies_hz;
    for (std::size_t i = 0; i < fs.size(); ++i) {
        if (std::find(fs.begin(), fs.begin() + static_cast<std::ptrdiff_t>(i), fs[i]) !=
            fs.begin() + static_cast<std::ptrdiff_t>(i)) {
            problems.push_back(config_problem(config, "frequencies_hz", significant_text(fs[i], 6),
                                              "is given twice", "frequency to characterise [Hz]"));
        }
    }
    if (dampers.empty()) {
        problems.push_back(config_problem(config, "dampers", "",
                                          "needs a damper whose model is not rigid",
                                          "the dampers to characterise"));
    }
    if (options.seeds < 1) {
        problems.push_back(config_problem(config, "seeds", std::to_string(options.seeds),
                                          "must be >= 1", "fillings per grid point"));
    }
    if (options.energy_layers < 0) {
        problems.push_back(config_problem(config, "output.energy_layers",
                                          std::to_string(options.energy_layers), "must be >= 0",
                                          "horizontal layers of the energy per layer"));
    }
    for (const auto& v : options.steady.validate()) {
        problems.push_back(config_problem(config, v.key, v.value, v.constraint, v.meaning));
    }
    if (!problems.empty()) throw config::ConfigException(problems);

    grid_plan.plan = plan_campaign(config, Selection::of(config, {}, {levels.front()}));
    const CampaignPlan& plan = grid_plan.plan;
    const Eigen::Vector3d direction = config.structure.excitation.direction.normalized();

    auto& beds = grid_plan.beds;
    auto& grids = grid_plan.grids;
    auto& rotations = grid_plan.rotations;
    // An automatic stiffness sized for the campaign (contact.stiffness_for = "campaign", the
    // default) is the campaign's: sized for its largest level (or the largest RMS its fixed
    // drive gives, campaign_plan.cpp), and for the largest characterised level if that is
    // larger, so that every level runs the numerics a sweep of `shakerbench run` runs.
    double largest_g = *std::max_element(levels.begin(), levels.end());
    for (const auto& task : plan.tasks) largest_g = std::max(largest_g, task.stiffness_level_g);
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
                // One contact per level (or one for all): every filling runs the same law
                // and step.
                const dem::ExcitationContact contact = damper->excitation_contact(
                    std::sqrt(2.0) * g_to_m_s2(damper->contact.sized_for_g(level, largest_g)),
                    prepared.first_mode_hz);
                for (int s = 0; s < options.seeds; ++s) {
                    CharacterizationGrid::Bed bed;
                    bed.arrangement = a;
                    bed.damper = damper;
                    bed.level_g = level;
                    bed.seed = campaign.seed + static_cast<std::uint64_t>(s);
                    bed.contact = contact;
                    beds.push_back(std::move(bed));
                }
            }
        }
    }
    for (std::size_t b = 0; b < beds.size(); ++b) {
        for (double f : grids[beds[b].arrangement]) {
            grid_plan.runs.push_back({b, f, {}, {}, {}, false, std::nullopt});
        }
    }
    assign_keys(grid_plan, options);
    return grid_plan;
}

/// The settled bed of bed `b` of the grid, by the campaign's procedure (a seed and a stiffness
/// give the campaign's bed), from the store when it holds it; counts the beds settled here.
dem::ParticleSet settle(const CharacterizationGrid& grid, std::size_t b, CheckpointStore* store,
                        int& settled_here) {
    const auto& bed = grid.beds[b];
    const PreparedArrangement& prepared = grid.plan.arrangements[bed.arrangement];
    const DamperMounting mounting = damper_mounting(prepared.arrangement, *bed.damper);
    bool settled = false;
    dem::ParticleSet particles =
        settled_bed(*bed.damper, bed.contact.stiffness, mounting.rotation,
                    prepared.structure.gravity_m_s2, bed.seed, store, bed.key, &settled);
    if (settled) ++settled_here;
    return particles;
}

/// Run `r` of the grid on its settled bed; `after_period` and `checkpoints` as
/// measure_apparent_mass's.
ApparentMassPoint measure(const CampaignConfig& config, const CharacterizeOptions& options,
                          const CharacterizationGrid& grid, std::size_t r,
                          const dem::ParticleSet& particles,
                          const std::function<void(int)>& after_period = {},
                          const RunCheckpoints& checkpoints = {}) {
    const Eigen::Vector3d direction = config.structure.excitation.direction.normalized();
    const auto& run = grid.runs[r];
    const auto& bed = grid.beds[run.bed];
    const PreparedArrangement& prepared = grid.plan.arrangements[bed.arrangement];
    const DamperMounting mounting = damper_mounting(prepared.arrangement, *bed.damper);
    EnclosureSetup setup;
    setup.options = bed.damper->solver_options(bed.contact.stiffness);
    setup.options.gravity_m_s2 = prepared.structure.gravity_m_s2;
    setup.mount_rotation = mounting.rotation;
    setup.offset_m = mounting.origin_m;
    setup.bed = particles;
    setup.dt_max_s = step_limit_s(grid, bed);
    setup.options.energy_layers = options.energy_layers;
    setup.bed_energy = options.energy_layers > 0;
    HarmonicDrive drive;
    drive.direction = direction;
    drive.rotation_per_translation_rad_m =
        grid.rotations[bed.arrangement * grid.dampers.size() + grid.damper_index(bed.damper)];
    drive.acceleration_m_s2 = std::sqrt(2.0) * g_to_m_s2(bed.level_g);
    drive.frequency_hz = run.frequency_hz;
    return measure_apparent_mass(setup, drive, options.steady, after_period, checkpoints);
}

/// A list as its length and its values.
void write_list(std::ostream& out, const std::vector<double>& values) {
    out << ' ' << values.size();
    for (double v : values) out << ' ' << exact_text(v);
}

std::vector<double> read_list(std::istream& in) {
    std::size_t count = 0;
    in >> count;
    std::vector<double> values;
    std::string field;
    for (std::size_t k = 0; k < count && in >> field; ++k) {
        values.push_back(std::strtod(field.c_str(), nullptr));
    }
    return values;
}

/// A run's result as exact text (hexadecimal floats), and back.
std::string point_text(const ApparentMassPoint& m) {
    std::ostringstream out;
    for (const double v : {m.apparent_mass_kg.real(), m.apparent_mass_kg.imag(), m.power_w,
                           m.h2_ratio, m.h3_ratio, m.kinetic_j, m.bed_mass_kg}) {
        out << exact_text(v) << ' ';
    }
    out << m.periods << ' ' << (m.settled ? 1 : 0) << ' ' << m.steps_per_period;
    if (m.energy) {
        const BedEnergy& e = *m.energy;
        out << " energy";
        for (double v : {e.normal_damping_w, e.friction_w, e.rolling_w, e.mechanical_change_w,
                         e.kinetic_lab_j, e.bin_hz})
            out << ' ' << exact_text(v);
        write_list(out, e.layer_power_w);
        write_list(out, e.kinetic_amplitude_j);
        write_list(out, e.dissipation_amplitude_w);
        write_list(out, e.layer_kinetic_j);
    }
    return out.str();
}

ApparentMassPoint parse_point(const std::string& text) {
    std::istringstream in(text);
    std::string field[7];
    ApparentMassPoint m;
    int settled = 0;
    for (auto& f : field) in >> f;
    in >> m.periods >> settled >> m.steps_per_period;
    if (!in) throw std::runtime_error("a characterisation run's result did not read: " + text);
    const auto number = [](const std::string& f) { return std::strtod(f.c_str(), nullptr); };
    m.apparent_mass_kg = {number(field[0]), number(field[1])};
    m.power_w = number(field[2]);
    m.h2_ratio = number(field[3]);
    m.h3_ratio = number(field[4]);
    m.kinetic_j = number(field[5]);
    m.bed_mass_kg = number(field[6]);
    m.settled = settled != 0;
    if (std::string tag; in >> tag) {
        std::string e[6];
        for (auto& f : e) in >> f;
        BedEnergy energy;
        energy.normal_damping_w = number(e[0]);
        energy.friction_w = number(e[1]);
        energy.rolling_w = number(e[2]);
        energy.mechanical_change_w = number(e[3]);
        energy.kinetic_lab_j = number(e[4]);
        energy.bin_hz = number(e[5]);
        energy.layer_power_w = read_list(in);
        energy.kinetic_amplitude_j = read_list(in);
        energy.dissipation_amplitude_w = read_list(in);
        // Results stored before the layers' agitation was measured end here.
        if (in >> std::ws; !in.eof()) energy.layer_kinetic_j = read_list(in);
        if (tag != "energy" || in.fail()) {
            throw std::runtime_error("a characterisation run's energy did not read: " + text);
        }
        m.energy = std::move(energy);
    }
    return m;
}

/// Where run `r` is: arrangement, damper, level, frequency and filling.
std::string run_name(const CharacterizationGrid& grid, std::size_t r) {
    const auto& run = grid.runs[r];
    const auto& bed = grid.beds[run.bed];
    const PreparedArrangement& prepared = grid.plan.arrangements[bed.arrangement];
    return prepared.arrangement.name + " " + bed.damper->name + " " +
           significant_text(bed.level_g, 6) + " g " + significant_text(run.frequency_hz, 6) +
           " Hz seed " + std::to_string(bed.seed);
}

void report(const CharacterizeOptions& options, const CharacterizationGrid& grid, std::size_t r,
            int done) {
    if (!options.progress) return;
    const auto& run = grid.runs[r];
    std::ostringstream line;
    const auto m = run.result.apparent_mass_kg;
    line << '[' << done << '/' << grid.runs.size() << "] " << run_name(grid, r)
         << ": M = " << significant_text(m.real(), 6) << (m.imag() < 0 ? " - " : " + ")
         << significant_text(std::abs(m.imag()), 6)
         << "i kg, P = " << significant_text(run.result.power_w, 6) << " W, " << run.result.periods
         << " periods" << (run.result.settled ? "" : " (not settled)");
    options.progress(line.str());
}

/// A run's result text as the store keeps it: a line, then its checksum line.
std::string sealed(const std::string& point) { return seal_checkpoint(point + '\n'); }

/// Where run `run` saves its progress (every options.checkpoint_interval_s of wall time) and
/// the progress it continues; none without a store.
RunCheckpoints checkpoints_of(const CharacterizeOptions& options,
                              const CharacterizationGrid::Run& run) {
    RunCheckpoints checkpoints;
    CheckpointStore* store = options.store;
    if (store == nullptr) return checkpoints;
    checkpoints.resume = run.progress ? &*run.progress : nullptr;
    using Clock = std::chrono::steady_clock;
    auto last = std::make_shared<Clock::time_point>(Clock::now());
    checkpoints.due = [last, interval = options.checkpoint_interval_s] {
        return std::chrono::duration<double>(Clock::now() - *last).count() >= interval;
    };
    checkpoints.save = [last, store, key = run.key](const RunProgress& progress) {
        store->save_progress(Unfinished::result, key, serialize_run_progress(progress));
        *last = Clock::now();
    };
    return checkpoints;
}

/// Every run not yet in the store on this process's threads: the beds they need settled
/// first (or read from the store), then the runs, each kept in the store as it ends; the
/// numbers depend neither on the thread count nor on the order they finish in. No exception
/// leaves a parallel region.
int run_here(const CampaignConfig& config, const CharacterizeOptions& options,
             CharacterizationGrid& grid) {
    const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
    std::vector<std::size_t> to_run, to_settle;
    std::vector<char> needed(grid.beds.size(), 0);
    for (std::size_t r = 0; r < grid.runs.size(); ++r) {
        if (grid.runs[r].stored) continue;
        to_run.push_back(r);
        const std::size_t b = grid.beds[grid.runs[r].bed].same_as;
        if (!needed[b]) to_settle.push_back(b);
        needed[b] = 1;
    }
    std::vector<dem::ParticleSet> beds(grid.beds.size());
    std::vector<std::exception_ptr> errors(std::max(to_settle.size(), to_run.size()));
    std::vector<int> settled(to_settle.size(), 0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (std::size_t k = 0; k < to_settle.size(); ++k) {
        try {
            beds[to_settle[k]] = settle(grid, to_settle[k], options.store, settled[k]);
        } catch (...) {
            errors[k] = std::current_exception();
        }
    }
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);
    }
    std::mutex progress_mutex;
    int done = static_cast<int>(grid.runs.size() - to_run.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (std::size_t k = 0; k < to_run.size(); ++k) {
        const std::size_t r = to_run[k];
        try {
            auto& run = grid.runs[r];
            // A line every progress_interval_s while the run goes: a large bed's run takes
            // tens of minutes, and only its end would say anything otherwise.
            using Clock = std::chrono::steady_clock;
            const auto start = Clock::now();
            auto last = start;
            const int continued = run.progress ? static_cast<int>(run.progress->periods.size()) : 0;
            if (continued > 0 && options.progress) {
                std::lock_guard<std::mutex> lock(progress_mutex);
                options.progress("  " + run_name(grid, r) + ": continues from its progress after " +
                                 std::to_string(continued) + " periods");
            }
            const auto going = [&](int periods) {
                const auto now = Clock::now();
                if (!options.progress ||
                    std::chrono::duration<double>(now - last).count() < options.progress_interval_s)
                    return;
                last = now;
                const double per_period = std::chrono::duration<double>(now - start).count() /
                                          std::max(1, periods - continued);
                std::lock_guard<std::mutex> lock(progress_mutex);
                options.progress("  " + run_name(grid, r) + ": " + std::to_string(periods) +
                                 " periods of at most " +
                                 std::to_string(options.steady.max_periods) + ", " +
                                 significant_text(per_period, 3) + " s per period");
            };
            try {
                run.result = measure(config, options, grid, r, beds[grid.beds[run.bed].same_as],
                                     going, checkpoints_of(options, run));
            } catch (const std::invalid_argument& e) {
                if (!run.progress) throw;
                throw CheckpointError(options.store->progress_name(Unfinished::result, run.key), 0,
                                      e.what());
            }
            run.progress.reset();
            if (options.store != nullptr) {
                options.store->save_result(run.key, sealed(point_text(run.result)));
            }
            std::lock_guard<std::mutex> lock(progress_mutex);
            report(options, grid, r, ++done);
        } catch (...) {
            errors[k] = std::current_exception();
        }
    }
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);
    }
    int count = 0;
    for (int n : settled) count += n;
    return count;
}

/// Every run not yet in the store handed to options.remote, its number as the input; each
/// result kept in the store as it arrives.
void run_remotely(const CharacterizeOptions& options, CharacterizationGrid& grid) {
    std::vector<std::string> inputs;
    std::vector<std::size_t> to_run;
    for (std::size_t r = 0; r < grid.runs.size(); ++r) {
        if (grid.runs[r].stored) continue;
        to_run.push_back(r);
        inputs.push_back(std::to_string(r));
    }
    if (to_run.empty()) return;
    int done = static_cast<int>(grid.runs.size() - to_run.size());
    const auto keep = [&](std::size_t index, const std::string& text) {
        if (index >= to_run.size()) return;
        auto& run = grid.runs[to_run[index]];
        run.result = parse_point(text);
        if (options.store != nullptr) options.store->save_result(run.key, sealed(text));
        report(options, grid, to_run[index], ++done);
    };
    const auto outputs = options.remote(inputs, keep);
    if (outputs.size() != to_run.size()) {
        throw std::runtime_error("characterisation: " + std::to_string(outputs.size()) +
                                 " results for " + std::to_string(to_run.size()) + " runs");
    }
    for (std::size_t k = 0; k < to_run.size(); ++k) {
        grid.runs[to_run[k]].result = parse_point(outputs[k]);
    }
}

/// The progress the store holds for the unfinished run `run`, if any; a damaged one is added
/// to `problems`.
void read_progress(CheckpointStore& store, CharacterizationGrid::Run& run,
                   std::vector<config::ConfigError>& problems) {
    const std::optional<std::string> text = store.load_progress(Unfinished::result, run.key);
    if (!text) return;
    const std::string name = store.progress_name(Unfinished::result, run.key);
    try {
        run.progress = parse_run_progress(*text, name);
    } catch (const CheckpointError& e) {
        problems.push_back(
            {name, 0, 0, "(run progress)", "",
             (e.line() > 0 ? "line " + std::to_string(e.line()) + ": " : "") + e.message(),
             "cannot be continued: delete it to run that point from its start, or "
             "run again with --restart to discard every stored result"});
    }
}

/// Opens the store and reads back every run it holds, and the progress of those it holds
/// unfinished. A stored result that is damaged is
/// refused before anything runs, every one named.
void resume_from_store(const CampaignConfig& config, const CharacterizeOptions& options,
                       CharacterizationGrid& grid) {
    CheckpointStore* store = options.store;
    if (store == nullptr) return;
    store->open(config_hash(config), options.restart);
    std::vector<config::ConfigError> problems;
    for (auto& run : grid.runs) {
        std::string key = run.key;
        std::optional<std::string> text = store->load_result(key);
        if (!text && !run.key_with_energy.empty()) {
            key = run.key_with_energy;
            text = store->load_result(key);
        }
        if (!text) {
            read_progress(*store, run, problems);
            continue;
        }
        const std::string content(checkpoint_content(*text));
        std::string damage;
        if (seal_checkpoint(content) != *text) {
            damage = "its checksum does not match its content (cut short or changed)";
        } else {
            try {
                run.result = parse_point(content);
                if (options.energy_layers == 0) run.result.energy.reset();  // not asked for
                run.stored = true;
            } catch (const std::exception& e) {
                damage = e.what();
            }
        }
        if (!damage.empty()) {
            problems.push_back({store->result_name(key), 0, 0, "(stored result)", "", damage,
                                "cannot be resumed: delete it to run that point again, or run "
                                "again with --restart to discard every stored result"});
        }
    }
    if (!problems.empty()) throw config::ConfigException(std::move(problems));
}

}  // namespace

CharacterizationWorker::CharacterizationWorker(const CampaignConfig& config,
                                               CharacterizeOptions options)
    : config_(config),
      options_(std::move(options)),
      grid_(std::make_unique<CharacterizationGrid>(plan_grid(config_, options_))) {}

CharacterizationWorker::~CharacterizationWorker() = default;

std::string CharacterizationWorker::run(const std::string& run_text) {
    char* end = nullptr;
    const long r = std::strtol(run_text.c_str(), &end, 10);
    if (end == run_text.c_str() || *end != '\0' || r < 0 ||
        r >= static_cast<long>(grid_->runs.size())) {
        throw std::invalid_argument("characterisation: no run " + run_text);
    }
    const auto run = static_cast<std::size_t>(r);
    const std::size_t b = grid_->beds[grid_->runs[run].bed].same_as;
    // A process settles each bed it needs once (two threads asking at once may both settle
    // it: the same bed), and its runs at the other frequencies reuse it.
    std::shared_ptr<const dem::ParticleSet> bed;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto it = beds_.find(b);
        if (it != beds_.end()) bed = it->second;
    }
    if (!bed) {
        int settled = 0;
        bed = std::make_shared<const dem::ParticleSet>(settle(*grid_, b, nullptr, settled));
        std::lock_guard<std::mutex> lock(mutex_);
        beds_.emplace(b, bed);
    }
    return point_text(measure(config_, options_, *grid_, run, *bed));
}

CharacterizeResult characterize(const CampaignConfig& config, const CharacterizeOptions& options) {
    const auto started = std::chrono::steady_clock::now();
    CharacterizationGrid grid = plan_grid(config, options);
    resume_from_store(config, options, grid);
    int resumed = 0;
    for (const auto& run : grid.runs) resumed += run.stored ? 1 : 0;
    if (options.progress && resumed > 0) {
        options.progress("resumed " + std::to_string(resumed) + " of " +
                         std::to_string(grid.runs.size()) + " runs from the store");
    }
    int beds_settled = 0;
    if (options.remote) {
        run_remotely(options, grid);
    } else {
        beds_settled = run_here(config, options, grid);
    }
    const auto& levels = grid.levels;
    const auto& dampers = grid.dampers;
    const auto& plan = grid.plan;
    const auto& grids = grid.grids;
    const auto& rotations = grid.rotations;
    const auto& runs = grid.runs;
    const auto& beds = grid.beds;
    const auto damper_index = [&](const DamperSpec* d) { return grid.damper_index(d); };

    CharacterizeResult result;
    result.resumed_runs = resumed;
    result.beds_settled = beds_settled;
    CharacterizationTable& table = result.table;
    table.config = config.source;
    table.config_hash = config_hash(config);
    for (const DamperSpec* d : dampers)
        table.damper_hashes.emplace_back(d->name, damper_hash(config, d->name));
    table.command = options.command_line;
    table.criterion = options.steady.describe();
    for (const auto& run : runs) {
        const auto& bed = beds[run.bed];
        result.runs_by_filling.push_back({bed.damper->name,
                                          plan.arrangements[bed.arrangement].arrangement.name,
                                          bed.level_g, run.frequency_hz, bed.seed, run.result});
    }
    for (std::size_t a = 0; a < plan.arrangements.size(); ++a) {
        const PreparedArrangement& prepared = plan.arrangements[a];
        for (const DamperSpec* damper : dampers) {
            for (double level : levels) {
                for (double f : grids[a]) {
                    std::vector<double> re, im, power, h2, h3, kinetic, periods, mass;
                    bool settled = true;
                    for (const auto& run : runs) {
                        const auto& bed = beds[run.bed];
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

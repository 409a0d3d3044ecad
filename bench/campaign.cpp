// The stepped-sine campaign: plan, sweeps as parallel tasks, results in memory.
#include "bench/campaign.hpp"

#include <omp.h>

#include <Eigen/Core>
#include <chrono>
#include <cstdio>
#include <exception>
#include <sstream>

#include "bench/campaign_output.hpp"
#include "bench/resolved_config.hpp"
#include "core/significant_text.hpp"

namespace sb::bench {
namespace {

namespace id = identification;

}  // namespace

/// "H-0 2 g: 2 points with status closest left out of the fits (6.301, 6.412 Hz)".
std::string skipped_points_line(const id::LevelIdentification& level, const std::string& unit) {
    std::ostringstream out;
    out << level.arrangement << ' ' << significant_text(level.level_g) << ' ' << unit << ": "
        << level.skipped_hz.size() << " point" << (level.skipped_hz.size() == 1 ? "" : "s")
        << " with status " << id::flagged_status_text(level) << " left out of the fits (";
    for (std::size_t i = 0; i < level.skipped_hz.size(); ++i) {
        char f[32];
        std::snprintf(f, sizeof f, "%.3f", level.skipped_hz[i]);
        out << (i > 0 ? ", " : "") << f;
    }
    out << " Hz)";
    return out.str();
}

void identify_campaign(const CampaignConfig& config,
                       const std::function<void(const std::string&)>& progress,
                       CampaignResult& result) {
    id::IdentifyOptions identify;
    identify.response_channel = "acc_" + config.campaign.control_point;
    result.levels = id::identify_recording(result.recording, identify);
    result.recording.damping = id::damping_rows(result.levels);
    if (progress) {
        for (const auto& level : result.levels) {
            if (!level.skipped_hz.empty()) progress(skipped_points_line(level, level_unit(config)));
        }
    }
}

/// recording.toml's channels: the reference, then the control point, then the responses (and
/// the force into the structure when a shaker drives it, its voltage the reference).
id::Recording campaign_recording(const CampaignConfig& config,
                                 const std::vector<RecordedChannel>& channels) {
    const auto& excitation = config.structure.excitation;
    id::Recording rec;
    rec.info.name = config.name;
    rec.info.kind = "simulated";
    const bool force = excitation.kind == structure::ExcitationSpec::Kind::force;
    rec.info.excitation = force ? "force" : "base";
    rec.info.description = config.description;
    const bool shaker = force && config.physics.shaker.on();
    if (shaker) {
        rec.channels.push_back(
            {"voltage", "voltage", "V", excitation.point, id::ChannelRole::reference});
    } else if (force) {
        rec.channels.push_back(
            {"force", "force", "N", excitation.point, id::ChannelRole::reference});
    } else {
        // An imported model has no support to name: its base is "base".
        rec.channels.push_back({"base_acc", "acceleration", "m/s^2",
                                excitation.support.empty() ? "base" : excitation.support,
                                id::ChannelRole::reference});
    }
    for (std::size_t i = 0; i < channels.size(); ++i) {
        rec.channels.push_back({channels[i].name, channels[i].quantity_name(), channels[i].unit(),
                                channels[i].location(),
                                i == 0 ? id::ChannelRole::control : id::ChannelRole::response});
    }
    if (shaker) {
        rec.channels.push_back(
            {"force", "force", "N", excitation.point, id::ChannelRole::response});
    }
    return rec;
}

namespace {

/// The sweeps on this process's OpenMP threads.
class ThreadExecutor : public SweepExecutor {
  public:
    explicit ThreadExecutor(int threads)
        : threads_(threads > 0 ? threads : omp_get_max_threads()) {}

    std::vector<SweepResult> run(const CampaignConfig& config, const CampaignPlan& plan,
                                 const std::string& config_hash, CheckpointStore& store,
                                 SweepProgress& progress) override {
        const std::size_t count = plan.tasks.size();
        std::vector<SweepResult> sweeps(count);
        std::vector<std::exception_ptr> errors(count);
        // Sweeps are independent tasks: each owns its specimen and its checkpoint, so the
        // numbers are the same whatever the thread count. Eigen would split large products
        // over OpenMP threads when a sweep runs alone (one thread in the region) and not when
        // it shares the region, changing their blocking and so their rounding: it runs
        // single-threaded here. No exception leaves the parallel region.
        const int eigen_threads = Eigen::nbThreads();
        Eigen::setNbThreads(1);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads_)
        for (std::size_t i = 0; i < count; ++i) {
            try {
                sweeps[i] = run_sweep(config, plan.tasks[i], config_hash, store, progress);
            } catch (...) {
                errors[i] = std::current_exception();
            }
        }
        Eigen::setNbThreads(eigen_threads);
        for (const auto& e : errors) {
            if (e) std::rethrow_exception(e);
        }
        return sweeps;
    }
    [[nodiscard]] int processes() const override { return 1; }
    [[nodiscard]] int threads() const override { return threads_; }

  private:
    int threads_;
};

}  // namespace

CampaignResult run_campaign(const CampaignConfig& config, const CampaignContext& context) {
    const auto started = std::chrono::steady_clock::now();
    const CampaignSpec& campaign = config.campaign;
    const CampaignPlan plan = plan_campaign(config, context.selection);
    CampaignResult result;
    result.config_hash = config_hash(config);
    NoCheckpointStore none;
    CheckpointStore& store = context.store != nullptr ? *context.store : none;
    store.open(result.config_hash, context.restart);

    CampaignProgress progress(context.progress, plan.points());
    if (context.progress) {
        const RandomSpec& random = config.campaign.random;
        context.progress("campaign " + config.name + ": " + std::to_string(plan.tasks.size()) +
                         (random.on() ? " random tests of " + significant_text(random.low_hz) +
                                            "-" + significant_text(random.high_hz) + " Hz"
                                      : " sweeps, " + std::to_string(plan.points()) + " points"));
    }
    ThreadExecutor threaded(context.threads);
    SweepExecutor& executor = context.executor != nullptr ? *context.executor : threaded;
    std::vector<SweepResult> sweeps =
        executor.run(config, plan, result.config_hash, store, progress);

    result.channels = recorded_channels(campaign, config.structure.excitation);
    result.recording = campaign_recording(config, result.channels);
    CampaignSummary& summary = result.summary;
    for (const auto& sweep : sweeps) {
        summary.points += static_cast<int>(sweep.rows.size());
        result.recording.points.insert(result.recording.points.end(), sweep.rows.begin(),
                                       sweep.rows.end());
        summary.resumed_points += sweep.resumed_points;
        summary.periods_simulated += sweep.periods_simulated;
        for (const auto& row : sweep.rows) {
            summary.converged += row.status == "converged";
            summary.limit_cycle += row.status == "limit-cycle-2";
            summary.closest += row.status == "closest";
        }
    }
    identify_campaign(config, context.progress, result);
    result.sweeps = std::move(sweeps);
    result.threads = executor.threads();
    result.ranks = executor.processes();
    summary.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

CampaignSummary run_campaign(const CampaignConfig& config, const CampaignRunOptions& options) {
    FileCheckpointStore store(options.out_dir);
    CampaignContext context;
    context.threads = options.threads;
    context.store = &store;
    context.restart = options.restart;
    context.executor = options.executor;
    if (options.progress != nullptr) {
        std::ostream* out = options.progress;
        context.progress = [out](const std::string& line) { *out << line << '\n' << std::flush; };
        *out << "recording directory: " << options.out_dir.string() << '\n';
    }
    const CampaignResult result = run_campaign(config, context);
    RecordingDirectory directory;
    directory.out_dir = options.out_dir;
    directory.config_text = options.config_text;
    directory.command_line = options.command_line;
    write_campaign_output(config, result, directory);
    return result.summary;
}

}  // namespace sb::bench

// The settled bed of a damper in its mounting, kept in a checkpoint store.
#include "bench/settled_bed.hpp"

#include <chrono>
#include <optional>
#include <stdexcept>

#include "bench/campaign_spec.hpp"
#include "bench/checkpoint_store.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "dem/setup.hpp"

namespace sb::bench {
namespace {

/// A pour saving its progress in `store` under `key` every `interval_s` of wall time, and
/// continuing the progress stored there.
dem::ParticleSet pour_with_checkpoints(const dem::SolverOptions& local,
                                       const dem::SettleOptions& settle, std::uint64_t seed,
                                       CheckpointStore& store, const std::string& key,
                                       double interval_s) {
    using Clock = std::chrono::steady_clock;
    std::optional<dem::PourProgress> progress;
    if (const auto text = store.load_progress(Unfinished::bed, key)) {
        progress = parse_pour_progress(*text, store.progress_name(Unfinished::bed, key));
    }
    auto last = Clock::now();
    dem::PourCheckpoints checkpoints;
    checkpoints.due = [&] {
        return std::chrono::duration<double>(Clock::now() - last).count() >= interval_s;
    };
    checkpoints.save = [&](const dem::PourProgress& p) {
        store.save_progress(Unfinished::bed, key, serialize_pour_progress(p));
        last = Clock::now();
    };
    checkpoints.resume = progress ? &*progress : nullptr;
    try {
        return dem::pour(local, seed, settle, {}, checkpoints);
    } catch (const std::invalid_argument& e) {
        if (!progress) throw;
        throw CheckpointError(store.progress_name(Unfinished::bed, key), 0, e.what());
    }
}

dem::ParticleSet settle_now(const DamperSpec& damper, double stiffness,
                            const Eigen::Matrix3d& rotation, const Eigen::Vector3d& gravity_m_s2,
                            std::uint64_t seed, CheckpointStore* store, const std::string& key,
                            double checkpoint_interval_s) {
    dem::SolverOptions local = damper.solver_options(stiffness);
    local.gravity_m_s2 = rotation.transpose() * gravity_m_s2;
    local.track_energy = false;
    local.lock = dem::LockOptions{};  // the bed settles free; a lock then holds it as it lies
    if (damper.fill == DamperSpec::Fill::pour) {
        if (store == nullptr) return dem::pour(local, seed, damper.settle);
        return pour_with_checkpoints(local, damper.settle, seed, *store, key,
                                     checkpoint_interval_s);
    }
    dem::ParticleSet filled;
    try {
        filled = dem::fill_random(local, seed);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error("damper " + damper.name + ": " + e.what() + " (set dampers." +
                                 damper.name + ".settle.fill = \"pour\")");
    }
    return dem::settle(local, filled, damper.settle);
}

}  // namespace

dem::ParticleSet settled_bed(const DamperSpec& damper, double stiffness,
                             const Eigen::Matrix3d& rotation, const Eigen::Vector3d& gravity_m_s2,
                             std::uint64_t seed, CheckpointStore* store, const std::string& key,
                             bool* settled_here, double checkpoint_interval_s) {
    std::optional<std::string> text;
    if (store != nullptr) text = store->load_bed(key);
    if (settled_here != nullptr) *settled_here = !text;
    if (!text) {
        text = dem::particles_text(settle_now(damper, stiffness, rotation, gravity_m_s2, seed,
                                              store, key, checkpoint_interval_s));
        if (store != nullptr) store->save_bed(key, *text);
    }
    return dem::parse_particles_text(*text, key);
}

}  // namespace sb::bench

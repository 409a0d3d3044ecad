// The settled bed of a damper in its mounting, kept in a checkpoint store.
#include "bench/settled_bed.hpp"

#include <optional>
#include <stdexcept>

#include "bench/campaign_spec.hpp"
#include "bench/checkpoint_store.hpp"
#include "dem/setup.hpp"

namespace sb::bench {
namespace {

dem::ParticleSet settle_now(const DamperSpec& damper, double stiffness,
                            const Eigen::Matrix3d& rotation, const Eigen::Vector3d& gravity_m_s2,
                            std::uint64_t seed) {
    dem::SolverOptions local = damper.solver_options(stiffness);
    local.gravity_m_s2 = rotation.transpose() * gravity_m_s2;
    local.track_energy = false;
    local.lock = dem::LockOptions{};  // the bed settles free; a lock then holds it as it lies
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

}  // namespace

dem::ParticleSet settled_bed(const DamperSpec& damper, double stiffness,
                             const Eigen::Matrix3d& rotation, const Eigen::Vector3d& gravity_m_s2,
                             std::uint64_t seed, CheckpointStore* store, const std::string& key,
                             bool* settled_here) {
    std::optional<std::string> text;
    if (store != nullptr) text = store->load_bed(key);
    if (settled_here != nullptr) *settled_here = !text;
    if (!text) {
        text = dem::particles_text(settle_now(damper, stiffness, rotation, gravity_m_s2, seed));
        if (store != nullptr) store->save_bed(key, *text);
    }
    return dem::parse_particles_text(*text, key);
}

}  // namespace sb::bench

// The complete state of a dem::Solver as plain data: taken with Solver::state(), written and
// read back number by number, and continued with Solver(options, state, enclosure).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "dem/enclosure.hpp"

namespace sb::dem {

/// Tangential history spring xi of a particle-particle contact (coulomb_spring: F_t = -k_t xi,
/// contact_law.hpp), world frame of SolverState::enclosure [m].
struct PairHistory {
    std::uint32_t i = 0;  ///< particle id, i < j
    std::uint32_t j = 0;  ///< particle id
    Eigen::Vector3d history_m = Eigen::Vector3d::Zero();
};

/// Tangential history spring of a particle-wall contact, world frame of SolverState::enclosure
/// [m]. `wall` is the id Enclosure::for_each_contact gives the wall or obstacle (cylinder side
/// 0, bottom 1, top 2; box faces 0..5; plates from kPlateBase; rods from kRodBase): it depends
/// only on the enclosure options, so it names the same wall after a rebuild.
struct WallHistory {
    std::uint32_t particle = 0;
    std::uint32_t wall = 0;
    Eigen::Vector3d history_m = Eigen::Vector3d::Zero();
};

/// A particle moving with the enclosure until LockOptions::release_time_s.
struct LockedParticle {
    std::uint32_t id = 0;
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< frozen, enclosure frame [m]
};

/// Everything a Solver needs to continue exactly: the particle state, the tangential springs
/// of the touching contacts, the lock and the clock. Plain data (every number a double or an
/// integer), so that it can be written exactly (e.g. as hexadecimal floats) and read back.
///
/// The particle state and the springs are stored as the solver holds them, in the world frame,
/// together with the enclosure pose and velocity they belong to (`enclosure`): a state
/// restored at that same pose continues bitwise identically, which a round trip through the
/// enclosure frame (x -> R^T (x - x_c) -> R x_l + x_c) would not give. Restored at another pose
/// the state moves rigidly with the enclosure (enclosure-frame positions, velocities relative
/// to the enclosure, spins and springs in enclosure axes kept); local_particles() gives the
/// enclosure-frame particles.
struct SolverState {
    /// Pose and velocity of the enclosure the world-frame values below belong to (the one set
    /// for the last step, or set since) [SI].
    EnclosureState enclosure{};
    std::vector<Eigen::Vector3d> positions_m{};               ///< centres, world [m]
    std::vector<Eigen::Vector3d> velocities_m_s{};            ///< world [m/s]
    std::vector<Eigen::Vector3d> angular_velocities_rad_s{};  ///< world [rad/s]
    std::vector<double> radii_m{};                            ///< [m]
    /// Springs of the particle pairs touching in the last step, sorted by (i, j); empty unless
    /// the tangential law is coulomb_spring (the only law with a history).
    std::vector<PairHistory> pair_histories{};
    /// Springs of the particle-wall contacts of the last step, sorted by (particle, wall);
    /// empty unless the law is coulomb_spring.
    std::vector<WallHistory> wall_histories{};
    /// The particles locked now, by id; empty once released.
    std::vector<LockedParticle> locked{};
    /// True once the locked particles were freed (at LockOptions::release_time_s or by
    /// Solver::release()); a restored solver does not lock them again.
    bool released = false;
    double time_s = 0.0;    ///< solver clock [s] (LockOptions::release_time_s refers to it)
    std::int64_t step = 0;  ///< steps taken
    /// Direction against gravity in the enclosure frame from which the energy layers were
    /// built (not normalised; Solver::layers()); zero = from gravity at the restore pose.
    Eigen::Vector3d layers_up = Eigen::Vector3d::Zero();
};

}  // namespace sb::dem

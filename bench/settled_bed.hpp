// The settled bed of a damper in its mounting: the one procedure the campaign and the
// characterisation share, so that a seed and a stiffness give the same bed in both.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <string>

#include "dem/solver.hpp"

namespace sb::bench {

struct DamperSpec;
class CheckpointStore;

/// Wall time between two saves of a settling bed's progress [s]: a 13,500-sphere bed's
/// progress is a few megabytes, written in well under a second.
inline constexpr double kSettlingCheckpointIntervalS = 120.0;

/// The bed of `damper` filled with `seed` and settled under `gravity_m_s2` (the structure's,
/// turned into the enclosure frame by `rotation`) with contacts of `stiffness`. Taken from
/// `store` under `key` when it holds one, else settled and saved there (`store` may be null:
/// nothing kept). Always read back from its text (17 significant digits, exact), so a bed
/// settled now, one read from the store and one settled on another rank give the same
/// numbers. `settled_here`, when given, is set to whether this call settled it.
///
/// A poured bed (settle.fill = "pour") saves its progress in `store` every
/// `checkpoint_interval_s` of wall time while it settles (a bed of tens of thousands of spheres
/// settles for hours) and continues from the progress stored there: an interrupted settle
/// resumes, bitwise as if uninterrupted. A stored progress that is damaged or does not fit
/// this bed throws CheckpointError naming it (store.progress_name(Unfinished::bed, key)).
dem::ParticleSet settled_bed(const DamperSpec& damper, double stiffness,
                             const Eigen::Matrix3d& rotation, const Eigen::Vector3d& gravity_m_s2,
                             std::uint64_t seed, CheckpointStore* store, const std::string& key,
                             bool* settled_here = nullptr,
                             double checkpoint_interval_s = kSettlingCheckpointIntervalS);

}  // namespace sb::bench

// Planning a campaign: which sweeps (arrangement x level) run on which frequencies, each a
// task that runs on its own (the seam a scheduler distributes).
#pragma once

#include <string>
#include <vector>

#include "bench/campaign_config.hpp"
#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// One sweep a caller asks for: an arrangement of the config at a level, on the config's
/// frequency grid or on given frequencies (those a measurement has).
struct SweepSelection {
    std::string arrangement;
    double level_g = 0.0;                ///< target RMS level [g]
    std::vector<double> frequencies_hz;  ///< in sweep order; empty: the config's grid
};

/// Which points a campaign simulates; empty: every selected arrangement of the config at
/// every level, each on its grid.
struct Selection {
    std::vector<SweepSelection> sweeps;

    /// Every combination of `arrangements` (empty: the config's) and `levels_g` (empty: the
    /// config's), each on `frequencies_hz` (empty: the grid).
    static Selection of(const CampaignConfig& config, std::vector<std::string> arrangements,
                        std::vector<double> levels_g, std::vector<double> frequencies_hz = {});
};

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
    std::vector<double> frequencies_hz;  ///< the config's grid
};

/// One sweep to run: everything it needs besides the config and a store.
struct SweepTask {
    std::size_t index = 0;  ///< place in the campaign (output order)
    const PreparedArrangement* prepared = nullptr;
    /// The sweep's level: a target RMS [g], or a fixed drive's amplitude in level_unit.
    double level_g = 0.0;
    std::string level_unit = "g";        ///< "g", or a fixed drive's "N", "m/s^2", "V", "m"
    std::vector<double> frequencies_hz;  ///< in sweep order
    int filling = 0;                     ///< which filling of the bed (0, 1, ... seeds - 1)
    std::uint64_t seed = 1;              ///< its seed: campaign.seed + filling
    /// Level an automatic contact stiffness is sized for: the campaign's largest (also
    /// covering this sweep's) unless the damper asks for each sweep's own [g].
    double stiffness_level_g = 0.0;
    /// On the config's grid: frequencies may be added to resolve the estimates (never on
    /// given frequencies, which are exactly what a caller asked for).
    bool refine = false;
    /// File-name friendly and unique: "H-0_1g"; a sweep on given frequencies adds a hash of
    /// them ("H-0_1g_f3a9c0d12"), so its checkpoint is never taken for the grid's, and a
    /// further filling its index ("H-0_1g_s2").
    std::string key;
};

struct CampaignPlan {
    std::vector<PreparedArrangement> arrangements;  ///< stable addresses: tasks point here
    std::vector<SweepTask> tasks;                   ///< in campaign order
    [[nodiscard]] int points() const;
};

/// The unit of a sweep's level: "g" for the controller's target; a fixed drive's amplitude
/// in "N", "m/s^2" (base acceleration), "V" (through the shaker) or "m" (base displacement).
std::string level_unit(const CampaignConfig& config);

/// Under a fixed drive, the largest RMS acceleration [g] at the control point that the linear
/// model with the particles as rigid mass gives over the arrangement's grid at the largest
/// amplitude: what an automatic contact stiffness is sized for. Without the particles'
/// damping it overestimates the response near resonance, so the stiffness errs stiff (safe
/// overlaps, a shorter step); give dampers.NAME.contact.normal_stiffness to choose it.
double fixed_drive_level_g(const CampaignConfig& config, const PreparedArrangement& prepared);

/// The sweeps of `selection` (or of the whole config). Throws config::ConfigException when
/// the config cannot run a campaign (no level, no arrangement) or the selection names an
/// arrangement the config does not define, a level or a frequency <= 0.
CampaignPlan plan_campaign(const CampaignConfig& config, const Selection& selection);

/// The structure of an arrangement: gravity set, masses at named points placed, mounting
/// blocks added at the damper points, and the particles of rigid dampers (of every damper
/// when all_particles_rigid) as rigid masses at the centre of a settled bed.
structure::StructureSpec arrangement_structure(const CampaignConfig& config,
                                               const ArrangementSpec& arrangement,
                                               bool all_particles_rigid);

/// Mass of a damper's particles for a filling seed [kg].
double particle_mass_kg(const DamperSpec& damper, std::uint64_t seed);

}  // namespace sb::bench

// Characterising a particle damper alone: its enclosure moved harmonically along the
// excitation direction (with the arrangement's gravity and tilt, and the rotation that goes
// with the translation in the driven mode), no structure; per amplitude and frequency the
// complex apparent mass M = -F1/a1, the dissipated power, the harmonics of the force and the
// bed's agitation, averaged over several fillings (docs/characterisation.md).
#pragma once

#include <Eigen/Core>
#include <complex>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "bench/characterization_progress.hpp"
#include "bench/checkpoint_store.hpp"
#include "bench/describing_function.hpp"
#include "core/violation.hpp"
#include "dem/solver.hpp"

namespace sb::bench {

/// When a characterised point is steady. The per-period fundamental of a granular bed's force
/// fluctuates from period to period (the bed is chaotic), so a single period never settles
/// exactly: after `transient_periods`, the means of the last two windows of `window_periods`
/// must agree within `tolerance` times the force a rigid bed of the same mass would exert
/// (m |a1|). The point's values are the means over those two windows. A point that does not
/// settle within `max_periods` is flagged and gives the last two windows.
struct SteadyStateOptions {
    int transient_periods = 4;  ///< periods left out at the start [-]
    int window_periods = 8;     ///< periods per window [-]
    double tolerance = 0.03;    ///< |mean_B - mean_A| <= tolerance m |a1| [-]
    int max_periods = 64;       ///< budget [-]
    /// > 0: also the bed's stored (kinetic, potential, elastic) energy changes over the two
    /// windows by at most this share of the walls' work over them (or of the kinetic energy
    /// 1/2 m (A/w)^2 the bed carries riding its enclosure, if larger): a bed still filling or
    /// draining its store is not steady, whatever its force does. 0: off [-].
    double energy_tolerance = 0.0;
    /// Keys: transient_periods, window_periods, tolerance, max_periods, energy_tolerance.
    [[nodiscard]] Violations validate() const;
    /// One line for the file's header.
    [[nodiscard]] std::string describe() const;
};

/// The prescribed motion of the damper's point: acceleration a(t) = A sin(w t) along
/// `direction`, with the point turned by theta(t) = rotation_per_translation u(t).
struct HarmonicDrive {
    Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
    Eigen::Vector3d rotation_per_translation_rad_m = Eigen::Vector3d::Zero();  ///< [rad/m]
    double acceleration_m_s2 = 0.0;                                            ///< peak A [m/s^2]
    double frequency_hz = 0.0;                                                 ///< [Hz]
};

/// The damper on its point: DEM options (gravity in the structure frame, the contact
/// stiffness chosen), the mounting, the settled bed (enclosure frame), the largest time step.
struct EnclosureSetup {
    dem::SolverOptions options;
    Eigen::Matrix3d mount_rotation = Eigen::Matrix3d::Identity();  ///< enclosure -> structure
    Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();  ///< enclosure origin from the point
    dem::ParticleSet bed;
    double dt_max_s = 0.0;  ///< the period is split into whole steps no longer than this [s]
    /// Measure where the energy goes (ApparentMassPoint::energy); the layers are
    /// options.energy_layers. Costs one pass over the particles per step.
    bool bed_energy = false;
};

/// Where a characterised bed's energy goes over the steady windows (paper 002's Figs. 12 and
/// 13): the dissipated power per mechanism and per horizontal layer, and the spectra of the
/// bed's kinetic energy and dissipated power. Filled when EnclosureSetup::bed_energy is set.
struct BedEnergy {
    double normal_damping_w = 0.0;  ///< normal dashpots, mean over the windows [W]
    double friction_w = 0.0;        ///< sliding friction [W]
    double rolling_w = 0.0;         ///< rolling resistance [W]
    /// Rate of change of the bed's kinetic, potential and elastic energy over the windows
    /// [W]: the walls' power is this plus the three above, up to the ledger's error.
    double mechanical_change_w = 0.0;
    /// Per horizontal layer along gravity, bottom first (dem::HorizontalLayers; the count is
    /// the solver's energy_layers) [W].
    std::vector<double> layer_power_w;
    /// Per horizontal layer: the mean kinetic energy, relative to the enclosure, of the
    /// particles whose centre is in it (dem::EnergyLedger::layer_kinetic_time) [J]; they add
    /// up to the bed's agitation (ApparentMassPoint::kinetic_j, sampled every step).
    std::vector<double> layer_kinetic_j;
    /// Mean kinetic energy of the particles in the laboratory frame (what a DEM code that
    /// moves the walls reports, the enclosure's own motion included) [J].
    double kinetic_lab_j = 0.0;
    /// Spacing of the spectra's bins: 1 / (length of the two windows) [Hz]; bin k of the
    /// vectors below is at k * bin_hz, k = 1, 2, ...
    double bin_hz = 0.0;
    /// One-sided amplitude (2 |X_k| / N) of the laboratory kinetic energy sampled every step
    /// over the windows, mean removed, up to kSpectrumHarmonics times the drive [J].
    std::vector<double> kinetic_amplitude_j;
    /// The same of the dissipated power (dissipation per step / step) [W].
    std::vector<double> dissipation_amplitude_w;

    /// Bins reported: up to this many times the drive frequency.
    static constexpr int kSpectrumHarmonics = 8;
};

/// One characterised point of one filling.
struct ApparentMassPoint {
    /// M = -Q1/a1 [kg], Q = F.d + M.psi the particles' generalised force on the point (force
    /// along the direction, moment about the point along the rotation), over the steady
    /// window; a1 = -i A.
    std::complex<double> apparent_mass_kg = 0.0;
    double power_w = 0.0;    ///< wall work on the particles per period / period [W]
    double h2_ratio = 0.0;   ///< |Q2| / |Q1| of the window's mean phasors [-]
    double h3_ratio = 0.0;   ///< |Q3| / |Q1| [-]
    double kinetic_j = 0.0;  ///< mean kinetic energy relative to the enclosure [J]
    double bed_mass_kg = 0.0;
    int periods = 0;       ///< periods simulated
    bool settled = false;  ///< the criterion was met within the budget
    int steps_per_period = 0;
    /// With EnclosureSetup::bed_energy: where the energy goes (else empty).
    std::optional<BedEnergy> energy;
};

/// Runs the damper of `setup` under `drive` until steady (or the budget) and measures it;
/// `after_period`, when given, is called after every period with the number done (the
/// progress of a long run). With `checkpoints`, saves the run's progress at the ends of
/// periods it asks for, or continues a saved one: the result is bitwise the uninterrupted
/// run's. Throws dem::SimulationError when a DEM guard fires, std::invalid_argument for a
/// drive or criterion it cannot run, or a progress that does not fit the run.
ApparentMassPoint measure_apparent_mass(const EnclosureSetup& setup, const HarmonicDrive& drive,
                                        const SteadyStateOptions& steady,
                                        const std::function<void(int)>& after_period = {},
                                        const RunCheckpoints& checkpoints = {});

/// Rotation per unit translation along `direction` of `point` in the first mode the
/// excitation drives (the structure with the particles as rigid mass) [rad/m]: a cantilever's
/// tip turns as it moves.
Eigen::Vector3d rotation_per_translation(const PreparedArrangement& prepared,
                                         const std::string& point,
                                         const Eigen::Vector3d& direction);

/// What to characterise beyond the config.
struct CharacterizeOptions {
    std::vector<double> levels_g;        ///< RMS levels [g]; empty: campaign.levels_g
    std::vector<double> frequencies_hz;  ///< empty: each arrangement's grid
    /// > 0 and no frequencies_hz: this many frequencies, equally spaced over each
    /// arrangement's grid.
    int frequency_count = 0;
    int seeds = 3;  ///< fillings: campaign.seed, campaign.seed + 1, ...
    /// > 0: measure where the energy goes (BedEnergy) with this many horizontal layers.
    int energy_layers = 0;
    /// With energy_layers = 0 and a store: a run the store holds with this many energy layers
    /// serves too, its energy left out (the ledger does not touch the motion and the power
    /// comes from the load on the point, so its other numbers are the run's; runs stored
    /// before the power came from the load differ in the power's last digits). 0: none.
    int stored_energy_layers = 0;
    bool rotation = true;  ///< the point turns with the driven mode (else translation only)
    SteadyStateOptions steady;
    int threads = 0;  ///< runs in parallel; 0: OpenMP's default
    /// Receives progress lines; empty: none.
    std::function<void(const std::string&)> progress;
    /// Wall time between the lines of a run still going (a bed of ten thousand spheres takes
    /// tens of minutes per run) [s]; 0: after every period.
    double progress_interval_s = 60.0;
    /// Wall time between two saves of a run's progress in `store` (at the end of a period):
    /// a run of a bed of tens of thousands of spheres takes hours, and an interrupted one
    /// continues from its last save, bitwise as if uninterrupted [s]; 0: after every period.
    double checkpoint_interval_s = 120.0;
    std::string command_line;  ///< for the file's header
    /// Runs the grid in other processes (MPI ranks; distributed/rounds.hpp): given each run's
    /// number as text, returns each one's result as text (CharacterizationWorker::run's
    /// output), in order, and hands each to `on_result` (its index among the numbers, the
    /// text) as it arrives, so that it is stored at once. Empty: this process's threads run
    /// it.
    std::function<std::vector<std::string>(
        const std::vector<std::string>& run_numbers,
        const std::function<void(std::size_t index, const std::string& result)>& on_result)>
        remote;
    /// Keeps every finished run and settled bed, opened by characterize() with the config's
    /// hash: a characterisation interrupted, or extended by levels, frequencies or fillings,
    /// simulates only what the store does not hold, and gives the numbers an uninterrupted
    /// one gives. Each run is kept under a key of everything its numbers depend on beyond the
    /// config (level, frequency, filling, contact stiffness and step, the criterion, the
    /// rotation, the energy layers); a run still going keeps its progress there too
    /// (checkpoint_interval_s). Null: nothing kept.
    CheckpointStore* store = nullptr;
    bool restart = false;  ///< the store forgets what it holds for this config first
};

/// One run of a characterisation: a grid point on one filling.
struct CharacterizedRun {
    std::string damper;
    std::string arrangement;
    double level_g = 0.0;       ///< RMS [g]
    double frequency_hz = 0.0;  ///< [Hz]
    std::uint64_t seed = 0;     ///< of the filling
    ApparentMassPoint result;
};

struct CharacterizeResult {
    CharacterizationTable table;
    std::vector<CharacterizedRun> runs_by_filling;  ///< every run, in the grid's order
    int runs = 0;                                   ///< grid points x fillings
    int resumed_runs = 0;                           ///< of them, read back from the store
    int beds_settled = 0;                           ///< beds settled by this call
    int unsettled_runs = 0;                         ///< of them, not steady within the budget
    long long periods = 0;                          ///< of every run, resumed ones included
    double wall_time_s = 0.0;
};

struct CharacterizationGrid;

/// Another process's side of a distributed characterisation: the same config and options
/// plan the same runs; each run's bed is settled once per process, then the run measured.
class CharacterizationWorker {
  public:
    /// Throws what characterize throws for a config or options it cannot characterise.
    CharacterizationWorker(const CampaignConfig& config, CharacterizeOptions options);
    ~CharacterizationWorker();
    CharacterizationWorker(const CharacterizationWorker&) = delete;
    CharacterizationWorker& operator=(const CharacterizationWorker&) = delete;
    /// Runs run number `run_number` and returns its result as exact text; several threads may
    /// call it at once. Throws
    /// std::invalid_argument for a number that names no run, dem::SimulationError when a DEM
    /// guard fires.
    std::string run(const std::string& run_number);

  private:
    const CampaignConfig& config_;
    CharacterizeOptions options_;
    std::unique_ptr<CharacterizationGrid> grid_;
    std::mutex mutex_;
    std::map<std::size_t, std::shared_ptr<const dem::ParticleSet>> beds_;
};

/// Characterises every damper of `config` whose model is not rigid, in every selected
/// arrangement, at every level and frequency, each on `options.seeds` fillings; the runs are
/// independent and run in parallel (the numbers do not depend on the thread count). Throws
/// config::ConfigException when there is nothing to characterise (no level, no such damper)
/// or an option is out of range, dem::SimulationError when a DEM guard fires.
CharacterizeResult characterize(const CampaignConfig& config, const CharacterizeOptions& options);

}  // namespace sb::bench

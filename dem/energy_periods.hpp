// Energy exchanged over intervals (excitation periods) from snapshots of the solver's ledger.
#pragma once

#include <vector>

#include "dem/solver.hpp"

namespace sb::dem {

/// What happened between two ledger snapshots [J], duration [s].
struct EnergyInterval {
    double duration_s = 0.0;
    double wall_work = 0.0;                   ///< work done by the walls on the particles
    double normal_damping = 0.0;              ///< dissipated by the normal dashpots
    double friction = 0.0;                    ///< dissipated by sliding friction
    double rolling = 0.0;                     ///< dissipated by rolling resistance
    double mechanical_change = 0.0;           ///< change of kinetic + potential + elastic energy
    std::vector<double> layer_dissipation{};  ///< per layer (solver's energy_layers)
    /// Per layer: the mean over the interval of the kinetic energy relative to the enclosure
    /// of the particles whose centre is in it (EnergyLedger::layer_kinetic_time) [J].
    std::vector<double> layer_kinetic_mean{};

    double dissipated() const { return normal_damping + friction + rolling; }
    /// Time-averaged dissipated power [W].
    double dissipated_power_w() const { return duration_s > 0.0 ? dissipated() / duration_s : 0.0; }
    /// wall_work - mechanical_change - dissipated: zero for an exact ledger.
    double balance_error() const { return wall_work - mechanical_change - dissipated(); }
};

/// The interval from `start` to `end` (two Solver::energy() snapshots, same reset epoch).
EnergyInterval energy_between(const EnergyLedger& start, const EnergyLedger& end,
                              double duration_s);

/// Per-period accounting: construct at the start of the first period, call end_period() at
/// every period boundary (after the last step of the period). Costs one Solver::energy() call
/// (O(particles + contacts)) per period; needs SolverOptions::track_energy.
class EnergyPeriods {
  public:
    explicit EnergyPeriods(const Solver& solver);
    /// Closes the period ending at the solver's present time, stores it and returns it.
    const EnergyInterval& end_period(const Solver& solver);
    const std::vector<EnergyInterval>& periods() const { return periods_; }

  private:
    EnergyLedger last_;
    double last_time_s_ = 0.0;
    std::vector<EnergyInterval> periods_;
};

}  // namespace sb::dem

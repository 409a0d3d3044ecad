// Energy exchanged over intervals from snapshots of the solver's ledger.
#include "dem/energy_periods.hpp"

#include <stdexcept>

namespace sb::dem {

EnergyInterval energy_between(const EnergyLedger& a, const EnergyLedger& b, double duration_s) {
    EnergyInterval out;
    out.duration_s = duration_s;
    out.wall_work = b.wall_work - a.wall_work;
    out.normal_damping = b.normal_damping - a.normal_damping;
    out.friction = b.friction - a.friction;
    out.rolling = b.rolling - a.rolling;
    out.mechanical_change = b.mechanical() - a.mechanical();
    out.layer_dissipation = b.layer_dissipation;
    for (std::size_t k = 0; k < out.layer_dissipation.size() && k < a.layer_dissipation.size();
         ++k) {
        out.layer_dissipation[k] -= a.layer_dissipation[k];
    }
    out.layer_kinetic_mean = b.layer_kinetic_time;
    for (std::size_t k = 0; k < out.layer_kinetic_mean.size(); ++k) {
        const double before = k < a.layer_kinetic_time.size() ? a.layer_kinetic_time[k] : 0.0;
        out.layer_kinetic_mean[k] =
            duration_s > 0.0 ? (out.layer_kinetic_mean[k] - before) / duration_s : 0.0;
    }
    return out;
}

EnergyPeriods::EnergyPeriods(const Solver& solver)
    : last_(solver.energy()), last_time_s_(solver.time()) {
    if (!solver.options().track_energy) {
        throw std::invalid_argument(
            "EnergyPeriods: the solver keeps no energy ledger "
            "(track_energy = false)");
    }
}

const EnergyInterval& EnergyPeriods::end_period(const Solver& solver) {
    EnergyLedger now = solver.energy();
    periods_.push_back(energy_between(last_, now, solver.time() - last_time_s_));
    last_ = std::move(now);
    last_time_s_ = solver.time();
    return periods_.back();
}

}  // namespace sb::dem

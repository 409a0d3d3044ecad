// The coupled specimen as the controller's plant: one call = one period of the stepped sine.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <optional>
#include <vector>

#include "bench/coupled_specimen.hpp"
#include "control/plant.hpp"

namespace sb::bench {

/// Energies of a DEM damper over one period [J] (dem::EnergyLedger differences), or their
/// mean per period over a window.
struct PeriodEnergy {
    double wall_work_j = 0.0;       ///< work of the walls on the particles
    double normal_damping_j = 0.0;  ///< dissipated by the normal dashpots
    double friction_j = 0.0;        ///< dissipated by sliding friction
    double rolling_j = 0.0;         ///< dissipated by rolling resistance
    double kinetic_j = 0.0;         ///< kinetic energy of the particles at the period's end
    std::vector<double> layer_dissipation_j;  ///< per horizontal layer, bottom first
    /// Per horizontal layer: the mean kinetic energy, relative to the enclosure, of the
    /// particles whose centre is in it [J] (dem::EnergyLedger::layer_kinetic_time).
    std::vector<double> layer_kinetic_j;
};

/// What one period gave on every channel.
struct PeriodChannels {
    std::vector<double> mean;                         ///< per channel
    std::vector<double> mean_square;                  ///< per channel, mean removed
    std::vector<double> minimum, maximum;             ///< per channel, over every step
    std::vector<std::complex<double>> fundamental;    ///< per channel, x = Re{X e^{i w t}}
    std::vector<std::complex<double>> second;         ///< per channel, harmonic at 2 w
    std::vector<std::complex<double>> third;          ///< per channel, harmonic at 3 w
    std::vector<std::vector<double>> series;          ///< decimated samples, per channel
    std::vector<std::optional<PeriodEnergy>> energy;  ///< per attachment (DEM dampers)
};

/// Channel values over a window of periods.
struct WindowChannels {
    std::vector<double> rms;                        ///< mean removed over the window
    std::vector<std::complex<double>> fundamental;  ///< mean of the periods' phasors
    /// |H2| / |H1| and |H3| / |H1| of the window's mean phasors, per channel [-].
    std::vector<double> h2_ratio;
    std::vector<double> h3_ratio;
};

class SpecimenPlant : public control::Plant {
  public:
    /// `series_samples_per_period` > 0 keeps that many samples of every period.
    /// `scale_response_on_update`: when the amplitude changes at the same frequency, the
    /// structure's response is first scaled by new/old about its mean over the last period
    /// (CoupledSpecimen::scale_response), so the update lands near the new steady state.
    /// `track_energy`: record every DEM damper's energies per period (its solver keeps the
    /// ledger).
    SpecimenPlant(CoupledSpecimen& specimen, int series_samples_per_period,
                  bool scale_response_on_update = false, bool track_energy = false);

    /// Runs one period at `amplitude`; the first call at a new frequency switches the
    /// specimen's time step. Reports the control channel (the first acceleration channel).
    control::PeriodResult run_period(double amplitude, double frequency_hz) override;

    /// Forgets the periods of the previous point (a point never scales the response of the
    /// one before, so a resumed sweep repeats the same arithmetic).
    void begin_point() {
        periods_.clear();
        have_period_mean_ = false;
    }
    [[nodiscard]] const std::vector<PeriodChannels>& periods() const { return periods_; }
    /// Steady values over periods [begin, end) of the current point.
    [[nodiscard]] WindowChannels window(int begin, int end) const;
    /// Mean energies per period over periods [begin, end), per attachment (empty for those
    /// without a DEM ledger, and without energy tracking).
    [[nodiscard]] std::vector<std::optional<PeriodEnergy>> window_energy(int begin, int end) const;
    [[nodiscard]] long long steps_run() const { return steps_run_; }

  private:
    CoupledSpecimen* specimen_;
    int series_samples_per_period_;
    bool scale_response_on_update_;
    bool track_energy_;
    double last_amplitude_ = 0.0;    ///< amplitude of the last period run [input unit]
    bool have_period_mean_ = false;  ///< a whole period at the current frequency was run
    Eigen::VectorXd period_mean_q_;  ///< mean modal displacement over the last period
    Eigen::VectorXd period_sum_q_;
    std::vector<PeriodChannels> periods_;
    std::vector<double> values_;
    std::vector<std::vector<double>> samples_;
    long long steps_run_ = 0;
};

}  // namespace sb::bench

// The coupled specimen as the controller's plant.
#include "bench/specimen_plant.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/units.hpp"
#include "dem/energy_periods.hpp"
#include "identification/harmonics.hpp"

namespace sb::bench {

namespace {

/// A damper's ledger now and the damper's clock.
struct LedgerSnapshot {
    dem::EnergyLedger ledger;
    double time_s = 0.0;
};

LedgerSnapshot ledger_now(const dem::Solver& solver) { return {solver.energy(), solver.time()}; }

/// One period's energies: the cumulative works' differences, the kinetic energy at its end,
/// the layers' agitation averaged over it.
PeriodEnergy over_period(const LedgerSnapshot& begin, const LedgerSnapshot& end) {
    const dem::EnergyInterval interval =
        dem::energy_between(begin.ledger, end.ledger, end.time_s - begin.time_s);
    PeriodEnergy e;
    e.wall_work_j = interval.wall_work;
    e.normal_damping_j = interval.normal_damping;
    e.friction_j = interval.friction;
    e.rolling_j = interval.rolling;
    e.kinetic_j = end.ledger.kinetic_translational + end.ledger.kinetic_rotational;
    e.layer_dissipation_j = interval.layer_dissipation;
    e.layer_kinetic_j = interval.layer_kinetic_mean;
    return e;
}

/// sum += values / count, element by element (sum sized to values the first time).
void add_mean_share(std::vector<double>& sum, const std::vector<double>& values, double count) {
    sum.resize(values.size(), 0.0);
    for (std::size_t k = 0; k < values.size(); ++k) sum[k] += values[k] / count;
}

}  // namespace

SpecimenPlant::SpecimenPlant(CoupledSpecimen& specimen, int series_samples_per_period,
                             bool scale_response_on_update, bool track_energy)
    : specimen_(&specimen),
      series_samples_per_period_(series_samples_per_period),
      scale_response_on_update_(scale_response_on_update),
      track_energy_(track_energy) {}

control::PeriodResult SpecimenPlant::run_period(double amplitude, double frequency_hz) {
    if (frequency_hz != specimen_->frequency_hz()) {
        specimen_->set_frequency(frequency_hz);
        have_period_mean_ = false;
    }
    // Every period starts at phase 0 of the point's sine, so the state now is that of the
    // start of a period: scaling the response about the last period's mean carries a steady
    // response at the old amplitude to the steady response at the new one.
    if (scale_response_on_update_ && have_period_mean_ && last_amplitude_ > 0.0 &&
        amplitude != last_amplitude_) {
        specimen_->scale_response(amplitude / last_amplitude_, period_mean_q_);
    }
    const int n = specimen_->steps_per_period();
    const std::size_t channels = specimen_->channel_names().size();
    samples_.resize(channels);
    for (auto& s : samples_) {
        s.assign(static_cast<std::size_t>(n), 0.0);
    }
    period_sum_q_.setZero(specimen_->modal_displacement().size());
    // The ledgers at the period's start (after any scaling, which restarts them).
    const auto& attachments = specimen_->attachments();
    std::vector<std::optional<LedgerSnapshot>> energy_begin(attachments.size());
    if (track_energy_) {
        for (std::size_t a = 0; a < attachments.size(); ++a) {
            if (const dem::Solver* solver = dem_solver(attachments[a])) {
                energy_begin[a] = ledger_now(*solver);
            }
        }
    }
    for (int k = 0; k < n; ++k) {
        specimen_->step(amplitude, values_);
        for (std::size_t c = 0; c < channels; ++c) {
            samples_[c][static_cast<std::size_t>(k)] = values_[c];
        }
        if (scale_response_on_update_) {
            period_sum_q_ += specimen_->modal_displacement();
        }
    }
    steps_run_ += n;
    if (scale_response_on_update_) {
        period_mean_q_ = period_sum_q_ / n;
        have_period_mean_ = true;
    }
    last_amplitude_ = amplitude;

    // Every period starts at phase 0 of the point's sine, so the sample k (end of step k) is
    // at time (k + 1) dt of the period: X = (2/N) sum x_k e^{-i w t_k} is the exact
    // fundamental of a signal sampled over one whole period.
    PeriodChannels period;
    period.mean.resize(channels);
    period.mean_square.resize(channels);
    period.minimum.resize(channels);
    period.maximum.resize(channels);
    period.fundamental.resize(channels);
    period.second.resize(channels);
    period.third.resize(channels);
    const double w_dt = kTwoPi / n;
    std::vector<std::complex<double>> phasor(static_cast<std::size_t>(n));
    std::vector<std::complex<double>> phasor2(static_cast<std::size_t>(n));
    std::vector<std::complex<double>> phasor3(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
        const auto i = static_cast<std::size_t>(k);
        phasor[i] = std::polar(1.0, -w_dt * (k + 1));
        phasor2[i] = std::polar(1.0, -2.0 * w_dt * (k + 1));
        phasor3[i] = std::polar(1.0, -3.0 * w_dt * (k + 1));
    }
    for (std::size_t c = 0; c < channels; ++c) {
        const auto& x = samples_[c];
        double sum = 0.0;
        std::complex<double> acc = 0.0;
        std::complex<double> acc2 = 0.0;
        std::complex<double> acc3 = 0.0;
        for (int k = 0; k < n; ++k) {
            const auto i = static_cast<std::size_t>(k);
            sum += x[i];
            acc += x[i] * phasor[i];
            acc2 += x[i] * phasor2[i];
            acc3 += x[i] * phasor3[i];
        }
        const double mean = sum / n;
        double ms = 0.0;
        for (double v : x) {
            ms += (v - mean) * (v - mean);
        }
        period.mean[c] = mean;
        period.mean_square[c] = ms / n;
        const auto [low, high] = std::minmax_element(x.begin(), x.end());
        period.minimum[c] = *low;
        period.maximum[c] = *high;
        // Whole periods sampled uniformly: the DFT bins at w, 2w, 3w are exact harmonics.
        period.fundamental[c] = 2.0 / n * acc;
        period.second[c] = 2.0 / n * acc2;
        period.third[c] = 2.0 / n * acc3;
        if (series_samples_per_period_ > 0) {
            const int stride = std::max(1, n / series_samples_per_period_);
            std::vector<double> kept;
            for (int k = stride - 1; k < n; k += stride) {
                kept.push_back(x[static_cast<std::size_t>(k)]);
            }
            period.series.push_back(std::move(kept));
        }
    }

    if (track_energy_) {
        period.energy.resize(attachments.size());
        for (std::size_t a = 0; a < attachments.size(); ++a) {
            if (energy_begin[a]) {
                period.energy[a] =
                    over_period(*energy_begin[a], ledger_now(*dem_solver(attachments[a])));
            }
        }
    }

    control::PeriodResult result;
    result.rms = std::sqrt(period.mean_square[1]);
    // Harmonics 1..10 of the control channel (FFTW, identification/harmonics): the distortion
    // the particles add is part of what a point records.
    const auto analysis = identification::analyse_harmonics(samples_[1], 1.0 / specimen_->dt_s(),
                                                            specimen_->frequency_hz(), 10);
    result.harmonics.assign(analysis.amplitude.begin() + 1, analysis.amplitude.end());
    periods_.push_back(std::move(period));
    return result;
}

WindowChannels SpecimenPlant::window(int begin, int end) const {
    if (begin < 0 || end > static_cast<int>(periods_.size()) || begin >= end) {
        throw std::out_of_range("specimen plant: window [" + std::to_string(begin) + ", " +
                                std::to_string(end) + ") outside the " +
                                std::to_string(periods_.size()) + " periods of the point");
    }
    const std::size_t channels = periods_.front().mean.size();
    const double count = end - begin;
    WindowChannels out;
    out.rms.assign(channels, 0.0);
    out.fundamental.assign(channels, 0.0);
    out.h2_ratio.assign(channels, 0.0);
    out.h3_ratio.assign(channels, 0.0);
    for (std::size_t c = 0; c < channels; ++c) {
        double mean = 0.0;
        for (int p = begin; p < end; ++p) {
            mean += periods_[static_cast<std::size_t>(p)].mean[c] / count;
        }
        // Window mean square about the window mean, from the periods' own means and spreads.
        double ms = 0.0;
        for (int p = begin; p < end; ++p) {
            const auto& period = periods_[static_cast<std::size_t>(p)];
            const double offset = period.mean[c] - mean;
            ms += (period.mean_square[c] + offset * offset) / count;
            out.fundamental[c] += period.fundamental[c] / count;
        }
        out.rms[c] = std::sqrt(ms);
        std::complex<double> second = 0.0;
        std::complex<double> third = 0.0;
        for (int p = begin; p < end; ++p) {
            second += periods_[static_cast<std::size_t>(p)].second[c] / count;
            third += periods_[static_cast<std::size_t>(p)].third[c] / count;
        }
        const double first = std::abs(out.fundamental[c]);
        out.h2_ratio[c] = first > 0.0 ? std::abs(second) / first : 0.0;
        out.h3_ratio[c] = first > 0.0 ? std::abs(third) / first : 0.0;
    }
    return out;
}

std::vector<std::optional<PeriodEnergy>> SpecimenPlant::window_energy(int begin, int end) const {
    std::vector<std::optional<PeriodEnergy>> out(specimen_->attachments().size());
    if (!track_energy_ || begin >= end) return out;
    const double count = end - begin;
    for (std::size_t a = 0; a < out.size(); ++a) {
        for (int p = begin; p < end; ++p) {
            const auto& e = periods_[static_cast<std::size_t>(p)].energy;
            if (a >= e.size() || !e[a]) continue;
            if (!out[a]) out[a] = PeriodEnergy{};
            PeriodEnergy& m = *out[a];
            m.wall_work_j += e[a]->wall_work_j / count;
            m.normal_damping_j += e[a]->normal_damping_j / count;
            m.friction_j += e[a]->friction_j / count;
            m.rolling_j += e[a]->rolling_j / count;
            m.kinetic_j += e[a]->kinetic_j / count;
            add_mean_share(m.layer_dissipation_j, e[a]->layer_dissipation_j, count);
            add_mean_share(m.layer_kinetic_j, e[a]->layer_kinetic_j, count);
        }
    }
    return out;
}

}  // namespace sb::bench

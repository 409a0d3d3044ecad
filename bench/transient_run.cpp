// A run from rest, period by period.
#include "bench/transient_run.hpp"

#include <algorithm>
#include <cmath>

#include "config/value.hpp"

namespace sb::bench {

// Numbers in shortest round-trip digits (config::number_text): the rows a checkpoint carries
// come back exact.
using config::number_text;

void run_transient(CoupledSpecimen& specimen, SpecimenPlant& plant, const TransientDrive& drive,
                   SweepCheckpoint& checkpoint, const std::function<void()>& save,
                   const std::function<void(int)>& progress) {
    const double f = drive.frequency_hz;
    const double period_s = 1.0 / f;
    if (checkpoint.transient_periods == 0 && checkpoint.transient_envelope.empty()) {
        // At rest: no harmonic response, only the static deflection under the weight.
        specimen.set_frequency(f);
        specimen.start_from_linear_steady_state(0.0, 0.0);
        checkpoint.state = specimen.state();
    }
    while (checkpoint.transient_periods < drive.periods) {
        specimen.set_frequency(f);
        specimen.restore(checkpoint.state);
        plant.begin_point();
        const int first = checkpoint.transient_periods;
        const int count = std::min(drive.checkpoint_periods, drive.periods - first);
        for (int p = 0; p < count; ++p) plant.run_period(drive.amplitude, f);
        const int steps = specimen.steps_per_period();
        for (int p = 0; p < count; ++p) {
            const PeriodChannels& period = plant.periods()[static_cast<std::size_t>(p)];
            const double start_s = (first + p) * period_s;
            std::string envelope = std::to_string(first + p) + "," + number_text(start_s);
            for (double v : period.minimum) envelope += "," + number_text(v);
            for (double v : period.maximum) envelope += "," + number_text(v);
            checkpoint.transient_envelope.push_back(std::move(envelope));
            const std::size_t samples = period.series.front().size();
            const int stride = std::max(1, steps / static_cast<int>(samples));
            for (std::size_t k = 0; k < samples; ++k) {
                // Sample k is the end of step (k + 1) stride of the period.
                const double t = start_s + static_cast<double>((k + 1) * stride) * period_s / steps;
                std::string row = number_text(t);
                for (const auto& channel : period.series) row += "," + number_text(channel[k]);
                checkpoint.transient_series.push_back(std::move(row));
            }
        }
        checkpoint.transient_periods = first + count;
        checkpoint.state = specimen.state();
        save();
        progress(checkpoint.transient_periods);
    }
}

std::vector<std::string> release_events(const CampaignSpec& campaign) {
    std::vector<std::string> out;
    for (const DamperSpec& damper : campaign.dampers) {
        if (damper.locked || !(damper.lock.release_time_s > 0.0)) continue;
        const int count = damper.particles.count;
        const auto freed =
            std::min(count, static_cast<int>(std::llround(damper.lock.release_fraction * count)));
        out.push_back(damper.name + ": " + std::to_string(freed) + " of " + std::to_string(count) +
                      " particles freed at t = " + number_text(damper.lock.release_time_s) + " s");
    }
    return out;
}

std::string transient_series_header(const std::vector<std::string>& channels) {
    std::string header = "time_s";
    for (const auto& c : channels) header += "," + c;
    return header;
}

std::string transient_envelope_header(const std::vector<std::string>& channels) {
    std::string header = "period,start_s";
    for (const auto& c : channels) header += "," + c + "_min";
    for (const auto& c : channels) header += "," + c + "_max";
    return header;
}

}  // namespace sb::bench

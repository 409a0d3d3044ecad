// A random test as one sweep of a campaign.
#include "bench/random_sweep.hpp"

#include <cmath>
#include <sstream>

#include "bench/random_test.hpp"
#include "core/significant_text.hpp"
#include "core/units.hpp"

namespace sb::bench {

double linear_start_drive_rms(const RandomSpec& spec, double target_rms,
                              const std::function<double(double)>& linear_gain) {
    const int lines = 200;
    double mean_square_gain = 0.0;
    for (int k = 0; k < lines; ++k) {
        const double f = spec.low_hz + (spec.high_hz - spec.low_hz) * (k + 0.5) / lines;
        mean_square_gain += std::pow(linear_gain(f), 2) / lines;
    }
    return target_rms / std::sqrt(mean_square_gain);
}

void run_random_sweep(CoupledSpecimen& specimen, const RandomSweep& sweep,
                      SweepCheckpoint& checkpoint, const std::function<void()>& save,
                      SweepProgress& progress, SweepResult& out) {
    const RandomSpec& spec = *sweep.spec;
    const SweepTask& task = *sweep.task;
    RandomTestSetup setup;
    setup.spec = spec;
    setup.seed = task.seed;
    setup.target_rms_m_s2 = sweep.target_rms_m_s2;
    setup.start_drive_rms =
        sweep.target_rms_m_s2
            ? linear_start_drive_rms(spec, *sweep.target_rms_m_s2, sweep.linear_gain)
            : task.level_g;
    const std::string name =
        sweep.arrangement + " " + significant_text(task.level_g) + " " + task.level_unit;
    const auto spectra =
        run_random_test(specimen, setup, checkpoint, save,
                        [&](const std::string& line) { progress.note(name + ": " + line); });

    const double sample_rate_hz = spectra.segment_samples() * spec.resolution_hz;
    const RandomProgress& done = *checkpoint.random;
    const double measured = band_rms(spectra, 1, sample_rate_hz);
    const double achieved = done.level_rms;
    const bool held = !sweep.target_rms_m_s2 ||
                      std::abs(achieved / *sweep.target_rms_m_s2 - 1.0) <= spec.tolerance;
    out.rows = random_rows(spectra, sweep.arrangement, task.level_g, held ? "random" : "closest");
    for (auto& row : out.rows) {
        row.filling = task.filling;
        out.frequencies_hz.push_back(row.frequency_hz);
    }
    std::istringstream spectra_lines(random_spectra_text(spectra, specimen.channel_names()));
    for (std::string line; std::getline(spectra_lines, line);) {
        out.random_spectra.push_back(line);
    }
    out.settings.push_back(name + ": random test, " + std::to_string(done.level_segments) +
                           " level segments and " + std::to_string(spectra.sums().segments) +
                           " averages of " + significant_text(1.0 / spec.resolution_hz) +
                           " s; drive " + significant_text(done.drive_rms, 4) + " RMS, control " +
                           significant_text(achieved / kStandardGravity, 4) + " g RMS in " +
                           significant_text(spec.low_hz) + "-" + significant_text(spec.high_hz) +
                           " Hz (" + significant_text(measured / kStandardGravity, 4) +
                           " g measured)" +
                           (held ? "" : " (the level did not hold: lines marked closest)"));
    progress.note(out.settings.back());
    // The specimen's periods here are half segments.
    out.periods_simulated = 2 * done.level_segments + done.halves;
}

}  // namespace sb::bench

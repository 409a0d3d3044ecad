// The random test, half segment by half segment.
#include "bench/random_test.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <span>

#include "bench/random_noise.hpp"
#include "config/value.hpp"
#include "core/significant_text.hpp"

namespace sb::bench {
namespace {

using Samples = std::vector<std::vector<double>>;  ///< per channel, the reference first

/// The boxcar of one sample's width seen at f: sinc(f / fs).
double boxcar_gain(double frequency_hz, double sample_rate_hz) {
    const double x = std::numbers::pi * frequency_hz / sample_rate_hz;
    return x == 0.0 ? 1.0 : std::sin(x) / x;
}

/// `first` then `second`, per channel; the segments Welch takes.
void add_segment(identification::WelchSpectra& spectra, const Samples& first,
                 const Samples& second) {
    Samples joined(first.size());
    for (std::size_t c = 0; c < first.size(); ++c) {
        joined[c] = first[c];
        joined[c].insert(joined[c].end(), second[c].begin(), second[c].end());
    }
    std::vector<std::span<const double>> responses(joined.begin() + 1, joined.end());
    spectra.add_segment(joined.front(), responses);
}

}  // namespace

double band_rms(const identification::WelchSpectra& spectra, int channel, double sample_rate_hz) {
    double mean_square = 0.0;
    for (int k = 0; k < spectra.bins(); ++k) {
        const double psd =
            channel == 0 ? spectra.reference_psd(k) : spectra.response_psd(channel - 1, k);
        const double gain = boxcar_gain(spectra.frequency_hz(k), sample_rate_hz);
        mean_square += psd / (gain * gain);
    }
    return std::sqrt(mean_square * spectra.resolution_hz());
}

double expected_band_rms(const identification::WelchSpectra& spectra, double drive_rms,
                         double low_hz, double high_hz) {
    const double density = drive_rms * drive_rms / (high_hz - low_hz);
    double mean_square = 0.0;
    for (int k = 0; k < spectra.bins(); ++k) {
        const double f = spectra.frequency_hz(k);
        if (f < low_hz || f > high_hz) continue;
        mean_square += std::norm(spectra.h1(0, k)) * density;
    }
    return std::sqrt(mean_square * spectra.resolution_hz());
}

identification::WelchSpectra run_random_test(CoupledSpecimen& specimen,
                                             const RandomTestSetup& setup,
                                             SweepCheckpoint& checkpoint,
                                             const std::function<void()>& save,
                                             const std::function<void(const std::string&)>& note) {
    const RandomSpec& spec = setup.spec;
    const double half_s = 0.5 / spec.resolution_hz;
    // One "period" of the specimen is half a segment: a whole number of steps.
    specimen.set_frequency(2.0 * spec.resolution_hz);
    const int steps = specimen.steps_per_period();
    const int half_samples =
        std::min(steps, std::max(8, static_cast<int>(std::ceil(4.0 * spec.high_hz * half_s))));
    const int segment_samples = 2 * half_samples;
    const double sample_rate_hz = segment_samples * spec.resolution_hz;
    const auto channels = specimen.channel_names().size();  // the reference first
    identification::WelchSpectra averaged(segment_samples, sample_rate_hz, spec.low_hz,
                                          spec.high_hz, static_cast<int>(channels) - 1);
    // The noise record covers the longest run (level segments and averaging).
    const auto noise = std::make_shared<const BandLimitedNoise>(
        spec.low_hz, spec.high_hz, spec.longest_run_s() + 2.0 * half_s, setup.seed);
    const auto waveform = [noise](double t_s) { return (*noise)(t_s); };

    if (!checkpoint.random) {
        // At rest: only the static deflection under the weight.
        specimen.start_from_linear_steady_state(0.0, 0.0);
        checkpoint.random.emplace();
        checkpoint.random->drive_rms = setup.start_drive_rms;
        checkpoint.state = specimen.state();
    }
    RandomProgress* p = &*checkpoint.random;
    if (!p->sums.reference.empty()) averaged.restore(p->sums);
    const auto resume = [&] {
        specimen.set_frequency(2.0 * spec.resolution_hz);
        specimen.restore(checkpoint.state);
        // The noise goes on where the run stands: every segment run so far, half by half.
        specimen.set_waveform(waveform, (2 * p->level_segments + p->halves) * half_s);
    };
    const auto checkpoint_now = [&] {
        p->sums = averaged.sums();
        checkpoint.state = specimen.state();
        save();  // re-reads the checkpoint from its text, as a resumed test does
        p = &*checkpoint.random;
        resume();
    };
    std::vector<double> values;
    const auto run_half = [&] {
        Samples out(channels, std::vector<double>(static_cast<std::size_t>(half_samples), 0.0));
        std::vector<int> count(static_cast<std::size_t>(half_samples), 0);
        for (int k = 0; k < steps; ++k) {
            specimen.step(p->drive_rms, values);
            const auto j =
                static_cast<std::size_t>(static_cast<long long>(k) * half_samples / steps);
            for (std::size_t c = 0; c < channels; ++c) out[c][j] += values[c];
            ++count[j];
        }
        for (auto& channel : out) {
            for (std::size_t j = 0; j < channel.size(); ++j) channel[j] /= count[j];
        }
        return out;
    };
    resume();

    // The drive's RMS brought to the target by the level the spectra so far expect.
    const auto adjust = [&](double largest_step) {
        p->level_rms = expected_band_rms(averaged, p->drive_rms, spec.low_hz, spec.high_hz);
        if (!setup.target_rms_m_s2 || !(p->level_rms > 0.0)) return true;
        const double target = *setup.target_rms_m_s2;
        const bool held = std::abs(p->level_rms / target - 1.0) <= spec.tolerance;
        p->drive_rms *= std::clamp(target / p->level_rms, 1.0 / largest_step, largest_step);
        return held;
    };
    while (!p->level_done) {
        // Whole segments, not overlapping, into the same sums: the estimate of H1 grows
        // better with every segment whatever the drive was.
        const Samples first = run_half();
        const Samples second = run_half();
        add_segment(averaged, first, second);
        ++p->level_segments;
        const double drive = p->drive_rms;
        const bool held = adjust(4.0);
        p->level_done = held || p->level_segments >= spec.level_blocks;
        note("random level segment " + std::to_string(p->level_segments) + ": drive " +
             significant_text(drive, 4) + " RMS, control " + significant_text(p->level_rms, 4) +
             " RMS expected in the band" +
             (setup.target_rms_m_s2
                  ? " (target " + significant_text(*setup.target_rms_m_s2, 4) + ")"
                  : std::string()));
        if (p->level_done) averaged.clear();  // the averaging starts from no segment
        checkpoint_now();
    }
    while (p->halves < spec.averages + 1) {
        Samples half = run_half();
        if (!p->tail.empty()) {
            add_segment(averaged, p->tail, half);
            // As a random controller goes on closing its loop while it averages: small steps,
            // H1 (a ratio to the measured force) is not changed by them.
            adjust(1.25);
        }
        p->tail = std::move(half);
        ++p->halves;
        const bool last = p->halves == spec.averages + 1;
        if (last) p->tail.clear();
        if (last || p->halves % spec.checkpoint_segments == 0) checkpoint_now();
    }
    return averaged;
}

std::vector<identification::PointRow> random_rows(const identification::WelchSpectra& spectra,
                                                  const std::string& arrangement, double level_g,
                                                  const std::string& status) {
    std::vector<identification::PointRow> rows;
    const double df = spectra.resolution_hz();
    for (int k = 0; k < spectra.bins(); ++k) {
        identification::PointRow row;
        row.arrangement = arrangement;
        row.level_g = level_g;
        row.frequency_hz = spectra.frequency_hz(k);
        row.status = status;
        identification::ChannelValue reference;
        reference.rms = std::sqrt(spectra.reference_psd(k) * df);
        reference.amplitude = 1.0;
        row.values.push_back(reference);
        for (int c = 0; c < spectra.channels(); ++c) {
            identification::ChannelValue v;
            v.rms = std::sqrt(spectra.response_psd(c, k) * df);
            v.amplitude = spectra.h1(c, k);
            row.values.push_back(v);
        }
        rows.push_back(std::move(row));
    }
    return rows;
}

std::string random_spectra_text(const identification::WelchSpectra& spectra,
                                const std::vector<std::string>& channel_names) {
    using config::number_text;
    std::string text = "frequency_hz," + channel_names.front() + "_psd";
    for (std::size_t c = 1; c < channel_names.size(); ++c) {
        const std::string& n = channel_names[c];
        text += "," + n + "_psd," + n + "_h1_re," + n + "_h1_im," + n + "_coherence";
    }
    text += "\n";
    for (int k = 0; k < spectra.bins(); ++k) {
        text += number_text(spectra.frequency_hz(k)) + "," + number_text(spectra.reference_psd(k));
        for (int c = 0; c < spectra.channels(); ++c) {
            const auto h = spectra.h1(c, k);
            text += "," + number_text(spectra.response_psd(c, k)) + "," + number_text(h.real()) +
                    "," + number_text(h.imag()) + "," + number_text(spectra.coherence(c, k));
        }
        text += "\n";
    }
    return text;
}

}  // namespace sb::bench

// A random test (campaign.random): the specimen driven by band-limited noise, its level
// brought in segment by segment, then H1 by Welch's averaged spectra, as a random test's
// analyser measures it (paper 003, Figs. 6-8).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bench/campaign_spec.hpp"
#include "bench/coupled_specimen.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "identification/recording.hpp"
#include "identification/welch.hpp"

namespace sb::bench {

struct RandomTestSetup {
    RandomSpec spec;
    /// The band RMS the control channel must hold [m/s^2]; none: a fixed drive.
    std::optional<double> target_rms_m_s2;
    double start_drive_rms = 0.0;  ///< the drive's RMS at the start [N]
    std::uint64_t seed = 0;        ///< of the noise
};

/// Runs the test, or goes on with it from `checkpoint.random`. The specimen starts at rest
/// (the static deflection under the attachments' weight) and runs half segments of
/// 1 / (2 resolution_hz): the level segments first, each of two halves, the drive's RMS
/// scaled by target / expected_band_rms() of every level segment so far after each, until it
/// holds within the tolerance (at most level_blocks; a fixed drive runs one, to let the start
/// die out); then averages + 1 halves, each with the one before a Hann segment of Welch's
/// estimate, the drive still corrected by at most 25 % after each from the averages so far
/// (checkpoint.random->level_rms: the level expected over the last segment). Every channel is
/// recorded as the mean over each of 8 samples per period of the band's top (a boxcar
/// anti-alias filter, the same on every channel, so H1 keeps its value; its droop is divided
/// out of the RMS). The checkpoint is saved after every level segment and every
/// checkpoint_segments halves, the specimen going through state() and restore() whether or
/// not the run was interrupted, so a resumed test repeats the same arithmetic. `note` hears
/// where the level stands.
identification::WelchSpectra run_random_test(CoupledSpecimen& specimen,
                                             const RandomTestSetup& setup,
                                             SweepCheckpoint& checkpoint,
                                             const std::function<void()>& save,
                                             const std::function<void(const std::string&)>& note);

/// The band RMS of a channel (0: the reference) from Welch spectra whose samples are means over
/// 1 / sample_rate_hz (the boxcar's droop sinc²(f / fs) divided out of the densities).
double band_rms(const identification::WelchSpectra& spectra, int channel, double sample_rate_hz);

/// The control channel's band RMS that the drive's nominal spectrum (flat, `drive_rms` over
/// low_hz-high_hz) gives through the spectra's H1 of channel 1: sqrt(Σ |H1|² S0 df). A
/// random controller judges the level this way, not by the measured RMS: over one segment
/// T of a mode of damping ζ at f_n the measured RMS scatters by about 1/sqrt(π ζ f_n T)
/// (Bendat & Piersol 2010, §8.2.1; 25 % for 1.4 % at 47 Hz over 8 s), because the few
/// lines of the drive that excite the resonance have random magnitudes; H1 does not.
double expected_band_rms(const identification::WelchSpectra& spectra, double drive_rms,
                         double low_hz, double high_hz);

/// points.csv rows of a random test: one per line of the band, the reference's amplitude 1
/// (its RMS that of the line), each channel's H1 (its RMS that of the line).
std::vector<identification::PointRow> random_rows(const identification::WelchSpectra& spectra,
                                                  const std::string& arrangement, double level_g,
                                                  const std::string& status);

/// random/<sweep>.csv: per line, the frequency, the reference's PSD, and per channel its PSD,
/// H1 and coherence.
std::string random_spectra_text(const identification::WelchSpectra& spectra,
                                const std::vector<std::string>& channel_names);

}  // namespace sb::bench

// The recording directory of formats.md as data: what was recorded and one row per point.
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <vector>

namespace sb::identification {

/// Role of a channel (formats.md).
enum class ChannelRole {
    reference,  ///< denominator of transfer functions (exactly one)
    control,    ///< the channel whose RMS was controlled (at most one)
    response,   ///< any other measured channel
};

/// One channel of `[channels.NAME]` in recording.toml.
struct Channel {
    std::string name;      ///< the table key, also the points.csv column prefix
    std::string quantity;  ///< force | acceleration | velocity | displacement | voltage
    std::string unit;      ///< SI unit as text, e.g. "m/s^2"
    std::string location;  ///< free text or a named point of a config
    ChannelRole role = ChannelRole::response;
};

/// `[recording]` of recording.toml.
struct RecordingInfo {
    std::string name;
    std::string kind = "measured";     ///< measured | simulated
    std::string excitation = "force";  ///< force | base
    std::string description;
};

/// A time history (series/*.csv): uniform sampling, one column per channel.
struct TimeHistory {
    std::vector<std::string> channels;         ///< column names after time_s
    std::vector<double> time_s;                ///< [s]
    std::vector<std::vector<double>> columns;  ///< columns[c][sample] [channel unit]

    /// 1 / (mean sampling step) [Hz]; 0 with fewer than 2 samples.
    double sample_rate_hz() const;
};

/// One channel's values at one point.
struct ChannelValue {
    double rms = 0.0;                ///< RMS over the steady window [channel unit]
    std::complex<double> amplitude;  ///< fundamental, peak, x(t) = Re{X e^{iωt}} [channel unit]
    /// True when points.csv left the three cells empty and rms and amplitude were computed
    /// from the point's time history (fundamental over whole periods).
    bool from_series = false;
    /// |X_2|/|X_1| of this channel over the steady window [-]; NaN when not known (a file
    /// without the columns, an empty cell, a harmonic at or above Nyquist). A ratio that
    /// differs between measurement and model points at nonlinear physics the model lacks
    /// (contact, impacts of the particles), which the fundamental alone hides.
    double h2_ratio = std::numeric_limits<double>::quiet_NaN();
    double h3_ratio = std::numeric_limits<double>::quiet_NaN();  ///< |X_3|/|X_1| [-], as h2
};

/// One row of points.csv.
struct PointRow {
    std::string arrangement;  ///< e.g. "H-0"
    /// Target RMS level [g]; under a fixed drive the drive's peak amplitude in its own unit
    /// (N, m/s^2, m or V: docs/campaign.md).
    double level_g = 0.0;
    double frequency_hz = 0.0;  ///< excitation frequency [Hz]
    /// converged | limit-cycle-2 | closest | unsettled | measured (a run or a lab); random (a
    /// line of a random test's H1: the reference's amplitude 1, each channel's H1); predicted
    /// | extrapolated | uncertain (`shakerbench predict`, docs/characterisation.md)
    std::string status;
    std::string series;                ///< time history path relative to the directory, or empty
    std::vector<ChannelValue> values;  ///< one per channel, in Recording::channels order
    TimeHistory history{};             ///< the series, loaded and checked; empty without one
    /// Which filling of the particle bed (a campaign's seed offset) the point belongs to:
    /// the points of one filling make one FRF per level [-].
    int filling = 0;
};

/// One row of damping.csv.
struct DampingRow {
    std::string arrangement;
    double level_g = 0.0;               ///< [g]
    double natural_frequency_hz = 0.0;  ///< [Hz]
    double damping_ratio = 0.0;         ///< [-]
    std::string method;                 ///< half-power | circle-fit (| rational-fraction)
    /// Grid points the estimate rests on [-]; 0 when not known (a file without the column).
    int points_used = 0;
    /// Their frequencies, ascending [Hz]; empty when not known.
    std::vector<double> frequencies_used_hz{};
    /// Points of this arrangement and level with status `closest` left out of the FRF [-].
    int points_skipped = 0;
    /// Fillings the estimate averages (each its own FRF and estimate); with several, the
    /// frequency and damping are their means and the _std fields their sample standard
    /// deviation (the seed scatter) [-].
    int fillings = 1;
    double natural_frequency_std_hz = 0.0;  ///< [Hz]
    double damping_ratio_std = 0.0;         ///< [-]
    /// The filling of a per-filling row; -1 for a row over every filling.
    int filling = -1;
};

/// Every status a points.csv row may have, in the order messages list them.
inline constexpr const char* kPointStatuses[] = {"converged", "limit-cycle-2", "closest",
                                                 "unsettled", "measured",      "random",
                                                 "predicted", "extrapolated",  "uncertain"};

/// True for the statuses of points that did not hold their level (`closest`), did not settle
/// at a fixed drive (`unsettled`: their window is a long mean), or whose
/// prediction is not to be trusted (`extrapolated`: outside the characterised grid;
/// `uncertain`: not converged, unsettled characterisation, strongly non-harmonic): left out
/// of the fits unless asked for (IdentifyOptions::closest).
inline bool left_out_of_fits_by_default(const std::string& status) {
    return status == "closest" || status == "unsettled" || status == "extrapolated" ||
           status == "uncertain";
}

/// A whole recording directory.
struct Recording {
    RecordingInfo info;
    std::vector<Channel> channels;  ///< in the order of recording.toml
    std::vector<PointRow> points;
    std::vector<DampingRow> damping;  ///< empty when there is no damping.csv

    /// Index of the reference channel (exactly one after a successful read).
    std::size_t reference_index() const;
    /// Index of a channel by name, or channels.size() if absent.
    std::size_t channel_index(const std::string& name) const;
};

}  // namespace sb::identification

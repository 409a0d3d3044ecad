#include "correlation/features.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <map>
#include <numbers>
#include <stdexcept>

#include "identification/damping_curve.hpp"
#include "identification/recording_io.hpp"

namespace sb::correlation {
namespace {

namespace fs = std::filesystem;
using identification::DampingRow;
using identification::LevelIdentification;

std::string fixed(double v, int digits) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
    return buffer;
}

std::string level_text(double level_g) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%g g", level_g);
    return buffer;
}

bool same_frequency(double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b); }

/// The damping rows of one method, preferring the circle fit (it uses the whole resonance
/// circle, the half-power estimate only the points around the peak).
std::string chosen_method(const std::vector<DampingRow>& rows) {
    for (const char* method : {"circle-fit", "half-power"}) {
        for (const auto& r : rows) {
            if (r.method == method && r.filling < 0) return method;
        }
    }
    for (const auto& r : rows) {
        if (r.filling < 0) return r.method;
    }
    return {};
}

/// The complex FRF of one arrangement and level at `frequency_hz` averaged over fillings, and
/// the scatter over the fillings of ln|H| and of the phase (sample standard deviation).
struct FrfPoint {
    std::complex<double> mean;
    double log_magnitude_std = 0.0;
    double phase_std = 0.0;
    int fillings = 0;
};

FrfPoint frf_point(const std::vector<LevelIdentification>& levels, const std::string& arrangement,
                   double level_g, double frequency_hz) {
    std::vector<std::complex<double>> values;
    for (const auto& level : levels) {
        if (level.arrangement != arrangement || !same_level(level.level_g, level_g)) continue;
        const auto& f = level.frf.frequency_hz;
        for (std::size_t k = 0; k < f.size(); ++k) {
            if (same_frequency(f[k], frequency_hz)) values.push_back(level.frf.value[k]);
        }
    }
    FrfPoint p;
    p.fillings = static_cast<int>(values.size());
    if (values.empty()) return p;
    for (const auto& v : values) p.mean += v;
    p.mean /= static_cast<double>(values.size());
    if (values.size() > 1) {
        double s_mag = 0.0;
        double s_phase = 0.0;
        const double mean_log = std::log(std::abs(p.mean));
        const double mean_phase = std::arg(p.mean);
        for (const auto& v : values) {
            s_mag += std::pow(std::log(std::abs(v)) - mean_log, 2);
            s_phase +=
                std::pow(std::remainder(std::arg(v) - mean_phase, 2.0 * std::numbers::pi), 2);
        }
        const double n = static_cast<double>(values.size());
        p.log_magnitude_std = std::sqrt(s_mag / (n - 1.0));
        p.phase_std = std::sqrt(s_phase / (n - 1.0));
    }
    return p;
}

const DampingRow* find_row(const std::vector<DampingRow>& rows, const std::string& arrangement,
                           double level_g, const std::string& method) {
    for (const auto& r : rows) {
        if (r.filling < 0 && r.method == method && r.arrangement == arrangement &&
            same_level(r.level_g, level_g)) {
            return &r;
        }
    }
    return nullptr;
}

}  // namespace

std::string Feature::label() const {
    const std::string where = arrangement + " " + level_text(level_g);
    switch (kind) {
        case FeatureKind::natural_frequency:
            return where + " natural frequency";
        case FeatureKind::damping_ratio:
            return where + " damping";
        case FeatureKind::log_magnitude:
            return where + " |H| at " + fixed(frequency_hz, 3) + " Hz";
        case FeatureKind::phase:
            return where + " phase at " + fixed(frequency_hz, 3) + " Hz";
    }
    return where;
}

Measurement read_measurement(const fs::path& directory, const StatedUncertainty& stated) {
    Measurement m;
    m.directory = directory;
    identification::Recording recording;
    const bool has_toml = fs::exists(directory / "recording.toml");
    const bool has_damping = fs::exists(directory / "damping.csv");
    if (has_toml) {
        recording = identification::read_recording(directory);
    } else if (has_damping) {
        recording.damping = identification::read_damping_csv(directory / "damping.csv");
    } else {
        throw std::invalid_argument(
            directory.string() +
            ": not a recording directory: neither recording.toml (with points.csv) nor "
            "damping.csv is there");
    }
    const bool series = std::any_of(recording.points.begin(), recording.points.end(),
                                    [](const auto& p) { return !p.series.empty(); });
    m.depth = series ? "time histories" : !recording.points.empty() ? "points.csv" : "damping.csv";

    // The FRF of every arrangement and level (and filling), identified as `identify` does.
    std::vector<LevelIdentification> levels;
    if (!recording.points.empty()) {
        levels = identification::identify_recording(recording);
        if (!levels.empty()) m.response_channel = levels.front().channel;
        for (const auto& c : recording.channels) {
            if (c.role == identification::ChannelRole::reference) m.reference_quantity = c.quantity;
        }
    }
    std::vector<DampingRow> damping = recording.damping;
    if (damping.empty()) damping = identification::damping_rows(levels);
    m.damping_method = chosen_method(damping);
    for (const auto& r : damping) {
        if (r.filling < 0 && r.method == m.damping_method) m.damping.push_back(r);
    }

    // Arrangements and levels in order of first appearance, points' frequencies as measured.
    std::vector<std::pair<std::string, double>> order;
    const auto note = [&](const std::string& arrangement, double level_g) {
        const bool known = std::any_of(order.begin(), order.end(), [&](const auto& o) {
            return o.first == arrangement && same_level(o.second, level_g);
        });
        if (!known) order.emplace_back(arrangement, level_g);
    };
    for (const auto& p : recording.points) note(p.arrangement, p.level_g);
    for (const auto& r : m.damping) note(r.arrangement, r.level_g);

    for (const auto& [arrangement, level_g] : order) {
        bench::SweepSelection sweep{arrangement, level_g, {}};
        for (const auto& p : recording.points) {
            if (p.arrangement != arrangement || !same_level(p.level_g, level_g)) continue;
            const bool seen =
                std::any_of(sweep.frequencies_hz.begin(), sweep.frequencies_hz.end(),
                            [&](double f) { return same_frequency(f, p.frequency_hz); });
            if (!seen) sweep.frequencies_hz.push_back(p.frequency_hz);
        }
        m.selection.sweeps.push_back(sweep);

        // Where the level has FRF points, its frequency and damping are functions of those
        // points: compared as well, the same data would count twice and every interval come
        // out too narrow. They stand for the level only when it has no points.
        const bool has_points = !sweep.frequencies_hz.empty();
        const DampingRow* row =
            has_points ? nullptr : find_row(m.damping, arrangement, level_g, m.damping_method);
        if (row) {
            const double n = std::max(1, row->fillings);
            const bool repeats = row->fillings > 1;
            Feature fn{arrangement,
                       level_g,
                       FeatureKind::natural_frequency,
                       0.0,
                       row->natural_frequency_hz,
                       0.0,
                       repeats};
            fn.sigma = repeats ? row->natural_frequency_std_hz / std::sqrt(n)
                               : stated.frequency_relative * row->natural_frequency_hz;
            Feature zeta{arrangement, level_g, FeatureKind::damping_ratio, 0.0, row->damping_ratio,
                         0.0,         repeats};
            zeta.sigma = repeats ? row->damping_ratio_std / std::sqrt(n)
                                 : stated.damping_relative * row->damping_ratio;
            // The stated uncertainty is a floor: the scatter of a few repeats is itself
            // uncertain (two fillings give it one degree of freedom) and knows nothing of the
            // errors the repeats share (calibration of the sensors, the fixture).
            fn.sigma = std::max(fn.sigma, stated.frequency_relative * fn.value);
            zeta.sigma = std::max(zeta.sigma, stated.damping_relative * zeta.value);
            fn.repeats = zeta.repeats = std::max(1, row->fillings);
            m.features.push_back(fn);
            m.features.push_back(zeta);
        }
        for (double f : sweep.frequencies_hz) {
            const FrfPoint p = frf_point(levels, arrangement, level_g, f);
            if (p.fillings == 0 || std::abs(p.mean) <= 0.0) continue;  // a point left out
            const bool repeats = p.fillings > 1;
            const double root_n = std::sqrt(static_cast<double>(p.fillings));
            Feature mag{
                arrangement, level_g, FeatureKind::log_magnitude, f, std::log(std::abs(p.mean)),
                0.0,         repeats};
            Feature phase{arrangement, level_g, FeatureKind::phase, f, std::arg(p.mean),
                          0.0,         repeats};
            mag.sigma = std::max(repeats ? p.log_magnitude_std / root_n : 0.0, stated.frf_relative);
            phase.sigma = std::max(repeats ? p.phase_std / root_n : 0.0, stated.frf_relative);
            mag.repeats = phase.repeats = p.fillings;
            m.features.push_back(mag);
            m.features.push_back(phase);
        }
    }
    if (m.features.empty()) {
        throw std::invalid_argument(directory.string() +
                                    ": nothing to compare: no damping estimate and no FRF point");
    }
    return m;
}

SimulatedFeatures simulated_features(const bench::CampaignResult& result,
                                     const Measurement& measurement) {
    identification::IdentifyOptions options;
    // A simulated point that did not quite hold its level (`closest`) is still the model's
    // transfer function at nearly that level: left out, it would leave a hole in the features
    // that opens and closes as the free values move, and the misfit would jump with it.
    options.closest = identification::ClosestPolicy::use;
    const auto& channels = result.recording.channels;
    const bool has_channel = std::any_of(channels.begin(), channels.end(), [&](const auto& c) {
        return c.name == measurement.response_channel;
    });
    if (has_channel) options.response_channel = measurement.response_channel;
    const auto levels = identification::identify_recording(result.recording, options);
    const auto damping = identification::damping_rows(levels);

    SimulatedFeatures s;
    for (const auto& r : damping) {
        if (r.method == measurement.damping_method) s.damping.push_back(r);
    }
    for (const auto& p : result.recording.points) {
        s.points_flagged += identification::left_out_of_fits_by_default(p.status) ? 1 : 0;
        s.fillings = std::max(s.fillings, p.filling + 1);
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const auto& f : measurement.features) {
        double value = nan;
        double sigma = 0.0;
        if (f.kind == FeatureKind::natural_frequency || f.kind == FeatureKind::damping_ratio) {
            if (const DampingRow* row =
                    find_row(s.damping, f.arrangement, f.level_g, measurement.damping_method)) {
                const double root_n = std::sqrt(static_cast<double>(std::max(1, row->fillings)));
                const bool fn = f.kind == FeatureKind::natural_frequency;
                value = fn ? row->natural_frequency_hz : row->damping_ratio;
                sigma = (fn ? row->natural_frequency_std_hz : row->damping_ratio_std) / root_n;
            }
        } else {
            const FrfPoint p = frf_point(levels, f.arrangement, f.level_g, f.frequency_hz);
            if (p.fillings > 0 && std::abs(p.mean) > 0.0) {
                const double root_n = std::sqrt(static_cast<double>(p.fillings));
                const bool mag = f.kind == FeatureKind::log_magnitude;
                value = mag ? std::log(std::abs(p.mean)) : std::arg(p.mean);
                sigma = (mag ? p.log_magnitude_std : p.phase_std) / root_n;
            }
        }
        if (!std::isfinite(value)) value = nan;
        s.value.push_back(value);
        s.sigma.push_back(sigma);
    }
    return s;
}

double residual(const Feature& feature, double simulated, double simulated_sigma,
                int simulated_fillings) {
    if (!std::isfinite(simulated)) return kMissingResidual;
    double difference = simulated - feature.value;
    if (feature.kind == FeatureKind::phase) {
        difference = std::remainder(difference, 2.0 * std::numbers::pi);
    }
    const double seed2 = simulated_sigma * simulated_sigma * std::max(1, simulated_fillings);
    const double measured2 =
        std::max(feature.sigma * feature.sigma, seed2 / std::max(1, feature.repeats));
    return difference / std::sqrt(measured2 + simulated_sigma * simulated_sigma);
}

bool same_level(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); }

}  // namespace sb::correlation

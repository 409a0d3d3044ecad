// points.csv reader and writer (formats.md), checked against the channels of recording.toml.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "core/text_file.hpp"
#include "core/units.hpp"
#include "identification/csv_table.hpp"
#include "identification/file_error.hpp"
#include "identification/harmonics.hpp"
#include "identification/recording_io.hpp"

namespace sb::identification {

namespace {
const char* const kFixedColumns[] = {"arrangement", "level_g", "frequency_hz", "status", "series"};
const char* const kSuffixes[] = {"_rms", "_re", "_im"};
/// Optional: which filling of the bed a point belongs to (a campaign of several seeds).
const char* const kFillingColumn = "filling";
/// Optional per channel, as a pair: |X_2|/|X_1| and |X_3|/|X_1| (ChannelValue::h2_ratio,
/// h3_ratio). Written after every channel's three value columns, so that the columns of a
/// file without harmonics keep their positions.
const char* const kHarmonicSuffixes[] = {"_h2", "_h3"};
/// Harmonic columns of a channel in points.csv (none, or both).
struct HarmonicColumns {
    bool present = false;
    std::size_t h2 = 0;
    std::size_t h3 = 0;
};
/// A series must span a whole number of periods to this fraction of a period: time stamps
/// printed with 6 significant digits (other tools) give ~1e-6 relative, and an excitation
/// frequency printed with 6 digits ~1e-6 × the number of periods.
constexpr double kWholePeriodTolerance = 1e-3;

std::string channel_list(const Recording& rec) {
    std::string names;
    for (const auto& ch : rec.channels) names += (names.empty() ? "" : ", ") + ch.name;
    return names;
}

/// Loads the series of a row and checks it against recording.toml and the row's frequency.
TimeHistory load_series(const detail::CsvTable& t, const detail::CsvCell& cell,
                        const std::filesystem::path& directory, double frequency_hz,
                        const Recording& rec) {
    // A series belongs to the recording: a relative path that stays inside its directory. An
    // absolute path or one through ".." would read whatever file it names, and a control
    // character (a NUL ends the name the system sees) another file than the one written.
    const std::filesystem::path relative(cell.text);
    const bool control = std::any_of(cell.text.begin(), cell.text.end(),
                                     [](char c) { return static_cast<unsigned char>(c) < 0x20; });
    const bool outside = relative.is_absolute() || relative.has_root_name() ||
                         std::any_of(relative.begin(), relative.end(),
                                     [](const auto& part) { return part == ".."; });
    if (control || outside) {
        throw FileError(t.file, cell.line, cell.column,
                        "series file '" + cell.text +
                            "' must be a relative path inside the recording directory");
    }
    const auto path = directory / relative;
    if (!std::filesystem::is_regular_file(path)) {
        throw FileError(t.file, cell.line, cell.column,
                        "series file '" + cell.text + "' not found");
    }
    std::vector<std::string> known;
    for (const auto& ch : rec.channels) known.push_back(ch.name);
    TimeHistory h = read_time_history_csv(path, known);
    const double fs = h.sample_rate_hz();
    const double periods = static_cast<double>(h.time_s.size()) * frequency_hz / fs;
    if (h.time_s.size() < 2 || std::round(periods) < 1.0 ||
        std::abs(periods - std::round(periods)) > kWholePeriodTolerance) {
        std::ostringstream m;
        m.precision(8);
        m << h.time_s.size() << " samples at " << fs << " Hz hold " << periods << " periods of "
          << frequency_hz << " Hz (" << t.file << " line " << cell.line
          << "): a series must hold whole periods";
        throw FileError(path.string(), 0, 0, m.str());
    }
    // The fundamental needs more than two samples per period: at or above the Nyquist
    // frequency its bin does not exist, and it would read as zero.
    if (!(fs > 2.0 * frequency_hz)) {
        std::ostringstream m;
        m.precision(8);
        m << "sampled at " << fs << " Hz, which cannot hold " << frequency_hz << " Hz (" << t.file
          << " line " << cell.line << "): a series needs more than two samples per period";
        throw FileError(path.string(), 0, 0, m.str());
    }
    return h;
}

/// rms and fundamental of one channel of a series over its whole periods, on the series'
/// time axis (x(t) = Re{X e^{iωt}} with t = time_s: the analysis starts at t0 = time_s[0],
/// so X = X' e^{−iωt0}). The sample rate is taken from the whole-period count (n f / P),
/// which the check above has established, rather than from rounded time stamps.
/// The harmonic ratios come from the same analysis (harmonics.hpp): |X_k| does not depend on
/// the time origin, so they need no phase reference.
ChannelValue from_series(const TimeHistory& h, std::size_t column, double frequency_hz) {
    const double periods =
        std::round(static_cast<double>(h.time_s.size()) * frequency_hz / h.sample_rate_hz());
    const double fs = static_cast<double>(h.time_s.size()) * frequency_hz / periods;
    ChannelValue v;
    const double t0 = h.time_s.front();
    const HarmonicAnalysis analysis = analyse_harmonics(h.columns[column], fs, frequency_hz, 3);
    v.amplitude = analysis.amplitude[1] * std::polar(1.0, -hz_to_rad_s(frequency_hz) * t0);
    v.rms = rms_over_whole_periods(h.columns[column], fs, frequency_hz);
    v.h2_ratio = harmonic_ratio(analysis, 2);
    v.h3_ratio = harmonic_ratio(analysis, 3);
    v.from_series = true;
    return v;
}

/// A harmonic ratio cell: empty is NaN (not known), otherwise a finite number >= 0.
double ratio_cell(const detail::CsvTable& t, const detail::CsvCell& cell,
                  const std::string& column_name) {
    if (cell.text.empty()) return std::numeric_limits<double>::quiet_NaN();
    const double v = detail::number(t, cell, column_name);
    if (v < 0.0) {
        throw FileError(t.file, cell.line, cell.column,
                        "column '" + column_name + "': '" + cell.text +
                            "' is negative; a ratio of magnitudes is >= 0");
    }
    return v;
}

}  // namespace

void read_points_csv(const std::filesystem::path& path, Recording& rec) {
    const auto t = detail::read_csv(path);
    std::map<std::string, std::size_t> col;
    for (std::size_t i = 0; i < t.header.size(); ++i) {
        const auto& h = t.header[i];
        if (col.count(h.text) != 0)
            throw FileError(t.file, h.line, h.column, "duplicate column '" + h.text + "'");
        col[h.text] = i;
        bool known = false;
        for (const char* c : kFixedColumns) known = known || h.text == c;
        known = known || h.text == kFillingColumn;
        for (const auto& ch : rec.channels) {
            for (const char* s : kSuffixes) known = known || h.text == ch.name + s;
            for (const char* s : kHarmonicSuffixes) known = known || h.text == ch.name + s;
        }
        if (!known) {
            const std::string names = channel_list(rec);
            throw FileError(
                t.file, h.line, h.column,
                "unknown column '" + h.text +
                    "': not a fixed column and no channel of recording.toml matches (channels: " +
                    names + ")");
        }
    }
    auto need = [&](const std::string& name, const std::string& why) {
        const auto it = col.find(name);
        if (it == col.end()) {
            // At the header line (comments or blank lines may precede it), whole line.
            throw FileError(t.file, t.header.front().line, 0,
                            "missing column '" + name + "'" + why);
        }
        return it->second;
    };
    const std::size_t c_arr = need("arrangement", ""), c_lvl = need("level_g", ""),
                      c_f = need("frequency_hz", ""), c_st = need("status", ""),
                      c_se = need("series", "");
    std::vector<std::array<std::size_t, 3>> chan_cols;
    for (const auto& ch : rec.channels) {
        std::array<std::size_t, 3> c{};
        for (std::size_t k = 0; k < 3; ++k) {
            c[k] = need(ch.name + kSuffixes[k],
                        " for channel '" + ch.name + "' declared in recording.toml");
        }
        chan_cols.push_back(c);
    }
    // Harmonic columns are optional (a measured recording from another tool may have none),
    // but come in pairs: a file with only one of them is more likely cut than meant.
    std::vector<HarmonicColumns> harmonic_cols;
    for (const auto& ch : rec.channels) {
        const auto h2 = col.find(ch.name + kHarmonicSuffixes[0]);
        const auto h3 = col.find(ch.name + kHarmonicSuffixes[1]);
        HarmonicColumns hc;
        if (h2 != col.end() || h3 != col.end()) {
            const bool has_h2 = h2 != col.end();
            need(ch.name + kHarmonicSuffixes[has_h2 ? 1 : 0],
                 " for channel '" + ch.name + "': '" + ch.name + kHarmonicSuffixes[has_h2 ? 0 : 1] +
                     "' is present and the two harmonic columns come as a pair");
            hc = {true, h2->second, h3->second};
        }
        harmonic_cols.push_back(hc);
    }
    for (const auto& row : t.rows) {
        PointRow p;
        p.arrangement = row[c_arr].text;
        if (p.arrangement.empty())
            throw FileError(t.file, row[c_arr].line, row[c_arr].column, "empty arrangement");
        p.level_g = detail::number(t, row[c_lvl], "level_g");
        p.frequency_hz = detail::number(t, row[c_f], "frequency_hz");
        if (!(p.frequency_hz > 0.0))
            throw FileError(t.file, row[c_f].line, row[c_f].column, "frequency_hz must be > 0");
        p.status = row[c_st].text;
        if (std::none_of(std::begin(kPointStatuses), std::end(kPointStatuses),
                         [&](const char* known) { return p.status == known; })) {
            std::string known;
            for (const char* k : kPointStatuses)
                known += (known.empty() ? "" : " | ") + std::string(k);
            throw FileError(t.file, row[c_st].line, row[c_st].column,
                            "status '" + p.status + "' must be one of " + known);
        }
        if (const auto it = col.find(kFillingColumn); it != col.end()) {
            const auto& cell = row[it->second];
            const double filling =
                cell.text.empty() ? 0.0 : detail::number(t, cell, kFillingColumn);
            if (!(filling >= 0.0 && filling <= 1e6 && filling == std::floor(filling))) {
                throw FileError(t.file, cell.line, cell.column,
                                "filling '" + cell.text + "' must be a whole number >= 0");
            }
            p.filling = static_cast<int>(filling);
        }
        p.series = row[c_se].text;
        if (!p.series.empty()) {
            p.history = load_series(t, row[c_se], path.parent_path(), p.frequency_hz, rec);
        }
        for (std::size_t c = 0; c < rec.channels.size(); ++c) {
            const auto& cc = chan_cols[c];
            const auto& n = rec.channels[c].name;
            if (row[cc[0]].text.empty() && row[cc[1]].text.empty() && row[cc[2]].text.empty()) {
                // No values: computed from the series, which must hold the channel.
                const auto& cell = row[cc[0]];
                if (p.series.empty()) {
                    throw FileError(t.file, cell.line, cell.column,
                                    "columns '" + n + "_rms', '" + n + "_re', '" + n +
                                        "_im' are empty and the row has no series to compute "
                                        "them from");
                }
                std::size_t k = 0;
                while (k < p.history.channels.size() && p.history.channels[k] != n) ++k;
                if (k == p.history.channels.size()) {
                    throw FileError(t.file, cell.line, cell.column,
                                    "columns '" + n + "_rms', '" + n + "_re', '" + n +
                                        "_im' are empty and series '" + p.series +
                                        "' has no column '" + n + "'");
                }
                p.values.push_back(from_series(p.history, k, p.frequency_hz));
            } else {
                ChannelValue v;
                v.rms = detail::number(t, row[cc[0]], n + "_rms");
                v.amplitude = {detail::number(t, row[cc[1]], n + "_re"),
                               detail::number(t, row[cc[2]], n + "_im")};
                p.values.push_back(v);
            }
            // A number in the file is never replaced: a cell given wins over the series.
            const auto& hc = harmonic_cols[c];
            if (!hc.present) continue;
            auto& v = p.values.back();
            if (!row[hc.h2].text.empty() || !v.from_series)
                v.h2_ratio = ratio_cell(t, row[hc.h2], n + kHarmonicSuffixes[0]);
            if (!row[hc.h3].text.empty() || !v.from_series)
                v.h3_ratio = ratio_cell(t, row[hc.h3], n + kHarmonicSuffixes[1]);
        }
        rec.points.push_back(std::move(p));
    }
}

void write_points_csv(const std::filesystem::path& path, const Recording& rec) {
    std::ostringstream f;
    // A channel gets its harmonic columns when any row knows one of its ratios.
    std::vector<bool> harmonics(rec.channels.size(), false);
    for (const auto& p : rec.points) {
        for (std::size_t c = 0; c < p.values.size() && c < harmonics.size(); ++c) {
            harmonics[c] = harmonics[c] || std::isfinite(p.values[c].h2_ratio) ||
                           std::isfinite(p.values[c].h3_ratio);
        }
    }
    const bool fillings = std::any_of(rec.points.begin(), rec.points.end(),
                                      [](const PointRow& p) { return p.filling != 0; });
    f << "arrangement,level_g,frequency_hz,status,series" << (fillings ? ",filling" : "");
    for (const auto& ch : rec.channels)
        f << ',' << ch.name << "_rms," << ch.name << "_re," << ch.name << "_im";
    for (std::size_t c = 0; c < rec.channels.size(); ++c) {
        if (harmonics[c])
            f << ',' << rec.channels[c].name << "_h2," << rec.channels[c].name << "_h3";
    }
    f << '\n';
    using detail::exact_text;
    const auto ratio_text = [](double r) { return std::isfinite(r) ? exact_text(r) : ""; };
    for (const auto& p : rec.points) {
        detail::check_cell_text(p.arrangement, "arrangement");
        detail::check_cell_text(p.status, "status");
        detail::check_cell_text(p.series, "series");
        f << p.arrangement << ',' << exact_text(p.level_g) << ',' << exact_text(p.frequency_hz)
          << ',' << p.status << ',' << p.series;
        if (fillings) f << ',' << p.filling;
        for (const auto& v : p.values) {
            f << ',' << exact_text(v.rms) << ',' << exact_text(v.amplitude.real()) << ','
              << exact_text(v.amplitude.imag());
        }
        for (std::size_t c = 0; c < harmonics.size(); ++c) {
            if (!harmonics[c]) continue;
            const ChannelValue v = c < p.values.size() ? p.values[c] : ChannelValue{};
            f << ',' << ratio_text(v.h2_ratio) << ',' << ratio_text(v.h3_ratio);
        }
        f << '\n';
    }
    write_file_atomically(path, f.str());
}

}  // namespace sb::identification

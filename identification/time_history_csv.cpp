// series/*.csv time histories (formats.md): header time_s,<channel>,..., uniform sampling.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/text_file.hpp"
#include "identification/csv_table.hpp"
#include "identification/file_error.hpp"
#include "identification/recording_io.hpp"

namespace sb::identification {

namespace {
/// Jitter allowed on the sampling step: text with 17 digits reproduces steps to ~1e-15; files
/// from other tools print 6–10 digits, hence 1e-6 relative.
constexpr double kStepTolerance = 1e-6;
}  // namespace

double TimeHistory::sample_rate_hz() const {
    if (time_s.size() < 2) return 0.0;
    return static_cast<double>(time_s.size() - 1) / (time_s.back() - time_s.front());
}

TimeHistory read_time_history_csv(const std::filesystem::path& path) {
    return read_time_history_csv(path, {});
}

TimeHistory read_time_history_csv(const std::filesystem::path& path,
                                  const std::vector<std::string>& known_channels) {
    const auto t = detail::read_csv(path);
    if (t.header[0].text != "time_s") {
        throw FileError(t.file, t.header[0].line, t.header[0].column,
                        "first column must be 'time_s', found '" + t.header[0].text + "'");
    }
    TimeHistory h;
    for (std::size_t i = 1; i < t.header.size(); ++i) {
        const auto& cell = t.header[i];
        const bool known = known_channels.empty() ||
                           std::find(known_channels.begin(), known_channels.end(), cell.text) !=
                               known_channels.end();
        if (!known) {
            std::string names;
            for (const auto& n : known_channels) names += (names.empty() ? "" : ", ") + n;
            throw FileError(t.file, cell.line, cell.column,
                            "unknown channel '" + cell.text +
                                "': not a channel of recording.toml (channels: " + names + ")");
        }
        for (std::size_t j = 1; j < i; ++j) {
            if (t.header[j].text == cell.text) {
                throw FileError(t.file, cell.line, cell.column,
                                "duplicate column '" + cell.text + "'");
            }
        }
        h.channels.push_back(cell.text);
    }
    h.columns.resize(h.channels.size());
    for (const auto& row : t.rows) {
        h.time_s.push_back(detail::number(t, row[0], "time_s"));
        for (std::size_t c = 1; c < row.size(); ++c)
            h.columns[c - 1].push_back(detail::number(t, row[c], h.channels[c - 1]));
    }
    if (h.time_s.size() >= 2) {
        if (!(h.time_s.back() > h.time_s.front())) {
            const auto& cell = t.rows.back()[0];
            throw FileError(t.file, cell.line, cell.column,
                            "time_s must increase: it ends at " + cell.text + " s, not after " +
                                t.rows.front()[0].text + " s");
        }
        const double dt = 1.0 / h.sample_rate_hz();
        if (!(std::isfinite(dt) && dt > 0.0)) {
            const auto& cell = t.rows.back()[0];
            throw FileError(t.file, cell.line, cell.column,
                            "time_s spans more than a number can hold");
        }
        for (std::size_t i = 1; i < h.time_s.size(); ++i) {
            if (std::abs(h.time_s[i] - h.time_s[i - 1] - dt) > kStepTolerance * dt) {
                const auto& cell = t.rows[i][0];
                throw FileError(t.file, cell.line, cell.column,
                                "non-uniform sampling: step " +
                                    std::to_string(h.time_s[i] - h.time_s[i - 1]) + " s, mean " +
                                    std::to_string(dt) + " s");
            }
        }
    }
    return h;
}

std::string time_history_csv_text(const TimeHistory& h) {
    std::ostringstream f;
    f << "time_s";
    for (const auto& c : h.channels) f << ',' << c;
    f << '\n';
    for (std::size_t i = 0; i < h.time_s.size(); ++i) {
        f << detail::exact_text(h.time_s[i]);
        for (const auto& col : h.columns) f << ',' << detail::exact_text(col[i]);
        f << '\n';
    }
    return f.str();
}

void write_time_history_csv(const std::filesystem::path& path, const TimeHistory& h) {
    write_file_atomically(path, time_history_csv_text(h));
}

}  // namespace sb::identification

// points.csv reader and writer (formats.md), checked against the channels of recording.toml.
#include <array>
#include <fstream>
#include <map>

#include "identification/csv_table.hpp"
#include "identification/file_error.hpp"
#include "identification/recording_io.hpp"

namespace sb::identification {

namespace {
const char* const kFixedColumns[] = {"arrangement", "level_g", "frequency_hz", "status", "series"};
const char* const kSuffixes[] = {"_rms", "_re", "_im"};
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
        for (const auto& ch : rec.channels) {
            for (const char* s : kSuffixes) known = known || h.text == ch.name + s;
        }
        if (!known) {
            std::string names;
            for (const auto& ch : rec.channels) names += (names.empty() ? "" : ", ") + ch.name;
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
            throw FileError(t.file, 1, 0, "missing column '" + name + "'" + why);
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
        if (p.status != "converged" && p.status != "limit-cycle-2" && p.status != "closest" &&
            p.status != "measured") {
            throw FileError(t.file, row[c_st].line, row[c_st].column,
                            "status '" + p.status +
                                "' must be one of converged | limit-cycle-2 | closest | measured");
        }
        p.series = row[c_se].text;
        for (std::size_t c = 0; c < rec.channels.size(); ++c) {
            const auto& cc = chan_cols[c];
            const auto& n = rec.channels[c].name;
            ChannelValue v;
            v.rms = detail::number(t, row[cc[0]], n + "_rms");
            v.amplitude = {detail::number(t, row[cc[1]], n + "_re"),
                           detail::number(t, row[cc[2]], n + "_im")};
            p.values.push_back(v);
        }
        rec.points.push_back(std::move(p));
    }
}

void write_points_csv(const std::filesystem::path& path, const Recording& rec) {
    std::ofstream f(path, std::ios::binary);
    if (!f) throw FileError(path.string(), 0, 0, "cannot open the file for writing");
    f << "arrangement,level_g,frequency_hz,status,series";
    for (const auto& ch : rec.channels)
        f << ',' << ch.name << "_rms," << ch.name << "_re," << ch.name << "_im";
    f << '\n';
    using detail::exact_text;
    for (const auto& p : rec.points) {
        detail::check_cell_text(p.arrangement, "arrangement");
        detail::check_cell_text(p.status, "status");
        detail::check_cell_text(p.series, "series");
        f << p.arrangement << ',' << exact_text(p.level_g) << ',' << exact_text(p.frequency_hz)
          << ',' << p.status << ',' << p.series;
        for (const auto& v : p.values) {
            f << ',' << exact_text(v.rms) << ',' << exact_text(v.amplitude.real()) << ','
              << exact_text(v.amplitude.imag());
        }
        f << '\n';
    }
}

}  // namespace sb::identification

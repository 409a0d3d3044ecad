// damping.csv reader and writer (formats.md).
#include <fstream>

#include "identification/csv_table.hpp"
#include "identification/file_error.hpp"
#include "identification/recording_io.hpp"

namespace sb::identification {

std::vector<DampingRow> read_damping_csv(const std::filesystem::path& path) {
    const auto t = detail::read_csv(path);
    const char* const names[] = {"arrangement", "level_g", "natural_frequency_hz", "damping_ratio",
                                 "method"};
    std::size_t c[5];
    for (std::size_t k = 0; k < 5; ++k) {
        c[k] = t.header.size();
        for (std::size_t i = 0; i < t.header.size(); ++i) {
            if (t.header[i].text == names[k]) c[k] = i;
        }
        if (c[k] == t.header.size())
            throw FileError(t.file, t.header.front().line, 0,
                            std::string("missing column '") + names[k] + "'");
    }
    std::vector<DampingRow> rows;
    for (const auto& r : t.rows) {
        DampingRow d;
        d.arrangement = r[c[0]].text;
        d.level_g = detail::number(t, r[c[1]], names[1]);
        d.natural_frequency_hz = detail::number(t, r[c[2]], names[2]);
        d.damping_ratio = detail::number(t, r[c[3]], names[3]);
        d.method = r[c[4]].text;
        if (d.method != "half-power" && d.method != "circle-fit" &&
            d.method != "rational-fraction") {
            throw FileError(
                t.file, r[c[4]].line, r[c[4]].column,
                "method '" + d.method + "' must be half-power | circle-fit | rational-fraction");
        }
        rows.push_back(std::move(d));
    }
    return rows;
}

void write_damping_csv(const std::filesystem::path& path, const std::vector<DampingRow>& rows) {
    std::ofstream f(path, std::ios::binary);
    if (!f) throw FileError(path.string(), 0, 0, "cannot open the file for writing");
    f << "arrangement,level_g,natural_frequency_hz,damping_ratio,method\n";
    for (const auto& r : rows) {
        detail::check_cell_text(r.arrangement, "arrangement");
        detail::check_cell_text(r.method, "method");
        f << r.arrangement << ',' << detail::exact_text(r.level_g) << ','
          << detail::exact_text(r.natural_frequency_hz) << ','
          << detail::exact_text(r.damping_ratio) << ',' << r.method << '\n';
    }
}

}  // namespace sb::identification

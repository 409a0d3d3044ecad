// damping.csv reader and writer (formats.md).
#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>
#include <string_view>

#include "core/text_file.hpp"
#include "identification/csv_table.hpp"
#include "identification/file_error.hpp"
#include "identification/recording_io.hpp"
#include "identification/uff58_number.hpp"

namespace sb::identification {

namespace {

/// Separates the frequencies in the frequencies_used_hz cell (a comma would split the cell).
constexpr char kFrequencySeparator = ';';

/// Index of a column, or the header size when absent.
std::size_t find_column(const detail::CsvTable& t, std::string_view name) {
    for (std::size_t i = 0; i < t.header.size(); ++i) {
        if (t.header[i].text == name) return i;
    }
    return t.header.size();
}

/// A count cell: empty is 0 (not known), otherwise an integer >= 0.
int count_cell(const detail::CsvTable& t, const detail::CsvCell& cell, const char* column) {
    if (cell.text.empty()) return 0;
    int v = 0;
    const char* b = cell.text.data();
    const char* e = b + cell.text.size();
    const auto [ptr, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || ptr != e || v < 0) {
        throw FileError(t.file, cell.line, cell.column,
                        std::string("column '") + column + "': '" + cell.text +
                            "' is not a count (an integer >= 0)");
    }
    return v;
}

/// The frequencies of a frequencies_used_hz cell, separated by ';'; empty cell: none known.
/// A bad entry is reported at its own column within the line.
std::vector<double> frequencies_cell(const detail::CsvTable& t, const detail::CsvCell& cell) {
    std::vector<double> out;
    if (cell.text.empty()) return out;
    std::size_t b = 0;
    while (true) {
        const std::size_t e = cell.text.find(kFrequencySeparator, b);
        const std::string_view raw(cell.text.data() + b,
                                   (e == std::string::npos ? cell.text.size() : e) - b);
        const std::string part(detail::trim(raw));
        // At the entry's offset in the cell (exact unless the cell itself starts with blanks).
        detail::CsvCell entry{part, cell.line, cell.column + static_cast<int>(b)};
        const double f = detail::number(t, entry, "frequencies_used_hz");
        if (!(f > 0.0)) {
            throw FileError(t.file, entry.line, entry.column,
                            "column 'frequencies_used_hz': '" + part + "' is not a frequency > 0");
        }
        out.push_back(f);
        if (e == std::string::npos) break;
        b = e + 1;
    }
    return out;
}

}  // namespace

std::vector<DampingRow> read_damping_csv(const std::filesystem::path& path) {
    const auto t = detail::read_csv(path);
    const char* const names[] = {"arrangement", "level_g", "natural_frequency_hz", "damping_ratio",
                                 "method"};
    std::size_t c[5];
    for (std::size_t k = 0; k < 5; ++k) {
        c[k] = find_column(t, names[k]);
        if (c[k] == t.header.size())
            throw FileError(t.file, t.header.front().line, 0,
                            std::string("missing column '") + names[k] + "'");
    }
    // Optional: older files and other tools' files do not say which points an estimate used.
    const std::size_t c_used = find_column(t, "points_used");
    const std::size_t c_freq = find_column(t, "frequencies_used_hz");
    const std::size_t c_skip = find_column(t, "points_skipped");
    // Optional: the seed scatter over several fillings of the bed.
    const std::size_t c_fillings = find_column(t, "fillings");
    const std::size_t c_f_std = find_column(t, "natural_frequency_std_hz");
    const std::size_t c_z_std = find_column(t, "damping_ratio_std");
    const std::size_t c_filling = find_column(t, "filling");
    const std::size_t absent = t.header.size();
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
        if (c_used != absent) d.points_used = count_cell(t, r[c_used], "points_used");
        if (c_freq != absent) d.frequencies_used_hz = frequencies_cell(t, r[c_freq]);
        if (c_skip != absent) d.points_skipped = count_cell(t, r[c_skip], "points_skipped");
        if (c_fillings != absent && !r[c_fillings].text.empty()) {
            d.fillings = count_cell(t, r[c_fillings], "fillings");
        }
        if (c_f_std != absent && !r[c_f_std].text.empty()) {
            d.natural_frequency_std_hz = detail::number(t, r[c_f_std], "natural_frequency_std_hz");
        }
        if (c_z_std != absent && !r[c_z_std].text.empty()) {
            d.damping_ratio_std = detail::number(t, r[c_z_std], "damping_ratio_std");
        }
        if (c_filling != absent && !r[c_filling].text.empty()) {
            d.filling = count_cell(t, r[c_filling], "filling");
        }
        // Both known and different: the row contradicts itself.
        if (d.points_used > 0 && !d.frequencies_used_hz.empty() &&
            static_cast<std::size_t>(d.points_used) != d.frequencies_used_hz.size()) {
            throw FileError(t.file, r[c_freq].line, r[c_freq].column,
                            "column 'frequencies_used_hz' lists " +
                                std::to_string(d.frequencies_used_hz.size()) +
                                " frequencies but points_used is " + std::to_string(d.points_used));
        }
        rows.push_back(std::move(d));
    }
    return rows;
}

void write_damping_csv(const std::filesystem::path& path, const std::vector<DampingRow>& rows) {
    std::ostringstream f;
    // The columns of older files first, in their order, so that they keep their positions.
    const bool per_filling =
        std::any_of(rows.begin(), rows.end(), [](const DampingRow& r) { return r.filling >= 0; });
    f << "arrangement,level_g,natural_frequency_hz,damping_ratio,method,points_used,"
         "frequencies_used_hz,points_skipped,fillings,natural_frequency_std_hz,damping_ratio_std"
      << (per_filling ? ",filling" : "") << "\n";
    for (const auto& r : rows) {
        detail::check_cell_text(r.arrangement, "arrangement");
        detail::check_cell_text(r.method, "method");
        f << r.arrangement << ',' << detail::exact_text(r.level_g) << ','
          << detail::exact_text(r.natural_frequency_hz) << ','
          << detail::exact_text(r.damping_ratio) << ',' << r.method << ',' << r.points_used << ',';
        for (std::size_t i = 0; i < r.frequencies_used_hz.size(); ++i) {
            if (i > 0) f << kFrequencySeparator;
            f << detail::exact_text(r.frequencies_used_hz[i]);
        }
        f << ',' << r.points_skipped << ',' << r.fillings << ','
          << detail::exact_text(r.natural_frequency_std_hz) << ','
          << detail::exact_text(r.damping_ratio_std);
        if (per_filling) f << ',' << r.filling;
        f << '\n';
    }
    write_file_atomically(path, f.str());
}

}  // namespace sb::identification

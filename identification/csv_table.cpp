// CSV reading with cell positions.
#include "identification/csv_table.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "identification/file_error.hpp"
#include "identification/uff58_number.hpp"

namespace sb::identification::detail {

CsvTable read_csv(const std::filesystem::path& path) {
    CsvTable t;
    t.file = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FileError(t.file, 0, 0, "cannot open the file");
    std::string line;
    int number_of_line = 0;
    while (std::getline(in, line)) {
        ++number_of_line;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (trim(line).empty() || line.front() == '#') continue;
        std::vector<CsvCell> cells;
        std::size_t b = 0;
        while (true) {
            const std::size_t e = line.find(',', b);
            const std::string_view raw(line.data() + b,
                                       (e == std::string::npos ? line.size() : e) - b);
            cells.push_back({std::string(trim(raw)), number_of_line, static_cast<int>(b) + 1});
            if (e == std::string::npos) break;
            b = e + 1;
        }
        if (t.header.empty()) {
            t.header = std::move(cells);
            continue;
        }
        if (cells.size() != t.header.size()) {
            throw FileError(t.file, number_of_line, 1,
                            std::to_string(cells.size()) + " cells but the header has " +
                                std::to_string(t.header.size()));
        }
        t.rows.push_back(std::move(cells));
    }
    if (t.header.empty()) throw FileError(t.file, 1, 1, "empty file: no header line");
    return t;
}

double number(const CsvTable& table, const CsvCell& cell, const std::string& column_name) {
    double v = 0.0;
    const char* b = cell.text.data();
    const char* e = b + cell.text.size();
    if (b != e && *b == '+') ++b;
    const auto [ptr, ec] = std::from_chars(b, e, v);
    if (cell.text.empty() || ec != std::errc() || ptr != e) {
        throw FileError(table.file, cell.line, cell.column,
                        "column '" + column_name + "': '" + cell.text + "' is not a number");
    }
    // from_chars reads "nan" and "inf": a measured value is never either.
    if (!std::isfinite(v)) {
        throw FileError(table.file, cell.line, cell.column,
                        "column '" + column_name + "': '" + cell.text + "' is not a finite number");
    }
    return v;
}

void check_cell_text(const std::string& text, const std::string& what) {
    if (text.find_first_of(",\r\n") != std::string::npos ||
        (!text.empty() && text.front() == '#')) {
        throw std::invalid_argument(what + " '" + text +
                                    "' cannot be written to CSV (comma, line break or leading #)");
    }
}

std::string exact_text(double value) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", value);
    return buf;
}

}  // namespace sb::identification::detail

// A minimal CSV reader that remembers line and column of every cell (for FileError messages).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sb::identification::detail {

/// One cell with its 1-based position in the file.
struct CsvCell {
    std::string text;
    int line = 0;
    int column = 0;
};

/// A CSV file: header and rows. Comma-separated, no quoting, `#` lines and blank lines skipped,
/// CRLF accepted. Written here because the format is this simple and positions are needed.
struct CsvTable {
    std::string file;
    std::vector<CsvCell> header;
    std::vector<std::vector<CsvCell>> rows;
};

/// Reads a CSV file; throws FileError if it cannot be opened, has no header, or a row has a
/// different number of cells than the header.
CsvTable read_csv(const std::filesystem::path& path);

/// The cell as a finite double; FileError at the cell ("not a number", "not a finite number"
/// for nan and inf) otherwise.
double number(const CsvTable& table, const CsvCell& cell, const std::string& column_name);

/// Throws std::invalid_argument if `text` cannot be a cell of this CSV dialect (comma, line
/// break, or a leading `#`, which would start a comment line).
void check_cell_text(const std::string& text, const std::string& what);

/// Shortest text that reads back as the same double (17 significant digits, %.17g).
std::string exact_text(double value);

}  // namespace sb::identification::detail

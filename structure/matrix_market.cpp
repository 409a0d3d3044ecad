// Reader of Matrix Market coordinate files (real, general or symmetric).
#include "structure/matrix_market.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace sb::structure {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, int line, const std::string& message) {
    const std::string place = line > 0 ? ":" + std::to_string(line) : std::string();
    throw MatrixMarketError(file.string() + place + ": " + message);
}

/// Nothing but blanks may follow the numbers a line holds: a third value on an entry line is
/// a complex entry or a damaged line, never to be dropped.
bool only_blanks_left(std::istringstream& in) {
    std::string rest;
    return !(in >> rest);
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

/// Reads the header and the size line, leaving `in` at the first entry line.
MatrixMarketSize read_header(std::ifstream& in, const std::filesystem::path& file, int& line) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error)) {
        // A device or a pipe could be read forever (/dev/zero): only files are matrices.
        fail(file, 0,
             std::filesystem::exists(file, error) ? "not a regular file" : "cannot open file");
    }
    if (!in) fail(file, 0, "cannot open file");
    std::string text;
    if (!std::getline(in, text)) fail(file, 1, "empty file");
    ++line;
    std::istringstream header(lower(text));
    std::string banner, object, format, field, symmetry;
    header >> banner >> object >> format >> field >> symmetry;
    if (banner != "%%matrixmarket" || object != "matrix") {
        fail(file, line, "expected '%%MatrixMarket matrix ...' header");
    }
    if (format != "coordinate") fail(file, line, "only 'coordinate' format is supported");
    if (field != "real" && field != "double" && field != "integer") {
        fail(file, line, "only real entries are supported, got '" + field + "'");
    }
    if (symmetry != "general" && symmetry != "symmetric") {
        fail(file, line, "only 'general' or 'symmetric' are supported, got '" + symmetry + "'");
    }
    MatrixMarketSize size;
    size.symmetric = symmetry == "symmetric";
    size.rows = -1;
    while (std::getline(in, text)) {
        ++line;
        if (text.empty() || text[0] == '%' ||
            text.find_first_not_of(" \t\r") == std::string::npos) {
            continue;
        }
        std::istringstream numbers(text);
        if (!(numbers >> size.rows >> size.cols >> size.entries) || !only_blanks_left(numbers) ||
            size.rows <= 0 || size.cols <= 0 || size.entries < 0) {
            fail(file, line, "expected 'rows columns entries' with positive sizes");
        }
        break;
    }
    if (size.rows < 0) fail(file, line, "missing size line");
    if (size.rows > kMatrixMarketMaxDimension || size.cols > kMatrixMarketMaxDimension) {
        fail(file, line,
             std::to_string(size.rows) + " x " + std::to_string(size.cols) +
                 ": rows and columns are limited to " + std::to_string(kMatrixMarketMaxDimension));
    }
    if (size.symmetric && size.rows != size.cols) {
        fail(file, line, "a symmetric matrix must be square");
    }
    // Each place holds at most one entry (a symmetric file: the lower triangle).
    const long places = size.symmetric ? size.rows * (size.rows + 1) / 2 : size.rows * size.cols;
    if (size.entries > places) {
        fail(file, line,
             std::to_string(size.entries) + " entries, more than the " + std::to_string(places) +
                 " places of the matrix");
    }
    return size;
}

}  // namespace

MatrixMarketSize read_matrix_market_size(const std::filesystem::path& file) {
    std::ifstream in(file);
    int line = 0;
    return read_header(in, file, line);
}

Eigen::SparseMatrix<double> read_matrix_market_sparse(const std::filesystem::path& file) {
    std::ifstream in(file);
    int line = 0;
    const MatrixMarketSize size = read_header(in, file, line);
    const long rows = size.rows;
    const long cols = size.cols;
    const long entries = size.entries;
    const bool symmetric = size.symmetric;
    std::string text;

    std::vector<Eigen::Triplet<double>> triplets;
    // Per entry: its place (row-major) and line, to find an entry given twice.
    std::vector<std::pair<long, int>> places;
    // The size line is not trusted with the allocation: it grows with what is really read.
    triplets.reserve(
        static_cast<std::size_t>(std::min(symmetric ? 2 * entries : entries, 1L << 16)));
    long read = 0;
    while (read < entries && std::getline(in, text)) {
        ++line;
        if (text.empty() || text[0] == '%' ||
            text.find_first_not_of(" \t\r") == std::string::npos) {
            continue;
        }
        std::istringstream entry(text);
        long i = 0, j = 0;
        double value = 0.0;
        if (!(entry >> i >> j >> value) || !only_blanks_left(entry)) {
            fail(file, line, "expected 'row column value'");
        }
        if (i < 1 || i > rows || j < 1 || j > cols) {
            fail(file, line,
                 "index (" + std::to_string(i) + ", " + std::to_string(j) + ") outside " +
                     std::to_string(rows) + " x " + std::to_string(cols));
        }
        if (!std::isfinite(value)) fail(file, line, "non-finite value");
        if (symmetric && j > i) fail(file, line, "symmetric file must hold the lower triangle");
        const auto r = static_cast<int>(i - 1);
        const auto c = static_cast<int>(j - 1);
        triplets.emplace_back(r, c, value);
        if (symmetric && r != c) triplets.emplace_back(c, r, value);
        places.emplace_back((i - 1) * cols + (j - 1), line);
        ++read;
    }
    if (read < entries) {
        fail(file, line,
             "expected " + std::to_string(entries) + " entries, found " + std::to_string(read));
    }
    // Two entries at one place would be summed: the file means one of them, not their sum.
    std::sort(places.begin(), places.end());
    for (std::size_t k = 1; k < places.size(); ++k) {
        if (places[k].first == places[k - 1].first) {
            const long at = places[k].first;
            fail(file, std::max(places[k].second, places[k - 1].second),
                 "entry (" + std::to_string(at / cols + 1) + ", " + std::to_string(at % cols + 1) +
                     ") given twice (lines " +
                     std::to_string(std::min(places[k].second, places[k - 1].second)) + " and " +
                     std::to_string(std::max(places[k].second, places[k - 1].second)) + ")");
        }
    }
    Eigen::SparseMatrix<double> out(static_cast<Eigen::Index>(rows),
                                    static_cast<Eigen::Index>(cols));
    out.setFromTriplets(triplets.begin(), triplets.end());
    return out;
}

Eigen::MatrixXd read_matrix_market_dense(const std::filesystem::path& file) {
    {
        std::ifstream in(file);
        int line = 0;
        const MatrixMarketSize size = read_header(in, file, line);
        if (size.rows * size.cols > kMatrixMarketMaxDenseEntries) {
            fail(file, line,
                 std::to_string(size.rows) + " x " + std::to_string(size.cols) +
                     " is too large for a dense matrix (at most " +
                     std::to_string(kMatrixMarketMaxDenseEntries) + " entries)");
        }
    }
    return Eigen::MatrixXd(read_matrix_market_sparse(file));
}

}  // namespace sb::structure

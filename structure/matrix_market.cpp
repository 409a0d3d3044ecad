// Reader of Matrix Market coordinate files (real, general or symmetric).
#include "structure/matrix_market.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sb::structure {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, int line, const std::string& message) {
    const std::string place = line > 0 ? ":" + std::to_string(line) : std::string();
    throw MatrixMarketError(file.string() + place + ": " + message);
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

/// Reads the header and the size line, leaving `in` at the first entry line.
MatrixMarketSize read_header(std::ifstream& in, const std::filesystem::path& file, int& line) {
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
        if (!(numbers >> size.rows >> size.cols >> size.entries) || size.rows <= 0 ||
            size.cols <= 0 || size.entries < 0) {
            fail(file, line, "expected 'rows columns entries' with positive sizes");
        }
        break;
    }
    if (size.rows < 0) fail(file, line, "missing size line");
    if (size.symmetric && size.rows != size.cols) {
        fail(file, line, "a symmetric matrix must be square");
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
        if (!(entry >> i >> j >> value)) fail(file, line, "expected 'row column value'");
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
        ++read;
    }
    if (read < entries) {
        fail(file, line,
             "expected " + std::to_string(entries) + " entries, found " + std::to_string(read));
    }
    Eigen::SparseMatrix<double> out(static_cast<Eigen::Index>(rows),
                                    static_cast<Eigen::Index>(cols));
    out.setFromTriplets(triplets.begin(), triplets.end());
    return out;
}

Eigen::MatrixXd read_matrix_market_dense(const std::filesystem::path& file) {
    return Eigen::MatrixXd(read_matrix_market_sparse(file));
}

}  // namespace sb::structure

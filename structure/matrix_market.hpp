// Reader of Matrix Market coordinate files (real, general or symmetric).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <filesystem>
#include <stdexcept>

namespace sb::structure {

/// A Matrix Market file that cannot be read or holds bad content: bad input, not a failure.
class MatrixMarketError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// Rows and columns a file may announce: its size line is read before its entries, and a
/// matrix is allocated from it.
inline constexpr long kMatrixMarketMaxDimension = 1000000;
/// Entries of a matrix read densely (8 bytes each: 800 MB).
inline constexpr long kMatrixMarketMaxDenseEntries = 100000000;

/// Rows, columns and stored entries from the header and size line of a coordinate file.
struct MatrixMarketSize {
    long rows = 0;
    long cols = 0;
    long entries = 0;
    bool symmetric = false;
};

/// Reads only the header and the size line (cheap: used when a config is loaded). Throws
/// MatrixMarketError("file:line: message"): not a regular file, a bad header, sizes below 1
/// or above kMatrixMarketMaxDimension, more entries than the matrix has places.
MatrixMarketSize read_matrix_market_size(const std::filesystem::path& file);

/// Reads "%%MatrixMarket matrix coordinate real general|symmetric" (symmetric: the lower
/// triangle is mirrored). Throws MatrixMarketError("file:line: message") on bad content: an
/// entry outside the matrix, not finite, above the diagonal of a symmetric file, given twice,
/// with more than one value; fewer entries than the size line announces.
Eigen::SparseMatrix<double> read_matrix_market_sparse(const std::filesystem::path& file);

/// Same, as a dense matrix; more than kMatrixMarketMaxDenseEntries is an error.
Eigen::MatrixXd read_matrix_market_dense(const std::filesystem::path& file);

}  // namespace sb::structure

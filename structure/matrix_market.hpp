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

/// Rows, columns and stored entries from the header and size line of a coordinate file.
struct MatrixMarketSize {
    long rows = 0;
    long cols = 0;
    long entries = 0;
    bool symmetric = false;
};

/// Reads only the header and the size line (cheap: used when a config is loaded). Throws
/// MatrixMarketError("file:line: message").
MatrixMarketSize read_matrix_market_size(const std::filesystem::path& file);

/// Reads "%%MatrixMarket matrix coordinate real general|symmetric" (symmetric: the lower
/// triangle is mirrored). Throws MatrixMarketError("file:line: message") on bad content.
Eigen::SparseMatrix<double> read_matrix_market_sparse(const std::filesystem::path& file);

/// Same, as a dense matrix.
Eigen::MatrixXd read_matrix_market_dense(const std::filesystem::path& file);

}  // namespace sb::structure

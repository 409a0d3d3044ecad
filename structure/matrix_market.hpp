// Reader of Matrix Market coordinate files (real, general or symmetric).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <filesystem>

namespace sb::structure {

/// Reads "%%MatrixMarket matrix coordinate real general|symmetric" (symmetric: the lower
/// triangle is mirrored). Throws std::runtime_error("file:line: message") on bad content.
Eigen::SparseMatrix<double> read_matrix_market_sparse(const std::filesystem::path& file);

/// Same, as a dense matrix.
Eigen::MatrixXd read_matrix_market_dense(const std::filesystem::path& file);

}  // namespace sb::structure

// Fuzz target: a Matrix Market file (a structure's mass, stiffness or rigid-body matrix). A
// clean end is a matrix or structure::MatrixMarketError; what is read must agree with the
// size line and hold finite numbers.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "scratch.hpp"
#include "structure/matrix_market.hpp"

namespace {

/// Dense matrices are only built for sizes whose zeros a fuzzer can afford to write.
constexpr long kDenseEntries = 1L << 20;

[[noreturn]] void wrong(const char* what) {
    std::fprintf(stderr, "matrix market reader: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = sb::fuzz::scratch_dir() / "m.mtx";
    sb::fuzz::write_bytes(file, {reinterpret_cast<const char*>(data), size});
    namespace st = sb::structure;
    st::MatrixMarketSize header;
    try {
        header = st::read_matrix_market_size(file);
    } catch (const st::MatrixMarketError&) {
        return 0;
    }
    if (header.rows <= 0 || header.cols <= 0 || header.entries < 0) wrong("a size below 1");
    Eigen::SparseMatrix<double> sparse;
    try {
        sparse = st::read_matrix_market_sparse(file);
    } catch (const st::MatrixMarketError&) {
        return 0;
    }
    if (sparse.rows() != header.rows || sparse.cols() != header.cols) {
        wrong("the matrix is not the size its size line gives");
    }
    for (int k = 0; k < sparse.outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(sparse, k); it; ++it) {
            if (!std::isfinite(it.value())) wrong("a value that is not finite");
        }
    }
    if (header.rows * header.cols <= kDenseEntries) {
        const Eigen::MatrixXd dense = st::read_matrix_market_dense(file);
        if (dense.rows() != header.rows || dense.cols() != header.cols) wrong("dense size");
    }
    return 0;
}

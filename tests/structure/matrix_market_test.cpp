// Matrix Market reading and the matrix-imported structure.
#include "structure/matrix_market.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::structure {
namespace {

std::filesystem::path write(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / ("sb_structure_" + name);
    std::ofstream(path) << text;
    return path;
}

TEST(MatrixMarket, SymmetricFileIsMirrored) {
    const auto p = write("sym.mtx",
                         "%%MatrixMarket matrix coordinate real symmetric\n% comment\n"
                         "2 2 3\n1 1 4.0\n2 1 -1.5\n2 2 3.0\n");
    const Eigen::MatrixXd m = read_matrix_market_dense(p);
    Eigen::Matrix2d expected;
    expected << 4.0, -1.5, -1.5, 3.0;
    EXPECT_EQ(m, expected);
}

TEST(MatrixMarket, BadEntryNamesTheFileAndLine) {
    const auto p = write(
        "bad.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n3 1 2.0\n");
    try {
        (void)read_matrix_market_sparse(p);
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(p.string() + ":4:"), std::string::npos) << e.what();
    }
    const auto q = write("array.mtx", "%%MatrixMarket matrix array real general\n2 2\n");
    EXPECT_THROW((void)read_matrix_market_sparse(q), std::runtime_error);
}

TEST(MatrixModel, TwoDofChainFromFilesHasItsAnalyticFrequencies) {
    const auto dir = std::filesystem::temp_directory_path();
    write("m.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1.0\n2 2 1.0\n");
    write("k.mtx",
          "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 200.0\n2 1 -100.0\n"
          "2 2 100.0\n");
    StructureSpec spec;
    spec.kind = StructureSpec::Kind::matrix;
    spec.matrix.mass_file = "sb_structure_m.mtx";
    spec.matrix.stiffness_file = "sb_structure_k.mtx";
    spec.matrix.named_dofs = {{"base.z", 0}, {"tip.z", 1}};
    spec.excitation.point = "tip";
    const LinearModel model = build_linear_model(spec, dir);
    const ModalBasis basis = compute_modes(model, spec.damping, 2);
    EXPECT_NEAR(2.0 * 3.14159265358979323846 * basis.modes[0].frequency_hz,
                10.0 * std::sqrt((3.0 - std::sqrt(5.0)) / 2.0), 1e-10);
    EXPECT_EQ(model.point("tip").op(2, 1), 1.0);
}

}  // namespace
}  // namespace sb::structure

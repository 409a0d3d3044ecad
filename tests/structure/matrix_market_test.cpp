// Matrix Market reading and the matrix-imported structure.
#include "structure/matrix_market.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

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

/// The message of the MatrixMarketError `read` throws, or a failure.
template <typename Read>
std::string error_of(Read read) {
    try {
        read();
    } catch (const MatrixMarketError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no MatrixMarketError";
    return {};
}

/// fuzz/corpus/matrix_market/regression-huge-columns.mtx and regression-huge-rows.mtx: a size
/// line of 10^12 columns (or 3 x 10^9 rows) was allocated before any entry was read, and a row
/// past 2^31 would have been cut to an int.
TEST(MatrixMarket, ASizeBeyondTheLimitIsAnErrorBeforeAnythingIsAllocated) {
    const auto wide = write("wide.mtx",
                            "%%MatrixMarket matrix coordinate real general\n"
                            "1 1000000000000 0\n");
    const std::string m = error_of([&] { (void)read_matrix_market_sparse(wide); });
    EXPECT_NE(m.find("sb_structure_wide.mtx:2: 1 x 1000000000000: rows and columns are limited "
                     "to 1000000"),
              std::string::npos)
        << m;
    EXPECT_THROW((void)read_matrix_market_size(wide), MatrixMarketError);
    const auto tall = write("tall.mtx",
                            "%%MatrixMarket matrix coordinate real general\n"
                            "3000000000 1 1\n3000000000 1 1.0\n");
    EXPECT_THROW((void)read_matrix_market_sparse(tall), MatrixMarketError);
    const auto dense = write("dense.mtx",
                             "%%MatrixMarket matrix coordinate real general\n"
                             "20000 20000 0\n");
    EXPECT_NO_THROW((void)read_matrix_market_sparse(dense));
    EXPECT_NE(error_of([&] {
                  (void)read_matrix_market_dense(dense);
              }).find("too large for a dense matrix"),
              std::string::npos);
}

TEST(MatrixMarket, MoreEntriesThanPlacesIsAnErrorAtTheSizeLine) {
    const auto p = write("places.mtx",
                         "%%MatrixMarket matrix coordinate real symmetric\n"
                         "2 2 4\n1 1 1\n2 1 1\n2 2 1\n2 2 1\n");
    EXPECT_NE(error_of([&] {
                  (void)read_matrix_market_size(p);
              }).find(":2: 4 entries, more than the 3 places of the matrix"),
              std::string::npos);
}

TEST(MatrixMarket, AnEntryGivenTwiceIsAnErrorNamingBothLines) {
    // Summed, the two would give a stiffness neither line states.
    const auto p = write("twice.mtx",
                         "%%MatrixMarket matrix coordinate real general\n"
                         "2 2 3\n1 1 1.0\n2 2 4.0\n1 1 2.0\n");
    const std::string m = error_of([&] { (void)read_matrix_market_sparse(p); });
    EXPECT_NE(m.find("sb_structure_twice.mtx:5: entry (1, 1) given twice (lines 3 and 5)"),
              std::string::npos)
        << m;
}

TEST(MatrixMarket, AnEntryOrSizeLineWithMoreNumbersIsAnError) {
    const auto complex = write("complex.mtx",
                               "%%MatrixMarket matrix coordinate real general\n"
                               "1 1 1\n1 1 1.0 2.0\n");
    EXPECT_NE(error_of([&] {
                  (void)read_matrix_market_sparse(complex);
              }).find(":3: expected 'row column value'"),
              std::string::npos);
    const auto size = write("size4.mtx",
                            "%%MatrixMarket matrix coordinate real general\n"
                            "1 1 1 1\n1 1 1.0\n");
    EXPECT_THROW((void)read_matrix_market_size(size), MatrixMarketError);
}

TEST(MatrixMarket, ADeviceIsNotReadAsAMatrix) {
    EXPECT_EQ(error_of([] { (void)read_matrix_market_size("/dev/zero"); }),
              "/dev/zero: not a regular file");
}

TEST(MatrixMarket, TheSizeComesFromTheHeaderAlone) {
    const auto p = write("size.mtx",
                         "%%MatrixMarket matrix coordinate real general\n% comment\n4 3 1\n"
                         "9 9 not even read\n");
    const MatrixMarketSize size = read_matrix_market_size(p);
    EXPECT_EQ(size.rows, 4);
    EXPECT_EQ(size.cols, 3);
    EXPECT_FALSE(size.symmetric);
    EXPECT_THROW((void)read_matrix_market_size(p.string() + ".missing"), MatrixMarketError);
}

/// A three-DOF chain (1 kg masses, 100 N/m springs, fixed-free) in the temp folder.
StructureSpec chain_spec(const std::vector<std::pair<std::string, int>>& dofs) {
    write("chain_m.mtx",
          "%%MatrixMarket matrix coordinate real symmetric\n3 3 3\n1 1 1.0\n2 2 1.0\n3 3 1.0\n");
    write("chain_k.mtx",
          "%%MatrixMarket matrix coordinate real symmetric\n3 3 5\n1 1 200.0\n2 1 -100.0\n"
          "2 2 200.0\n3 2 -100.0\n3 3 100.0\n");
    StructureSpec spec;
    spec.kind = StructureSpec::Kind::matrix;
    spec.matrix.mass_file = "sb_structure_chain_m.mtx";
    spec.matrix.stiffness_file = "sb_structure_chain_k.mtx";
    spec.matrix.named_dofs = dofs;
    spec.excitation.point = dofs.front().first.substr(0, dofs.front().first.find('.'));
    return spec;
}

/// The three 1 kg masses of the chain: with the rigid translation known, the z effective
/// masses of all three modes add up to them.
void expect_effective_masses_sum_to_the_chain_mass(const StructureSpec& spec) {
    const LinearModel model = build_linear_model(spec, std::filesystem::temp_directory_path());
    EXPECT_TRUE(model.rigid_translation_known());
    const ModalBasis basis = compute_modes(model, spec.damping, 3);
    double sum = 0.0;
    for (const auto& m : basis.modes) sum += m.effective_mass_kg.z();
    EXPECT_NEAR(sum, 3.0, 1e-12);
}

TEST(MatrixModel, EffectiveMassesOfAFullyNamedImportSumToItsMass) {
    const StructureSpec spec = chain_spec({{"a.z", 0}, {"b.z", 1}, {"c.z", 2}});
    expect_effective_masses_sum_to_the_chain_mass(spec);
}

TEST(MatrixModel, EffectiveMassesOfAPartlyNamedImportAreUnknownNotWrong) {
    // Row 2 is not named: whether it translates or turns in a rigid motion is unknown, and a
    // rigid vector with 0 there would give effective masses summing to less than the mass.
    const StructureSpec spec = chain_spec({{"a.z", 0}, {"b.z", 1}});
    const LinearModel model = build_linear_model(spec, std::filesystem::temp_directory_path());
    EXPECT_FALSE(model.rigid_translation_known());
    const ModalBasis basis = compute_modes(model, spec.damping, 3);
    for (const auto& m : basis.modes) EXPECT_TRUE(m.effective_mass_kg.array().isNaN().all());
}

TEST(MatrixModel, ARigidBodyFileCompletesAPartlyNamedImport) {
    StructureSpec spec = chain_spec({{"a.z", 0}, {"b.z", 1}});
    write("chain_r.mtx",
          "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 3 1.0\n2 3 1.0\n3 3 1.0\n");
    spec.matrix.rigid_body_file = "sb_structure_chain_r.mtx";
    expect_effective_masses_sum_to_the_chain_mass(spec);
}

TEST(MatrixModel, AMassMatrixThatIsNotPositiveDefiniteIsRejectedWithItsFile) {
    StructureSpec spec = chain_spec({{"a.z", 0}});
    write("chain_m.mtx",
          "%%MatrixMarket matrix coordinate real symmetric\n3 3 2\n1 1 1.0\n3 3 1.0\n");
    try {
        (void)build_linear_model(spec, std::filesystem::temp_directory_path());
        FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("sb_structure_chain_m.mtx: the mass matrix must be "
                                             "positive definite"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace sb::structure

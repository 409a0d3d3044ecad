// The key reference: listing and the markdown tables of docs.
#include "config/reference.hpp"

#include <gtest/gtest.h>

#include "test_model.hpp"

namespace sb::config::test {
namespace {

TEST(ConfigReference, GenericRowsNameEveryKeyWithItsDefault) {
    const auto rows = key_rows(model_schema(), nullptr);
    std::vector<std::string> paths;
    for (const auto& r : rows) paths.push_back(r.path + " = " + r.value);
    for (const char* expected :
         {"length_m = 1.0", "stiffness = automatic", "shear = absent", "inner.beta = as alpha",
          "wheels.NAME.radius_m = 0.3", "spokes[i].length_m = required", "points.NAME = -"}) {
        EXPECT_NE(std::find(paths.begin(), paths.end(), expected), paths.end()) << expected;
    }
}

TEST(ConfigReference, TheMarkdownTableShowsTypeBoundUnitDefaultAndMeaning) {
    const auto tables = documented_tables(model_schema());
    ASSERT_FALSE(tables.empty());
    EXPECT_EQ(tables.front().header, "[]");  // the top-level keys
    const std::string md = markdown_table(tables.front());
    EXPECT_NE(md.find("| `length_m` | number > 0 [m] | `1.0` | length |"), std::string::npos) << md;
    EXPECT_NE(md.find("| `colour` | `\"red\"`, `\"blue\"` | `\"red\"` | colour |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| `stiffness` | number > 0 [N/m] or `\"automatic\"` | `\"automatic\"` | "
                      "stiffness; `\"automatic\"`: chosen by the bench |"),
              std::string::npos)
        << md;
}

TEST(ConfigReference, KeyBlocksAreRewrittenAndMissingOrUnknownOnesReported) {
    std::vector<std::string> problems;
    const std::string text =
        "intro\n<!-- keys [inner] -->\nstale\n<!-- /keys -->\nmiddle\n<!-- keys [nothing] -->\n"
        "<!-- /keys -->\nend\n";
    const std::string updated = update_key_blocks(text, model_schema(), problems);
    EXPECT_NE(updated.find("<!-- keys [inner] -->\n| key | type | default | meaning |"),
              std::string::npos)
        << updated;
    EXPECT_EQ(updated.find("stale"), std::string::npos);
    EXPECT_NE(updated.find("middle\n"), std::string::npos);
    EXPECT_NE(
        std::find(problems.begin(), problems.end(), "the block [nothing] names no declared table"),
        problems.end());
    EXPECT_NE(std::find(problems.begin(), problems.end(), "no keys block documents [[spokes]]"),
              problems.end());
    // Written again, nothing changes.
    std::vector<std::string> again;
    EXPECT_EQ(update_key_blocks(updated, model_schema(), again), updated);
}

}  // namespace
}  // namespace sb::config::test

#include "bench/config_reader.hpp"

#include <gtest/gtest.h>

namespace sb::bench {
namespace {

std::vector<ConfigError> errors_of(ConfigDocument& doc) {
    try {
        doc.diagnostics().throw_if_any();
    } catch (const ConfigException& e) {
        return e.errors();
    }
    return {};
}

TEST(ConfigReader, UnreadKeysAreReportedAsUnknownWithTheirLine) {
    auto doc = ConfigDocument::parse_text("[a]\nknown = 1.0\ntypo_key = 2\n", "t.toml");
    Section root = Section::root(doc);
    Section a = root.table("a", "");
    EXPECT_DOUBLE_EQ(a.number("known", 0.0, ""), 1.0);
    a.finish();
    root.finish();
    const auto errors = errors_of(doc);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].format(),
              "t.toml:3:12: a.typo_key = 2: unknown key (see docs/config.md for the keys of [a])");
}

TEST(ConfigReader, WrongTypeNamesTheExpectedType) {
    auto doc = ConfigDocument::parse_text("x = \"ten\"\n", "t.toml");
    Section root = Section::root(doc);
    root.number("x", 0.0, "a length [m]");
    root.finish();
    const auto errors = errors_of(doc);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].format(), "t.toml:1:5: x = \"ten\": must be a number (a length [m])");
}

TEST(ConfigReader, IntegersAreAcceptedWhereNumbersAreExpected) {
    auto doc = ConfigDocument::parse_text("x = 3\n", "t.toml");
    Section root = Section::root(doc);
    EXPECT_DOUBLE_EQ(root.number("x", 0.0, ""), 3.0);
    root.finish();
    EXPECT_TRUE(errors_of(doc).empty());
}

TEST(ConfigReader, ChoiceListsTheAllowedValues) {
    auto doc = ConfigDocument::parse_text("kind = \"glued\"\n", "t.toml");
    Section root = Section::root(doc);
    root.choice("kind", "clamped", {"clamped", "pinned"}, "boundary condition");
    const auto errors = errors_of(doc);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].constraint, "must be one of: clamped, pinned");
    EXPECT_EQ(errors[0].line, 1);
}

TEST(ConfigReader, SyntaxErrorsCarryLineAndColumn) {
    try {
        ConfigDocument::parse_text("a = 1\nb = = 2\n", "t.toml");
        FAIL() << "a syntax error must throw";
    } catch (const ConfigException& e) {
        ASSERT_EQ(e.errors().size(), 1u);
        EXPECT_EQ(e.errors()[0].line, 2);
        EXPECT_EQ(e.errors()[0].key_path, "(syntax)");
    }
}

TEST(ConfigReader, LeafViolationsAreLocatedInsideArraysOfTables) {
    auto doc = ConfigDocument::parse_text("[[m]]\nx = 1\n[[m]]\nx = 2\n", "t.toml");
    Section root = Section::root(doc);
    root.report({{"m[1].x", "2", "must be < 2", "test"}});
    const auto errors = errors_of(doc);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].line, 4);
    EXPECT_EQ(errors[0].key_path, "m[1].x");
}

}  // namespace
}  // namespace sb::bench

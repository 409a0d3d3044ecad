// Reading a document through declarations: every problem at its key, line and column.
#include <gtest/gtest.h>

#include "test_model.hpp"

namespace sb::config::test {
namespace {

std::vector<std::string> errors_of(const std::string& text) {
    std::vector<std::string> errors;
    read_model(text, errors);
    return errors;
}

TEST(ConfigRead, EveryKindOfKeyIsReadIntoItsMember) {
    std::vector<std::string> errors;
    const Model m = read_model(
        "length_m = 2.5\ncount = 2\nstiffness = 3e5\nflag = true\ncolour = \"blue\"\n"
        "blue_only = 4.0\nlevels = [1, 2.5]\nnames = [\"a\", \"b\"]\nlabel = \"x\"\n"
        "position = [1, 2, 3]\n[inner]\nalpha = 7.0\n[wheels.front]\nradius_m = 0.4\n"
        "[wheels.back]\n[[spokes]]\nlength_m = 0.2\n[[spokes]]\nlength_m = 0.3\ncount = 5\n"
        "[points]\nb = 0.5\na = 0.25\n",
        errors);
    ASSERT_TRUE(errors.empty()) << errors.front();
    EXPECT_EQ(m.length_m, 2.5);
    EXPECT_EQ(m.count, 2);
    EXPECT_EQ(m.stiffness, 3e5);
    EXPECT_FALSE(m.shear.has_value());
    EXPECT_TRUE(m.flag);
    EXPECT_EQ(m.colour, Colour::blue);
    EXPECT_EQ(m.blue_only, 4.0);
    EXPECT_EQ(m.levels, (std::vector<double>{1.0, 2.5}));
    EXPECT_EQ(m.names, (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(m.position[2], 3.0);
    EXPECT_EQ(m.inner.alpha, 7.0);
    EXPECT_FALSE(m.inner.beta.has_value());  // follows alpha: resolved when used
    // Named tables and NAME = number lines keep the order the file writes them in.
    ASSERT_EQ(m.wheels.size(), 2u);
    EXPECT_EQ(m.wheels[0].name, "front");
    EXPECT_EQ(m.wheels[1].radius_m, 0.3);
    ASSERT_EQ(m.spokes.size(), 2u);
    EXPECT_EQ(m.spokes[1].count, 5);
    ASSERT_EQ(m.points.size(), 2u);
    EXPECT_EQ(m.points[0].name, "b");
    EXPECT_EQ(m.points[1].x_m, 0.25);
}

TEST(ConfigRead, UnknownKeysAreReportedWithTheirLineAndColumn) {
    EXPECT_EQ(errors_of("[inner]\nalpha = 1.0\ntypo_key = 2\n"),
              (std::vector<std::string>{"t.toml:3:12: inner.typo_key = 2: unknown key (see "
                                        "docs/config.md for the keys of [inner])"}));
}

TEST(ConfigRead, AWrongTypeNamesTheExpectedTypeAndTheMeaningWithItsUnit) {
    EXPECT_EQ(errors_of("length_m = \"ten\"\n"),
              (std::vector<std::string>{
                  "t.toml:1:12: length_m = \"ten\": must be a number (length [m])"}));
    EXPECT_EQ(errors_of("count = 2.5\n"),
              (std::vector<std::string>{"t.toml:1:9: count = 2.5: must be an integer (count)"}));
}

TEST(ConfigRead, IntegersAreAcceptedWhereNumbersAreDeclared) {
    std::vector<std::string> errors;
    EXPECT_EQ(read_model("length_m = 3\n", errors).length_m, 3.0);
    EXPECT_TRUE(errors.empty());
}

TEST(ConfigRead, AValueOutsideItsBoundNamesTheBound) {
    EXPECT_EQ(errors_of("length_m = 0\n"),
              (std::vector<std::string>{"t.toml:1:12: length_m = 0: must be > 0 (length [m])"}));
}

TEST(ConfigRead, AnArrayElementOutsideItsBoundIsPlacedAtTheElement) {
    EXPECT_EQ(errors_of("levels = [1.0, -2.0]\n"),
              (std::vector<std::string>{
                  "t.toml:1:16: levels = -2.0: every value must be > 0 (levels [g])"}));
}

TEST(ConfigRead, AChoiceOutsideItsNamesListsThem) {
    EXPECT_EQ(errors_of("colour = \"green\"\n"),
              (std::vector<std::string>{
                  "t.toml:1:10: colour = \"green\": must be one of: red, blue (colour)"}));
}

TEST(ConfigRead, SyntaxErrorsCarryLineAndColumn) {
    const auto errors = errors_of("a = 1\nb = = 2\n");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].rfind("t.toml:2:", 0), 0u) << errors[0];
    EXPECT_NE(errors[0].find("(syntax)"), std::string::npos) << errors[0];
}

TEST(ConfigRead, AMissingRequiredKeyIsReportedAtItsTable) {
    EXPECT_EQ(errors_of("[[spokes]]\ncount = 2\n"),
              (std::vector<std::string>{
                  "t.toml:1:1: spokes[0].length_m: is required (spoke length [m])"}));
}

TEST(ConfigRead, AKeyThatDoesNotApplyIsAnErrorWhenDeclaredSo) {
    EXPECT_EQ(errors_of("blue_only = 3.0\n"),
              (std::vector<std::string>{"t.toml:1:13: blue_only = 3.0: does not apply: only "
                                        "for colour = \"blue\" (blue setting)"}));
}

TEST(ConfigRead, AutomaticIsAWordOnlyKeysDeclaredAutomaticTake) {
    std::vector<std::string> errors;
    EXPECT_FALSE(read_model("stiffness = \"automatic\"\n", errors).stiffness.has_value());
    EXPECT_TRUE(errors.empty());
    EXPECT_EQ(errors_of("length_m = \"automatic\"\n"),
              (std::vector<std::string>{
                  "t.toml:1:12: length_m = \"automatic\": must be a number (length [m])"}));
    EXPECT_EQ(errors_of("stiffness = 0.0\n"),
              (std::vector<std::string>{"t.toml:1:13: stiffness = 0.0: must be > 0 (stiffness "
                                        "[N/m])"}));
}

TEST(ConfigRead, ALeafViolationIsReportedAtTheKeyTheUserWroteWithItsDeclaredMeaning) {
    EXPECT_EQ(errors_of("[inner]\nalpha = 12.0\n"),
              (std::vector<std::string>{
                  "t.toml:2:9: inner.alpha = 12: must be <= 10 (alpha value [Pa])"}));
}

TEST(ConfigRead, ACheckAcrossKeysOfADefaultValueIsPlacedAtItsTable) {
    EXPECT_EQ(errors_of("levels = [1.0]\n[inner]\nalpha = 1.0\n"),
              (std::vector<std::string>{
                  "t.toml:1:1: count = 3: must be <= the number of levels (count)"}));
}

TEST(ConfigRead, ChecksDoNotJudgeATableWithErrors) {
    // The bad alpha is reported once, by its bound; the check across keys never sees it.
    EXPECT_EQ(errors_of("[inner]\nalpha = -1.0\n"),
              (std::vector<std::string>{
                  "t.toml:2:9: inner.alpha = -1.0: must be > 0 (alpha value [Pa])"}));
}

TEST(ConfigRead, EveryErrorIsCollectedNotJustTheFirst) {
    EXPECT_EQ(errors_of("length_m = -1\ncolour = \"green\"\nunknown = 1\n[[spokes]]\n").size(), 4u);
}

TEST(ConfigRead, ElementsOfArraysOfTablesArePlacedAtTheirOwnLines) {
    EXPECT_EQ(errors_of("[[spokes]]\nlength_m = 1.0\n[[spokes]]\nlength_m = -1.0\n"),
              (std::vector<std::string>{
                  "t.toml:4:12: spokes[1].length_m = -1.0: must be > 0 (spoke length [m])"}));
}

}  // namespace
}  // namespace sb::config::test

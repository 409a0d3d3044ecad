// Every value by its dotted path: read it, change it as if the file held the new value.
#include "config/dotted_path.hpp"

#include <gtest/gtest.h>

#include "test_model.hpp"

namespace sb::config::test {
namespace {

constexpr const char* kText =
    "length_m = 2.0\nlevels = [1.0, 2.0, 3.0]\n[inner]\nalpha = 4.0\n[wheels.front]\n"
    "radius_m = 0.4\n[[spokes]]\nlength_m = 0.2\n[[spokes]]\nlength_m = 0.3\n[points]\n"
    "\"p.1\" = 0.5\n";

struct Loaded {
    Model model;
    SourceMap where;
};

Loaded load() {
    Loaded l;
    std::vector<std::string> errors;
    l.model = read_model(kText, errors, &l.where);
    EXPECT_TRUE(errors.empty());
    return l;
}

/// The formatted errors of `change`, which must throw ConfigException.
template <class Change>
std::vector<std::string> errors_of(Change change) {
    try {
        change();
    } catch (const ConfigException& e) {
        std::vector<std::string> out;
        for (const auto& error : e.errors()) out.push_back(error.format());
        return out;
    }
    ADD_FAILURE() << "the change was accepted";
    return {};
}

TEST(DottedPath, GetGivesEveryKindOfValueTheWayTheBenchUsesIt) {
    const Loaded l = load();
    EXPECT_EQ(std::get<double>(get(model_schema(), &l.model, "length_m")), 2.0);
    EXPECT_EQ(std::get<std::int64_t>(get(model_schema(), &l.model, "count")), 3);
    EXPECT_TRUE(std::holds_alternative<std::monostate>(get(model_schema(), &l.model, "stiffness")));
    EXPECT_EQ(std::get<std::string>(get(model_schema(), &l.model, "colour")), "red");
    // A following key gives the value of the key it follows.
    EXPECT_EQ(std::get<double>(get(model_schema(), &l.model, "inner.beta")), 4.0);
    EXPECT_EQ(std::get<double>(get(model_schema(), &l.model, "wheels.front.radius_m")), 0.4);
    EXPECT_EQ(std::get<double>(get(model_schema(), &l.model, "spokes[1].length_m")), 0.3);
    EXPECT_EQ(std::get<double>(get(model_schema(), &l.model, "points.\"p.1\"")), 0.5);
}

TEST(DottedPath, SetChangesTheMemberAndAFollowingKeyFollowsIt) {
    Loaded l = load();
    set(model_schema(), &l.model, l.where, "inner.alpha", 6.0, {"--set", 0, 0});
    EXPECT_EQ(l.model.inner.alpha, 6.0);
    EXPECT_EQ(std::get<double>(get(model_schema(), &l.model, "inner.beta")), 6.0);
    set_text(model_schema(), &l.model, l.where, "inner.beta", "2.5", {"--set", 0, 0});
    set(model_schema(), &l.model, l.where, "inner.alpha", 7.0, {"--set", 0, 0});
    EXPECT_EQ(std::get<double>(get(model_schema(), &l.model, "inner.beta")), 2.5);
}

TEST(DottedPath, SetTextTakesTomlValuesAndBareWords) {
    Loaded l = load();
    const Origin o{"--set", 0, 0};
    set_text(model_schema(), &l.model, l.where, "colour", "blue", o);
    EXPECT_EQ(l.model.colour, Colour::blue);
    set_text(model_schema(), &l.model, l.where, "stiffness", "2e5", o);
    EXPECT_EQ(l.model.stiffness, 2e5);
    set_text(model_schema(), &l.model, l.where, "stiffness", "automatic", o);
    EXPECT_FALSE(l.model.stiffness.has_value());
    set_text(model_schema(), &l.model, l.where, "position", "[1, 2, 3.5]", o);
    EXPECT_EQ(l.model.position[2], 3.5);
    set_text(model_schema(), &l.model, l.where, "flag", "true", o);
    EXPECT_TRUE(l.model.flag);
    set_text(model_schema(), &l.model, l.where, "spokes[0].count", "4", o);
    EXPECT_EQ(l.model.spokes[0].count, 4);
    set_text(model_schema(), &l.model, l.where, "points.\"p.1\"", "0.75", o);
    EXPECT_EQ(l.model.points[0].x_m, 0.75);
}

TEST(DottedPath, AValueIsCheckedExactlyAsInTheFileAndNamedByItsOrigin) {
    Loaded l = load();
    EXPECT_EQ(errors_of([&] {
                  set_text(model_schema(), &l.model, l.where, "length_m", "-1", {"--set", 0, 0});
              }),
              (std::vector<std::string>{"--set: length_m = -1: must be > 0 (length [m])"}));
    EXPECT_EQ(errors_of([&] {
                  set_text(model_schema(), &l.model, l.where, "colour", "green", {"--set", 0, 0});
              }),
              (std::vector<std::string>{"--set: colour = green: must be one of: red, blue "
                                        "(colour)"}));
    EXPECT_EQ(l.model.length_m, 2.0);
}

TEST(DottedPath, AnUnknownOrIncompletePathIsRefusedNamingIt) {
    Loaded l = load();
    const Origin o{"--set", 0, 0};
    for (const char* path : {"no.such.key", "inner", "wheels.rear.radius_m", "spokes[5].count",
                             "spokes.count", "length_m.x", "inner..alpha"}) {
        const auto errors =
            errors_of([&] { set_text(model_schema(), &l.model, l.where, path, "1", o); });
        ASSERT_EQ(errors.size(), 1u) << path;
        EXPECT_EQ(errors[0].rfind("--set: ", 0), 0u) << errors[0];
    }
}

TEST(DottedPath, AChangeThatBreaksACheckAcrossKeysIsUndoneAndPlacedAtItsOrigin) {
    Loaded l = load();
    EXPECT_EQ(
        errors_of([&] {
            set(model_schema(), &l.model, l.where, "count", std::int64_t{5}, {"calibration", 0, 0});
        }),
        (std::vector<std::string>{
            "calibration: count = 5: must be <= the number of levels (count)"}));
    EXPECT_EQ(l.model.count, 3);
    EXPECT_TRUE(l.where.overrides.empty());
}

TEST(DottedPath, AKeyThatDoesNotApplyCannotBeSet) {
    Loaded l = load();
    const auto errors = errors_of([&] {
        set_text(model_schema(), &l.model, l.where, "blue_only", "3", {"--set", 0, 0});
    });
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("does not apply: only for colour = \"blue\""), std::string::npos)
        << errors[0];
}

TEST(DottedPath, ACheckErrorAfterAnOverrideIsPlacedAtTheOverride) {
    Loaded l = load();
    set(model_schema(), &l.model, l.where, "count", std::int64_t{3}, {"--set", 0, 0});
    // Shorter levels break the count check; the count was set on the command line.
    const auto errors = errors_of([&] {
        set_text(model_schema(), &l.model, l.where, "levels", "[1.0]", {"--set levels", 0, 0});
    });
    EXPECT_EQ(
        errors,
        (std::vector<std::string>{"--set: count = 3: must be <= the number of levels (count)"}));
}

TEST(DottedPath, OneNumberOfAVectorOrAnArrayIsAValueOfItsOwn) {
    Loaded l = load();
    const Origin o{"--set", 0, 0};
    EXPECT_EQ(std::get<double>(get(model_schema(), &l.model, "levels[1]")), 2.0);
    const Declaration& d = declaration(model_schema(), &l.model, "levels[2]");
    EXPECT_EQ(d.type, Type::number);
    EXPECT_EQ(d.unit, "g");
    set_text(model_schema(), &l.model, l.where, "levels[1]", "2.5", o);
    EXPECT_EQ(l.model.levels, (std::vector<double>{1.0, 2.5, 3.0}));
    set(model_schema(), &l.model, l.where, "position[2]", 0.25, o);
    EXPECT_EQ(l.model.position[2], 0.25);
    EXPECT_EQ(l.model.position[0], 0.0);
    // Checked like the whole value: the bound of every element, and the checks across keys.
    EXPECT_EQ(errors_of([&] { set_text(model_schema(), &l.model, l.where, "levels[0]", "-1", o); }),
              (std::vector<std::string>{"--set: levels[0] = -1: must be > 0 (levels, number 0 "
                                        "[g])"}));
    EXPECT_EQ(l.model.levels[0], 1.0);
    for (const char* path : {"levels[3]", "position[3]", "levels[0].x", "length_m[0]"}) {
        const auto errors =
            errors_of([&] { set_text(model_schema(), &l.model, l.where, path, "1", o); });
        ASSERT_EQ(errors.size(), 1u) << path;
        EXPECT_EQ(errors[0].rfind("--set: ", 0), 0u) << errors[0];
    }
}

TEST(DottedPath, SplitAssignmentNeedsAKeyAndAnEqualsSign) {
    std::string key;
    std::string value;
    EXPECT_TRUE(split_assignment("a.b=[1, 2]", key, value));
    EXPECT_EQ(key, "a.b");
    EXPECT_EQ(value, "[1, 2]");
    EXPECT_FALSE(split_assignment("a.b", key, value));
    EXPECT_FALSE(split_assignment("=3", key, value));
}

}  // namespace
}  // namespace sb::config::test

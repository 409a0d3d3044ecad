// Writing a typed model back: resolved TOML, canonical text, identity hash.
#include "config/write.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "config/dotted_path.hpp"
#include "test_model.hpp"

namespace sb::config::test {
namespace {

constexpr const char* kWrittenText =
    "length_m = 2.0\ncount = 2\nstiffness = 3e5\ncolour = \"blue\"\nblue_only = 4.0\nlevels = "
    "[1.0, 2.0]\n"
    "names = [\"a \\\"quoted\\\" name\", \"tab\\there\"]\n[inner]\nalpha = 4.0\n"
    "[wheels.\"front left\"]\nradius_m = 0.4\n[[spokes]]\nlength_m = 0.2\n[[spokes]]\n"
    "length_m = 0.3\ncount = 1\n[points]\n\"p.1\" = 0.5\nq = 0.25\n";

Model load(const std::string& text) {
    std::vector<std::string> errors;
    Model m = read_model(text, errors);
    EXPECT_TRUE(errors.empty()) << (errors.empty() ? "" : errors.front());
    return m;
}

TEST(ConfigWrite, TheWrittenTomlReadsBackToTheSameModelAndText) {
    const Model m = load(kWrittenText);
    const std::string written = write_toml(model_schema(), &m, "# header");
    const Model again = load(written);
    EXPECT_EQ(write_toml(model_schema(), &again, "# header"), written);
    EXPECT_EQ(canonical_text(model_schema(), &again), canonical_text(model_schema(), &m));
    EXPECT_EQ(again.wheels.at(0).name, "front left");
    EXPECT_EQ(again.names.at(0), "a \"quoted\" name");
    EXPECT_EQ(again.points.at(0).name, "p.1");
}

TEST(ConfigWrite, AutomaticIsWrittenAsTheWordAnAbsentOptionalNotAtAllAFollowerAsItsValue) {
    const Model m = load("length_m = 1.5\n");
    const std::string written = write_toml(model_schema(), &m, "");
    EXPECT_NE(written.find("\nstiffness = \"automatic\"\n"), std::string::npos) << written;
    EXPECT_EQ(written.find("shear"), std::string::npos) << written;
    EXPECT_NE(written.find("\nbeta = 1.0\n"), std::string::npos) << written;
    // Keys that do not apply are not written (blue_only with colour red).
    EXPECT_EQ(written.find("blue_only"), std::string::npos) << written;
}

TEST(ConfigWrite, NumbersAreWrittenWithDigitsThatReadBackExactly) {
    Model m;
    for (const double v : {0.1 + 0.2, 1.0 / 3.0, 1e-300, 72e9, 6.02214076e23, 1.0, 5e-324}) {
        m.length_m = v;
        const Model again = load(write_toml(model_schema(), &m, ""));
        EXPECT_EQ(again.length_m, v) << number_text(v);
    }
    EXPECT_EQ(number_text(3.0), "3.0");  // a float literal, not the integer 3
    EXPECT_EQ(number_text(std::numeric_limits<double>::infinity()), "inf");
}

TEST(ConfigWrite, TheCanonicalTextIsSortedAndIndependentOfOrderCommentsAndLayout) {
    const Model a = load("length_m = 2.0\n[inner]\nalpha = 4.0\n[wheels.w]\nradius_m = 0.5\n");
    const Model b = load(
        "# the same, written otherwise\nwheels.w.radius_m = 5e-1\ninner = { alpha = 4 }\n"
        "length_m = 2   # metres\n");
    EXPECT_EQ(canonical_text(model_schema(), &a), canonical_text(model_schema(), &b));
    EXPECT_EQ(identity_hash(model_schema(), &a), identity_hash(model_schema(), &b));
    const std::string text = canonical_text(model_schema(), &a);
    EXPECT_NE(text.find("inner.alpha = 4.0\ninner.beta = 4.0\n"), std::string::npos) << text;
}

TEST(ConfigWrite, EveryValueIsPartOfTheHash) {
    const Model base = load(kWrittenText);
    const std::string hash = identity_hash(model_schema(), &base);
    for (const auto& [path, value] : std::vector<std::pair<std::string, std::string>>{
             {"length_m", "2.0000000000000004"},
             {"stiffness", "automatic"},
             {"inner.beta", "4.5"},
             {"wheels.\"front left\".radius_m", "0.41"},
             {"spokes[1].count", "2"},
             {"points.q", "0.3"},
             {"label", "other"}}) {
        Model changed = base;
        SourceMap where;
        set_text(model_schema(), &changed, where, path, value, {"test", 0, 0});
        EXPECT_NE(identity_hash(model_schema(), &changed), hash) << path;
    }
}

TEST(ConfigWrite, Fnv1aGivesTheReferenceValues) {
    // Test vectors of the 64-bit FNV-1a hash (Fowler, Noll, Vo; IETF draft-eastlake-fnv).
    EXPECT_EQ(fnv1a_hex(""), "cbf29ce484222325");
    EXPECT_EQ(fnv1a_hex("a"), "af63dc4c8601ec8c");
    EXPECT_EQ(fnv1a_hex("foobar"), "85944171f73967e8");
}

}  // namespace
}  // namespace sb::config::test

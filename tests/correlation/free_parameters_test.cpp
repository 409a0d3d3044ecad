// Freeing config values by their dotted paths, and the designs of the searches.
#include "correlation/free_parameters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "config/errors.hpp"
#include "correlation/space_filling.hpp"

namespace sb::correlation {
namespace {

bench::CampaignConfig h0() {
    return bench::load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
}

std::string error_text(const std::function<void()>& f) {
    try {
        f();
    } catch (const config::ConfigException& e) {
        return e.what();
    }
    return "no error";
}

TEST(FreeParameters, AnIntervalGivenOrTheDeclaredOneAndTheStartFromTheConfig) {
    const auto config = h0();
    const auto free = parse_free_parameters(
        config, {"dampers.pd.contact.sliding_friction", "structure.beam.length_m=0.5:0.6"});
    ASSERT_EQ(free.size(), 2U);
    EXPECT_EQ(free[0].lo, 0.1);
    EXPECT_EQ(free[0].hi, 1.0);
    EXPECT_EQ(free[0].start, 0.6);  // paper 000's calibrated value, in the shipped config
    EXPECT_EQ(free[1].lo, 0.5);
    EXPECT_EQ(free[1].hi, 0.6);
    EXPECT_EQ(free[1].start, 0.543);
    EXPECT_NE(free[0].meaning.find("sliding friction"), std::string::npos);
}

TEST(FreeParameters, TheDefaultSetIsTheParticlesFrictionAndRestitution) {
    const auto free = default_free_parameters(h0());
    std::vector<std::string> paths;
    for (const auto& p : free) paths.push_back(p.path);
    EXPECT_EQ(paths, (std::vector<std::string>{"dampers.pd.contact.sliding_friction",
                                               "dampers.pd.contact.rolling_friction",
                                               "dampers.pd.contact.restitution"}));
}

TEST(FreeParameters, EveryBadItemIsNamedAtOnce) {
    const auto config = h0();
    const std::string text = error_text([&] {
        parse_free_parameters(
            config, {"dampers.pd.contact.no_such_key", "dampers.pd.contact.normal",
                     "structure.beam.length_m", "structure.beam.length_m=0.6:0.5",
                     "dampers.pd.contact.sliding_friction=-1:1", "structure.beam.width_m=a:b"});
    });
    EXPECT_NE(text.find("no_such_key: names no value"), std::string::npos) << text;
    EXPECT_NE(text.find("normal: is not a number"), std::string::npos) << text;
    EXPECT_NE(text.find("length_m: has no default search interval"), std::string::npos) << text;
    EXPECT_NE(text.find("MIN must be less than MAX"), std::string::npos) << text;
    EXPECT_NE(text.find("within the key's bound >= 0"), std::string::npos) << text;
    EXPECT_NE(text.find("width_m = a:b: must be MIN:MAX"), std::string::npos) << text;
    EXPECT_NE(error_text([&] { parse_free_parameters(config, {}); }).find("frees no key"),
              std::string::npos);
}

TEST(FreeParameters, ValuesSetAsIfTheFileHeldThemAndTheWallFrictionFollows) {
    const auto config = h0();
    const auto free = parse_free_parameters(config, {"dampers.pd.contact.sliding_friction"});
    const auto changed = with_values(config, free, to_values(free, {0.5}));
    EXPECT_DOUBLE_EQ(
        std::get<double>(bench::get_value(changed, "dampers.pd.contact.sliding_friction")), 0.55);
    EXPECT_DOUBLE_EQ(
        std::get<double>(bench::get_value(changed, "dampers.pd.contact.wall_sliding_friction")),
        0.55);
    EXPECT_DOUBLE_EQ(to_unit(free, {0.55})[0], 0.5);
}

TEST(FreeParameters, ALogScaleSearchesTheRatioAndANumberOfAVectorCanBeFreed) {
    const auto config = h0();
    const auto free =
        parse_free_parameters(config, {"structure.beam.youngs_modulus_pa=1e10:1e12:log",
                                       "structure.excitation.direction[2]=0.5:1"});
    ASSERT_EQ(free.size(), 2U);
    EXPECT_TRUE(free[0].log_scale);
    EXPECT_FALSE(free[1].log_scale);
    // The middle of a log interval is the geometric mean.
    const auto values = to_values(free, {0.5, 0.5});
    EXPECT_NEAR(values[0], 1e11, 1e-4);
    EXPECT_NEAR(to_unit(free, {1e11, 0.75})[0], 0.5, 1e-12);
    EXPECT_EQ(free[1].start, 1.0);
    const auto changed = with_values(config, free, values);
    EXPECT_NEAR(changed.structure.beam.youngs_modulus_pa, 1e11, 1e-4);
    EXPECT_EQ(changed.structure.excitation.direction.z(), 0.75);
    EXPECT_NE(error_text([&] {
                  parse_free_parameters(config, {"structure.beam.youngs_modulus_pa=0:1e12:log"});
              }).find("a log scale needs MIN > 0"),
              std::string::npos);
}

TEST(SpaceFilling, HaltonIsTheRadicalInverseInPrimeBases) {
    const auto h = halton(4, 2);
    // Index 1..4 in base 2: 1/2, 1/4, 3/4, 1/8; in base 3: 1/3, 2/3, 1/9, 4/9.
    EXPECT_DOUBLE_EQ(h[0][0], 0.5);
    EXPECT_DOUBLE_EQ(h[1][0], 0.25);
    EXPECT_DOUBLE_EQ(h[2][0], 0.75);
    EXPECT_DOUBLE_EQ(h[3][0], 0.125);
    EXPECT_DOUBLE_EQ(h[0][1], 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(h[1][1], 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(h[2][1], 1.0 / 9.0);
    EXPECT_DOUBLE_EQ(h[3][1], 4.0 / 9.0);
}

TEST(SpaceFilling, ALatinHypercubeUsesEveryStratumOnceAndIsReproducible) {
    const auto a = latin_hypercube(10, 3, 5);
    for (int d = 0; d < 3; ++d) {
        std::set<int> strata;
        for (const auto& p : a) strata.insert(static_cast<int>(p[d] * 10));
        EXPECT_EQ(strata.size(), 10U);
    }
    EXPECT_EQ(a, latin_hypercube(10, 3, 5));
    EXPECT_NE(a, latin_hypercube(10, 3, 6));
}

}  // namespace
}  // namespace sb::correlation

// Plot files of identified levels, and the SVGs gnuplot makes from them.
#include "identification/plots.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sdof_frf.hpp"

namespace sb::identification {
namespace {

namespace fs = std::filesystem;

std::string text_of(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (auto i = text.find(what); i != std::string::npos; i = text.find(what, i + 1)) ++n;
    return n;
}

/// Three levels of an SDOF with growing damping, arrangement "H-0".
std::vector<LevelIdentification> three_levels() {
    std::vector<LevelIdentification> levels;
    const double zetas[] = {0.02, 0.03, 0.05};
    const double level_g[] = {0.25, 0.5, 1.0};
    for (int i = 0; i < 3; ++i) {
        const auto frf = testing::modal_accelerance(
            testing::grid_around(6.4, zetas[i], 31, 4.0, 0.2), {{6.4, zetas[i], 1.0}});
        levels.push_back(identify_frf("H-0", level_g[i], frf, {}, true));
    }
    return levels;
}

fs::path fresh_dir(const std::string& name) {
    const auto dir = fs::temp_directory_path() / "sb_identification_plots_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(Plots, WriteOneDataBlockPerLevelAndAScriptThatNamesEveryLevel) {
    const auto dir = fresh_dir("script");
    PlotOptions options;
    options.render = false;
    const auto r = write_plots(dir, three_levels(), options);
    EXPECT_FALSE(r.rendered);
    EXPECT_NE(r.message.find("gnuplot plots.gp"), std::string::npos) << r.message;
    const auto frf = text_of(dir / "plots" / "H-0-frf.dat");
    EXPECT_EQ(count(frf, "# level "), 3);
    EXPECT_EQ(count(frf, "\n\n\n"), 2);  // blocks separated by two blank lines
    const auto damping = text_of(dir / "plots" / "H-0-damping.dat");
    EXPECT_EQ(count(damping, "\n"), 4);  // header and one row per level
    const auto script = text_of(r.script);
    for (const char* title :
         {"'0.25 g'", "'0.5 g'", "'1 g'", "'half-power'", "'circle-fit'", "'rational-fraction'"}) {
        EXPECT_GT(count(script, title), 0) << title;
    }
    ASSERT_EQ(r.svg.size(), 2u);
    EXPECT_EQ(r.svg[0], dir / "H-0-frf.svg");
}

TEST(Plots, SeveralFillingsOfALevelGiveOneCurvePointWithTheirScatterAsErrorBars) {
    // Two fillings at 1 g: damping 2 % and 4 %, the same frequency.
    std::vector<LevelIdentification> levels;
    const double zetas[] = {0.02, 0.04};
    for (int k = 0; k < 2; ++k) {
        const auto frf = testing::modal_accelerance(
            testing::grid_around(6.4, zetas[k], 31, 4.0, 0.2), {{6.4, zetas[k], 1.0}});
        levels.push_back(identify_frf("H-0", 1.0, frf, {}, true));
        levels.back().filling = k;
    }
    const auto dir = fresh_dir("fillings");
    PlotOptions options;
    options.render = false;
    const auto r = write_plots(dir, levels, options);
    // The FRF of each filling, the second named by its filling.
    const auto frf = text_of(dir / "plots" / "H-0-frf.dat");
    EXPECT_EQ(count(frf, "# level "), 2);
    EXPECT_EQ(count(frf, "# level 1 g, filling 1"), 1);
    // One row for the level: the mean damping 3 % and the sample std sqrt(2) %.
    std::istringstream damping(text_of(dir / "plots" / "H-0-damping.dat"));
    std::string header;
    std::getline(damping, header);
    double level = 0.0;
    double zeta_percent = 0.0;
    double zeta_std_percent = 0.0;
    damping >> level >> zeta_percent >> zeta_std_percent;
    EXPECT_EQ(level, 1.0);
    EXPECT_NEAR(zeta_percent, 3.0, 0.03);
    EXPECT_NEAR(zeta_std_percent, std::sqrt(2.0), 0.03);
    std::string rest;
    std::getline(damping, rest);
    std::string more;
    EXPECT_FALSE(std::getline(damping, more) && !more.empty()) << "one row per level";
    const auto script = text_of(r.script);
    EXPECT_GT(count(script, "yerrorlines"), 0);
    EXPECT_GT(count(script, "'1 g, filling 1'"), 0);
}

TEST(Plots, GnuplotMakesSvgsWithOneCurvePerLevelAndPerMethod) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
        GTEST_SKIP() << "gnuplot is not installed";
    }
    const auto dir = fresh_dir("svg");
    const auto r = write_plots(dir, three_levels());
    ASSERT_TRUE(r.rendered) << r.message;
    EXPECT_TRUE(r.message.empty()) << r.message;
    const auto frf = text_of(dir / "H-0-frf.svg");
    // Magnitude and phase panels: one curve per level in each.
    EXPECT_EQ(count(frf, "<g id=\"gnuplot_plot_"), 6);
    for (const char* title :
         {"<title>0.25 g</title>", "<title>0.5 g</title>", "<title>1 g</title>"}) {
        EXPECT_EQ(count(frf, title), 2) << title;
    }
    const auto damping = text_of(dir / "H-0-damping.svg");
    EXPECT_EQ(count(damping, "<g id=\"gnuplot_plot_"), 6);  // 3 methods × 2 panels
    EXPECT_EQ(count(damping, "<title>circle-fit</title>"), 2);
}

TEST(Plots, ALevelWithoutAPointIsLeftOutOfTheFrfPlotAndAnArrangementWithoutAnyHasNone) {
    // A predicted campaign whose points at a level were all `uncertain` identifies that
    // level with an empty FRF; gnuplot refuses a plot with no point ("x range is invalid").
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
        GTEST_SKIP() << "gnuplot is not installed";
    }
    auto levels = three_levels();
    LevelIdentification empty;
    empty.arrangement = "H-0";
    empty.level_g = 2.0;
    levels.push_back(empty);
    LevelIdentification other = empty;
    other.arrangement = "V-0";
    levels.push_back(other);
    const auto dir = fresh_dir("empty");
    const auto r = write_plots(dir, levels);
    ASSERT_TRUE(r.rendered) << r.message << "\n" << text_of(dir / "plots" / "gnuplot.log");
    const auto frf = text_of(dir / "H-0-frf.svg");
    EXPECT_EQ(count(frf, "<g id=\"gnuplot_plot_"), 6);  // the three levels with points
    EXPECT_EQ(count(frf, "<title>2 g</title>"), 0);
    EXPECT_EQ(count(text_of(dir / "plots" / "H-0-frf.dat"), "# level"), 3);
    EXPECT_FALSE(fs::exists(dir / "V-0-frf.svg"));
    for (const auto& svg : r.svg) EXPECT_NE(svg.filename(), "V-0-frf.svg");
}

}  // namespace
}  // namespace sb::identification

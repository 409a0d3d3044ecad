#include "bench/campaign_config.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "config/errors.hpp"
#include "tests/support/small_beam_config.hpp"

namespace sb::bench {
namespace {

const std::string& kValidBeam = sb::test::kSmallBeamConfig;

/// Runs `load`, expecting a config::ConfigException; returns its formatted errors.
template <class Load>
std::vector<std::string> errors_from(Load load) {
    try {
        load();
    } catch (const config::ConfigException& e) {
        std::vector<std::string> out;
        for (const auto& error : e.errors()) {
            out.push_back(error.format());
        }
        return out;
    }
    ADD_FAILURE() << "the config was accepted";
    return {};
}

/// Loads `text`, expecting failure; returns the formatted errors.
std::vector<std::string> errors_of(const std::string& text) {
    return errors_from([&] { (void)load_campaign_config_text(text, "bad.toml"); });
}

/// Loads the config file `file`, expecting failure; returns the formatted errors.
std::vector<std::string> errors_of_file(const std::filesystem::path& file) {
    return errors_from([&] { (void)load_campaign_config(file); });
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

TEST(CampaignConfig, AValidBeamConfigLoadsInSi) {
    const auto config = load_campaign_config_text(kValidBeam, "good.toml");
    EXPECT_EQ(config.name, "t");
    EXPECT_DOUBLE_EQ(config.structure.beam.length_m, 0.5);
    ASSERT_EQ(config.structure.beam.masses.size(), 1u);
    // A mass given by its point sits there, and takes its name, whenever the model is built.
    EXPECT_EQ(config.structure.beam.masses[0].point, "tip");
    EXPECT_DOUBLE_EQ(config.structure.beam.resolved().masses[0].x_m, 0.5);
    EXPECT_EQ(config.structure.beam.resolved().masses[0].name, "tip");
    EXPECT_FALSE(config.structure.beam.shear_modulus_pa.has_value());
}

TEST(CampaignConfig, ANegativeLengthIsReportedWithItsLine) {
    const auto errors = errors_of(replaced(kValidBeam, "length_m = 0.5", "length_m = -0.5"));
    ASSERT_FALSE(errors.empty());
    EXPECT_EQ(errors[0].rfind("bad.toml:9:12: structure.beam.length_m = -0.5: must be > 0", 0), 0u)
        << errors[0];
}

TEST(CampaignConfig, AnUnknownKeyIsAnError) {
    const auto errors =
        errors_of(replaced(kValidBeam, "width_m = 0.05", "width_m = 0.05\nwdith_m = 0.05"));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0].rfind("bad.toml:11:11: structure.beam.wdith_m = 0.05: unknown key", 0), 0u)
        << errors[0];
}

TEST(CampaignConfig, AMassOutsideTheBeamIsReported) {
    const auto errors = errors_of(replaced(kValidBeam, "point = \"tip\"", "x_m = 0.7"));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(
        errors[0].find("bad.toml:24:7: structure.beam.masses[0].x_m = 0.7: must be in [0, 0.5]"),
        std::string::npos)
        << errors[0];
}

TEST(CampaignConfig, AMissingSectionIsReported) {
    const auto errors = errors_of("[campaign]\nname = \"t\"\n");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("structure: is required"), std::string::npos) << errors[0];
}

TEST(CampaignConfig, AMissingBeamTableIsReported) {
    const auto errors = errors_of("[structure]\nkind = \"beam\"\n");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("structure.beam: is required"), std::string::npos) << errors[0];
}

TEST(CampaignConfig, AWrongTypeIsReported) {
    const auto errors =
        errors_of(replaced(kValidBeam, "density_kg_m3 = 2700.0", "density_kg_m3 = \"steel\""));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0],
              "bad.toml:12:17: structure.beam.density_kg_m3 = \"steel\": must be a number "
              "(beam density [kg/m^3])");
}

TEST(CampaignConfig, EveryErrorIsCollectedNotJustTheFirst) {
    std::string text = replaced(kValidBeam, "length_m = 0.5", "length_m = -0.5");
    text = replaced(text, "kind = \"clamped\"", "kind = \"glued\"");
    text = replaced(text, "mass_kg = 0.01", "mass_kg = 0.01\ncolour = \"red\"");
    EXPECT_GE(errors_of(text).size(), 3u);
}

TEST(CampaignConfig, AnUnknownExcitationPointIsReported) {
    const auto errors =
        errors_of(replaced(kValidBeam, "point = \"shaker\"", "point = \"nowhere\""));
    ASSERT_FALSE(errors.empty());
    EXPECT_NE(errors[0].find("structure.excitation.point = "), std::string::npos);
    EXPECT_NE(errors[0].find("nowhere"), std::string::npos) << errors[0];
}

TEST(CampaignConfig, TheBuiltInConfigLoads) {
    const auto config = load_campaign_config_text(builtin_config_text(), kBuiltinConfigName);
    EXPECT_EQ(config.structure.kind, structure::StructureSpec::Kind::beam);
    EXPECT_GE(config.structure.beam.masses.size(), 6u);
}

TEST(CampaignConfig, ADamperFillsByRandomInsertionUnlessToldToPour) {
    const auto plain = load_campaign_config_text(builtin_config_text(), kBuiltinConfigName);
    ASSERT_EQ(plain.campaign.dampers.size(), 1u);
    EXPECT_EQ(plain.campaign.dampers[0].fill, DamperSpec::Fill::random);
    const auto poured = load_campaign_config_text(
        std::string(builtin_config_text()) + "\n[dampers.pd.settle]\nfill = \"pour\"\n",
        "pour.toml");
    EXPECT_EQ(poured.campaign.dampers[0].fill, DamperSpec::Fill::pour);
}

TEST(CampaignConfig, TheDiameterScatterReadsWithinItsBoundAndIsLocatedOutside) {
    const std::string builtin(builtin_config_text());
    const auto scattered = [&](const std::string& value) {
        return replaced(builtin, "diameter_m = 0.003",
                        "diameter_m = 0.003\ndiameter_scatter = " + value);
    };
    EXPECT_EQ(load_campaign_config_text(builtin, "plain.toml")
                  .campaign.dampers[0]
                  .particles.diameter_scatter,
              0.0);
    EXPECT_EQ(load_campaign_config_text(scattered("0.05"), "scatter.toml")
                  .campaign.dampers[0]
                  .particles.diameter_scatter,
              0.05);
    for (const std::string value : {"-0.1", "0.3"}) {
        const auto errors = errors_of(scattered(value));
        ASSERT_EQ(errors.size(), 1u) << value;
        EXPECT_EQ(errors[0].rfind("bad.toml:40:20: dampers.pd.particles.diameter_scatter = " +
                                      value + ": must be in [0, 0.2]",
                                  0),
                  0u)
            << errors[0];
    }
}

TEST(CampaignConfig, AStiffnessFromTheMaterialsNeedsHertzAndNoGivenStiffness) {
    const std::string base = std::string(builtin_config_text());
    const std::string hertz =
        replaced(base, "normal = \"hooke\"", "normal = \"hertz\"\nstiffness_for = \"materials\"");
    const auto config = load_campaign_config_text(hertz, "hertz.toml");
    EXPECT_EQ(config.campaign.dampers[0].contact.stiffness_for,
              ContactSpec::StiffnessFor::materials);
    // at 2 g RMS near 6.4 Hz: steel on steel, the solver's own constants (stiffness 0)
    const dem::ExcitationContact chosen =
        config.campaign.dampers[0].excitation_contact(std::sqrt(2.0) * 2.0 * 9.80665, 6.4);
    EXPECT_EQ(chosen.stiffness, 0.0);
    EXPECT_GT(chosen.time_step_s, 0.0);

    auto errors = errors_of(
        replaced(base, "normal = \"hooke\"", "normal = \"hooke\"\nstiffness_for = \"materials\""));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("bad.toml:44:"), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("dampers.pd.contact.stiffness_for"), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("needs normal = \"hertz\""), std::string::npos) << errors[0];

    errors = errors_of(replaced(hertz, "max_overlap_fraction = 0.02",
                                "max_overlap_fraction = 0.02\nnormal_stiffness = 4e9"));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("dampers.pd.contact.normal_stiffness"), std::string::npos)
        << errors[0];
    EXPECT_NE(errors[0].find("cannot be given with stiffness_for"), std::string::npos) << errors[0];
}

TEST(CampaignConfig, ALockThatHoldsNothingOrFightsLockedIsReportedAtItsKey) {
    const std::string base = std::string(builtin_config_text());
    auto errors = errors_of(base + "\n[dampers.pd.lock]\nrelease_time_s = 5.0\n");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("dampers.pd.lock.release_time_s"), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("releases nothing"), std::string::npos) << errors[0];

    errors = errors_of(replaced(base, "[dampers.pd]\n", "[dampers.pd]\nlocked = true\n") +
                       "\n[dampers.pd.lock]\nfraction = 0.5\n");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("dampers.pd.lock.fraction"), std::string::npos) << errors[0];

    errors = errors_of(base + "\n[dampers.pd.lock]\nfraction = 1.0\nrelease_fraction = 1.5\n");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("dampers.pd.lock.release_fraction"), std::string::npos) << errors[0];
}

TEST(CampaignConfig, AnUnknownFillMethodIsReportedWithItsChoices) {
    const auto errors =
        errors_of(std::string(builtin_config_text()) + "\n[dampers.pd.settle]\nfill = \"shake\"\n");
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("dampers.pd.settle.fill = \"shake\""), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("pour"), std::string::npos) << errors[0];
}

TEST(CampaignConfig, AMissingBeamTableStillLetsTheOtherStructureErrorsThrough) {
    const auto errors = errors_of(
        "[structure]\nkind = \"beam\"\nmodes = 0\n[structure.damping]\ndefault_ratio = 1.5\n"
        "colour = \"red\"\n");
    ASSERT_EQ(errors.size(), 4u);
    EXPECT_EQ(errors[0],
              "bad.toml:1:1: structure.beam: is required (the beam of a structure of "
              "kind \"beam\")");
    EXPECT_EQ(errors[1].rfind("bad.toml:3:9: structure.modes = 0: must be >= 1", 0), 0u);
    EXPECT_EQ(errors[2].rfind("bad.toml:5:17: structure.damping.default_ratio = 1.5: must be in "
                              "[0, 1)",
                              0),
              0u);
    EXPECT_EQ(errors[3].rfind("bad.toml:6:10: structure.damping.colour = \"red\": unknown key", 0),
              0u);
}

TEST(CampaignConfig, ANegativeSeedIsAnErrorNotClampedToZero) {
    const auto errors = errors_of(replaced(kValidBeam, "name = \"t\"", "name = \"t\"\nseed = -1"));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0],
              "bad.toml:4:8: campaign.seed = -1: must be >= 0 (seed of the particle filling)");
}

TEST(CampaignConfig, ASectionThickerThanItIsWideIsAnError) {
    const auto errors =
        errors_of(replaced(kValidBeam, "thickness_m = 0.003", "thickness_m = 0.08"));
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(
        errors[0].rfind(
            "bad.toml:11:15: structure.beam.thickness_m = 0.08: must be <= width_m = 0.05", 0),
        0u)
        << errors[0];
}

/// A two-DOF import written to a fresh folder; returns the config text naming it.
std::filesystem::path write_two_dof_matrices(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("sb_bench_matrix_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "m.mtx")
        << "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1.0\n2 2 1.0\n";
    std::ofstream(dir / "k.mtx") << "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n"
                                    "1 1 200.0\n2 1 -100.0\n2 2 100.0\n";
    return dir;
}

std::string matrix_config(const std::string& dofs) {
    return "[structure]\nkind = \"matrix\"\n\n[structure.matrix]\nmass_file = \"m.mtx\"\n"
           "stiffness_file = \"k.mtx\"\n\n[structure.matrix.dofs]\n" +
           dofs + "\n[structure.excitation]\npoint = \"tip\"\n";
}

TEST(CampaignConfig, AMatrixImportLoadsWithItsFilesNextToTheConfig) {
    const auto dir = write_two_dof_matrices("good");
    std::ofstream(dir / "c.toml") << matrix_config("\"base.z\" = 0\n\"tip.z\" = 1\n");
    const auto config = load_campaign_config(dir / "c.toml");
    EXPECT_EQ(config.structure.kind, structure::StructureSpec::Kind::matrix);
    EXPECT_EQ(config.structure.matrix.mass_file, dir / "m.mtx");
    EXPECT_TRUE(config.structure.matrix.mass_file.is_absolute());
    ASSERT_EQ(config.structure.matrix.named_dofs.size(), 2u);
    EXPECT_EQ(config.structure.matrix.named_dofs[1], (std::pair<std::string, int>{"tip.z", 1}));
}

TEST(CampaignConfig, AMatrixDofBeyondTheMatrixIsReportedAtItsLine) {
    const auto dir = write_two_dof_matrices("row");
    const auto file = dir / "c.toml";
    std::ofstream(file) << matrix_config("\"base.z\" = 0\n\"tip.z\" = 2\n");
    const auto errors = errors_of_file(file);
    ASSERT_EQ(errors.size(), 1u);
    // The DOF's name holds a dot: its path quotes it, as --set takes it.
    EXPECT_EQ(errors[0], file.string() +
                             ":10:11: structure.matrix.dofs.\"tip.z\" = 2: must be < 2, the rows "
                             "of mass_file (zero-based row of a named DOF)");
}

TEST(CampaignConfig, MatricesOfDifferentSizesAreReportedAtTheStiffnessFile) {
    const auto dir = write_two_dof_matrices("sizes");
    std::ofstream(dir / "k.mtx")
        << "%%MatrixMarket matrix coordinate real symmetric\n3 3 1\n1 1 200.0\n";
    const auto file = dir / "c.toml";
    std::ofstream(file) << matrix_config("\"tip.z\" = 1\n");
    const auto errors = errors_of_file(file);
    ASSERT_EQ(errors.size(), 1u);
    // The file is named as the bench resolved it: absolute, next to the config.
    EXPECT_EQ(errors[0],
              file.string() + ":6:18: structure.matrix.stiffness_file = \"" +
                  (dir / "k.mtx").string() +
                  "\": must hold 2 x 2 like mass_file, holds 3 x 3 (Matrix Market stiffness "
                  "matrix)");
}

}  // namespace
}  // namespace sb::bench

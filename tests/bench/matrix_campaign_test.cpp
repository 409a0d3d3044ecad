// Campaigns on an imported model: base excitation, masses the bench adds at its named points
// (rigid dampers, mounting blocks, the shaker's armature), and the config's errors.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/arrangement.hpp"
#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "core/units.hpp"
#include "structure/linear_model.hpp"

namespace sb::bench {
namespace {

using namespace std::complex_literals;
using test::fresh_dir;

// The chain base -k1- m1 -k2- m2 along z, stiffness-proportional damping C = beta K (a
// dashpot beta k_i across each spring).
constexpr double kM1 = 1.0, kM2 = 0.5;       // [kg]
constexpr double kK1 = 4.0e4, kK2 = 1.0e4;   // [N/m]
constexpr double kStiffnessLossBeta = 2e-4;  // [s]
constexpr double kConfigMassKg = 0.1;        // [[structure.matrix.masses]] at m1
constexpr double kBlockMassKg = 0.05;        // the arrangement's mounting block at m2
// The rigid bed: 20 steel spheres of 3 mm.
constexpr int kSpheres = 20;
constexpr double kSphereDiameterM = 0.003, kSteelKgM3 = 7800.0;

/// Closed-form X2/X_b of the chain in absolute coordinates (Cramer's rule on the 2 x 2
/// dynamic stiffness):
///   [k1 + k2 - W^2 m1 + iW(c1 + c2), -(k2 + iW c2)] [X1]   [k1 + iW c1]
///   [-(k2 + iW c2), k2 - W^2 m2 + iW c2          ] [X2] = [0         ] X_b
std::complex<double> chain_transmissibility(double m1, double m2, double f_hz) {
    const double w = kTwoPi * f_hz;
    const std::complex<double> s1 = kK1 + 1i * w * kStiffnessLossBeta * kK1;
    const std::complex<double> s2 = kK2 + 1i * w * kStiffnessLossBeta * kK2;
    const std::complex<double> d11 = s1 + s2 - w * w * m1;
    const std::complex<double> d22 = s2 - w * w * m2;
    return s2 * s1 / (d11 * d22 - s2 * s2);
}

/// The chain's config in a fresh folder with its matrix files; `excitation` completes it,
/// `matrix_keys` adds keys to [structure.matrix].
std::filesystem::path write_chain_config(const std::string& name, const std::string& excitation,
                                         const std::string& matrix_keys = "") {
    const auto dir = fresh_dir(name);
    std::filesystem::create_directories(dir);
    write_file_atomically(dir / "m.mtx",
                          "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 " +
                              std::to_string(kM1) + "\n2 2 " + std::to_string(kM2) + "\n");
    write_file_atomically(
        dir / "k.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 " +
                           std::to_string(kK1 + kK2) + "\n2 1 " + std::to_string(-kK2) + "\n2 2 " +
                           std::to_string(kK2) + "\n");
    const std::string text = R"([campaign]
name = "matrix-chain"
levels_g = [0.2]
arrangements = ["V"]
control_point = "m2"
response_points = ["m1"]
point_start = "linear-steady-state"  # exact for the linear specimen a rigid bed makes

[campaign.frequencies]
values_hz = [15.0, 18.5, 24.0]
refine_points = 0

[arrangements.V]
oscillation = "vertical"
block_mass_kg = 0.05

[dampers.pd]
point = "m2"
model = "rigid"

[dampers.pd.particles]
count = 20
diameter_m = 0.003
density_kg_m3 = 7800.0

[controller]
tolerance = 0.01

[output]
series = false

[structure]
kind = "matrix"
modes = 2

[structure.matrix]
mass_file = "m.mtx"
stiffness_file = "k.mtx"
)" + matrix_keys + R"(
[structure.matrix.dofs]
m1 = 0
"m2.z" = 1

[[structure.matrix.masses]]
point = "m1"
mass_kg = 0.1

[structure.damping]
model = "rayleigh"
beta_s = 2e-4

)" + excitation;
    write_file_atomically(dir / "chain.toml", text);
    return dir / "chain.toml";
}

const std::string kBase = "[structure.excitation]\nkind = \"base\"\ndirection = [0.0, 0.0, 1.0]\n";

TEST(MatrixCampaign, ARigidDamperOnABaseDrivenImportGivesTheClosedFormTransmissibility) {
    const CampaignConfig config = load_campaign_config(write_chain_config("matrix-base", kBase));
    CampaignContext context;
    context.threads = 1;
    const CampaignResult result = run_campaign(config, context);

    // The reference is the base acceleration; the control point is m2.
    const auto& channels = result.recording.channels;
    ASSERT_GE(channels.size(), 3u);
    EXPECT_EQ(channels[0].name, "base_acc");
    EXPECT_EQ(channels[0].location, "base");
    EXPECT_EQ(channels[1].name, "acc_m2");

    // m2 carries the rigid bed and the block, m1 the config's mass.
    const double bed_kg = kSpheres * kSteelKgM3 * kPi / 6.0 * std::pow(kSphereDiameterM, 3);
    const double m1 = kM1 + kConfigMassKg;
    const double m2 = kM2 + bed_kg + kBlockMassKg;
    ASSERT_EQ(result.recording.points.size(), 3u);
    for (const auto& p : result.recording.points) {
        EXPECT_EQ(p.status, "converged");
        const std::complex<double> measured = p.values[1].amplitude / p.values[0].amplitude;
        const std::complex<double> expected = chain_transmissibility(m1, m2, p.frequency_hz);
        EXPECT_LT(std::abs(measured / expected - 1.0), 1e-3)
            << p.frequency_hz << " Hz: |X2/Xb| " << std::abs(measured) << " against "
            << std::abs(expected) << ", error " << std::abs(measured / expected - 1.0);
        // Controlled to the level: 0.2 g RMS at m2.
        EXPECT_NEAR(p.values[1].rms / kStandardGravity, 0.2, 0.2 * 0.01);
    }
}

TEST(MatrixCampaign, TheShakersArmatureJoinsTheImportAtTheDrivePoint) {
    const std::string force =
        "[structure.excitation]\nkind = \"force\"\npoint = \"m2\"\n"
        "direction = [0.0, 0.0, 1.0]\n\n[physics.shaker]\nforce_factor_n_per_a = 10.0\n"
        "armature_mass_kg = 0.3\n";
    const CampaignConfig config =
        load_campaign_config(write_chain_config("matrix-armature", force));
    const structure::StructureSpec spec =
        arrangement_structure(config, config.campaign.arrangements.front(), false);
    const structure::LinearModel model = structure::build_linear_model(spec, config.base_dir);
    const double bed_kg = kSpheres * kSteelKgM3 * kPi / 6.0 * std::pow(kSphereDiameterM, 3);
    EXPECT_NEAR(model.mass()(0, 0), kM1 + kConfigMassKg, 1e-12);
    EXPECT_NEAR(model.mass()(1, 1), kM2 + 0.3 + kBlockMassKg + bed_kg, 1e-12);
    EXPECT_EQ(model.mass()(0, 1), 0.0);
}

/// The text of the ConfigException loading `path` throws, or a failure.
std::string config_error(const std::filesystem::path& path) {
    try {
        (void)load_campaign_config(path);
    } catch (const config::ConfigException& e) {
        return e.what();
    }
    ADD_FAILURE() << "no ConfigException";
    return {};
}

TEST(MatrixCampaign, AnInfluenceFileOfTheWrongSizeIsAConfigErrorAtItsKey) {
    const auto path =
        write_chain_config("matrix-bad-influence", kBase, "base_influence_file = \"r.mtx\"\n");
    write_file_atomically(path.parent_path() / "r.mtx",
                          "%%MatrixMarket matrix coordinate real general\n3 1 1\n1 1 1.0\n");
    const std::string message = config_error(path);
    EXPECT_NE(message.find("structure.matrix.base_influence_file"), std::string::npos) << message;
    EXPECT_NE(message.find("must hold 2 x 1"), std::string::npos) << message;
}

/// The chain with its damping as a matrix file, C = beta K, and [structure.damping] set to a
/// modal 30 % that the file must replace.
std::filesystem::path write_chain_with_damping_file(const std::string& name,
                                                    const std::string& c_text) {
    const auto path = write_chain_config(name, kBase, "damping_file = \"c.mtx\"\n");
    write_file_atomically(path.parent_path() / "c.mtx", c_text);
    std::string text = read_text_file(path);
    const std::string rayleigh = "model = \"rayleigh\"\nbeta_s = 2e-4\n";
    text.replace(text.find(rayleigh), rayleigh.size(), "default_ratio = 0.3\n");
    write_file_atomically(path, text);
    return path;
}

TEST(MatrixCampaign, ADampingMatrixFileGivesTheClosedFormOfItsDashpots) {
    const std::string c = "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 " +
                          std::to_string(kStiffnessLossBeta * (kK1 + kK2)) + "\n2 1 " +
                          std::to_string(-kStiffnessLossBeta * kK2) + "\n2 2 " +
                          std::to_string(kStiffnessLossBeta * kK2) + "\n";
    const CampaignConfig config =
        load_campaign_config(write_chain_with_damping_file("matrix-damping-file", c));
    const CampaignResult result = test::run_on_one_thread(config);
    const double bed_kg = kSpheres * kSteelKgM3 * kPi / 6.0 * std::pow(kSphereDiameterM, 3);
    ASSERT_EQ(result.recording.points.size(), 3u);
    for (const auto& p : result.recording.points) {
        EXPECT_EQ(p.status, "converged");
        const std::complex<double> measured = p.values[1].amplitude / p.values[0].amplitude;
        const std::complex<double> expected = chain_transmissibility(
            kM1 + kConfigMassKg, kM2 + bed_kg + kBlockMassKg, p.frequency_hz);
        EXPECT_LT(std::abs(measured / expected - 1.0), 1e-3)
            << p.frequency_hz << " Hz: |X2/Xb| " << std::abs(measured) << " against "
            << std::abs(expected);
    }
}

TEST(MatrixCampaign, ADampingMatrixOfTheWrongSizeOrFeedingEnergyInIsRefused) {
    const std::string wrong_size =
        "%%MatrixMarket matrix coordinate real symmetric\n3 3 1\n1 1 1.0\n";
    const std::string message =
        config_error(write_chain_with_damping_file("matrix-damping-size", wrong_size));
    EXPECT_NE(message.find("structure.matrix.damping_file"), std::string::npos) << message;
    EXPECT_NE(message.find("must hold 2 x 2"), std::string::npos) << message;

    // Readable and of the right size, but with a negative eigenvalue: refused when the model
    // is built, naming the file.
    const std::string negative =
        "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1.0\n2 2 -1.0\n";
    const CampaignConfig config =
        load_campaign_config(write_chain_with_damping_file("matrix-damping-negative", negative));
    try {
        (void)structure::build_linear_model(config.structure, config.base_dir);
        ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("c.mtx: the damping matrix must be positive "
                                             "semi-definite"),
                  std::string::npos)
            << e.what();
    }
}

TEST(MatrixCampaign, WithoutRigidTranslationTheInfluenceFileIsAskedFor) {
    const auto path = write_chain_config("matrix-no-rigid", kBase);
    std::string text = read_text_file(path);
    text.erase(text.find("m1 = 0\n"), 7);  // row 0 unnamed: its rigid share is unknown
    text.replace(text.find("point = \"m1\""), 12, "point = \"m2\"");
    text.replace(text.find("response_points = [\"m1\"]"), 24, "response_points = []");
    write_file_atomically(path, text);
    const std::string message = config_error(path);
    EXPECT_NE(message.find("structure.matrix.base_influence_file"), std::string::npos) << message;
    EXPECT_NE(message.find("is required under base excitation"), std::string::npos) << message;
}

TEST(MatrixCampaign, ASupportOfAnImportIsAConfigError) {
    const std::string with_support =
        "[structure.excitation]\nkind = \"base\"\nsupport = \"root\"\n";
    const std::string message = config_error(write_chain_config("matrix-support", with_support));
    EXPECT_NE(message.find("structure.excitation.support"), std::string::npos) << message;
    EXPECT_NE(message.find("must be absent for an imported model"), std::string::npos) << message;
}

TEST(MatrixCampaign, AnEnclosureMassOfAnImportTurnsAndMovesWithTheEnclosure) {
    // The enclosure at m2, 5 mm above the inner bottom centre at 0 deg, mounted at 90 deg:
    // its centre of gravity rides up the enclosure's own axis, and its axial inertia turns
    // from z to y.
    const std::string enclosure = kBase + R"(
[[structure.matrix.masses]]
name = "enclosure"
point = "m2"
mass_kg = 0.02
offset_m = [0.0, 0.0, 0.005]
inertia_kg_m2 = [3.8e-6, 3.8e-6, 1.5e-6]
)";
    const auto path = write_chain_config("matrix-enclosure", enclosure);
    std::string text = read_text_file(path);
    text.replace(text.find("model = \"rigid\""), 15,
                 "model = \"rigid\"\nenclosure_mass = \"enclosure\"");
    text.replace(text.find("block_mass_kg = 0.05"), 20, "damper_angle_deg = 90.0");
    write_file_atomically(path, text);
    const CampaignConfig config = load_campaign_config(path);
    const ArrangementSpec& arrangement = config.campaign.arrangements.front();
    const DamperMounting m = damper_mounting(arrangement, config.campaign.dampers.front());
    const auto spec = arrangement_structure(config, arrangement, false);
    int found = 0;
    for (const auto& mass : spec.matrix.masses) {
        if (mass.name != "enclosure") continue;
        ++found;
        EXPECT_EQ(mass.point, "m2");
        EXPECT_LT((mass.offset_m - (m.origin_m + 0.005 * m.rotation.col(2))).norm(), 1e-15);
        EXPECT_NEAR(std::abs(m.rotation.col(2).y()), 1.0, 1e-12);  // the axis along y at 90 deg
        EXPECT_NEAR(mass.inertia_kg_m2.x(), 3.8e-6, 1e-18);
        EXPECT_NEAR(mass.inertia_kg_m2.y(), 1.5e-6, 1e-18);
        EXPECT_NEAR(mass.inertia_kg_m2.z(), 3.8e-6, 1e-18);
    }
    EXPECT_EQ(found, 1);

    // A mass of the import at another point is refused, naming the key.
    text.replace(text.find("point = \"m2\"\nmass_kg = 0.02"), 12, "point = \"m1\"");
    write_file_atomically(path, text);
    try {
        (void)load_campaign_config(path);
        ADD_FAILURE() << "an enclosure mass away from the damper was accepted";
    } catch (const config::ConfigException& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("dampers.pd.enclosure_mass"), std::string::npos) << message;
        EXPECT_NE(message.find("[[structure.matrix.masses]] entry at point \"m2\""),
                  std::string::npos)
            << message;
    }
}

}  // namespace
}  // namespace sb::bench

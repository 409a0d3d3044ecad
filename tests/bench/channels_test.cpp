// Channels in any direction and of any quantity: a point's acceleration, velocity and
// displacement along a direction other than the drive's, and a damper's force on the
// structure.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <filesystem>
#include <string>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"
#include "campaign_fixtures.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "core/units.hpp"

namespace sb::bench {
namespace {

using Complex = std::complex<double>;
using namespace std::complex_literals;

// One point p with two translations, y (row 0) and z (row 1), coupled through the
// stiffness: K = [[ky, kc], [kc, kz]], M = m I, C = beta K. Base motion along z moves both
// DOFs by the rigid translation r = (0, 1): only the coupling kc makes y move.
constexpr double kMassKg = 1.0;
constexpr double kKy = 3.0e4, kKz = 5.0e4, kKc = 1.0e4;  // [N/m]
constexpr double kBeta = 2e-4;                           // [s]
constexpr double kBaseAccM_s2 = 2.0;                     // fixed drive, peak

/// The absolute steady state of p per unit base acceleration phasor, x = x_rel + r u_b with
/// (K (1 + i w beta) - w^2 M) x_rel = -M r a_b and u_b = -a_b / w^2.
Eigen::Vector2cd absolute_displacement_per_base_acceleration(double f_hz) {
    const double w = kTwoPi * f_hz;
    Eigen::Matrix2d k;
    k << kKy, kKc, kKc, kKz;
    const Eigen::Matrix2cd dynamic =
        k.cast<Complex>() * (1.0 + 1i * w * kBeta) - w * w * kMassKg * Eigen::Matrix2cd::Identity();
    const Eigen::Vector2cd r(0.0, 1.0);
    const Eigen::Vector2cd relative = dynamic.partialPivLu().solve(-kMassKg * r);
    return relative - r / (w * w);
}

std::filesystem::path write_coupled_point_config(const std::string& name,
                                                 const std::string& channels) {
    const auto dir = test::fresh_dir(name);
    std::filesystem::create_directories(dir);
    write_file_atomically(dir / "m.mtx",
                          "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1.0\n"
                          "2 2 1.0\n");
    write_file_atomically(dir / "k.mtx",
                          "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 " +
                              std::to_string(kKy) + "\n2 1 " + std::to_string(kKc) + "\n2 2 " +
                              std::to_string(kKz) + "\n");
    const std::string text = R"([campaign]
name = "coupled-point"
arrangements = ["V"]
control_point = "p"
point_start = "linear-steady-state"

[campaign.drive]
kind = "fixed"
amplitudes = [2.0]

[campaign.frequencies]
values_hz = [20.0, 30.0, 45.0]
refine_points = 0

[arrangements.V]
oscillation = "vertical"

[controller]
tolerance = 0.001

[structure]
kind = "matrix"
modes = 2

[structure.matrix]
mass_file = "m.mtx"
stiffness_file = "k.mtx"

[structure.matrix.dofs]
"p.y" = 0
"p.z" = 1

[structure.damping]
model = "rayleigh"
beta_s = 2e-4

[structure.excitation]
kind = "base"
direction = [0.0, 0.0, 1.0]
)" + channels;
    write_file_atomically(dir / "point.toml", text);
    return dir / "point.toml";
}

const std::string kMotionChannels = R"(
[[campaign.channels]]
point = "p"
direction = [0.0, 1.0, 0.0]

[[campaign.channels]]
quantity = "displacement"
point = "p"
direction = [0.0, 1.0, 0.0]

[[campaign.channels]]
quantity = "velocity"
point = "p"

[[campaign.channels]]
quantity = "displacement"
point = "p"
name = "tip_z"
)";

TEST(Channels, AChannelAlongYOnAZDrivenImportReadsTheCouplingTerm) {
    const CampaignConfig config =
        load_campaign_config(write_coupled_point_config("channels-y", kMotionChannels));
    const CampaignResult result = test::run_on_one_thread(config);

    const auto& channels = result.recording.channels;
    ASSERT_EQ(channels.size(), 6u);
    EXPECT_EQ(channels[1].name, "acc_p");
    EXPECT_EQ(channels[2].name, "acc_p_y");
    EXPECT_EQ(channels[3].name, "disp_p_y");
    EXPECT_EQ(channels[3].quantity, "displacement");
    EXPECT_EQ(channels[3].unit, "m");
    EXPECT_EQ(channels[4].name, "vel_p");
    EXPECT_EQ(channels[4].unit, "m/s");
    EXPECT_EQ(channels[5].name, "tip_z");

    ASSERT_EQ(result.recording.points.size(), 3u);
    for (const auto& p : result.recording.points) {
        EXPECT_EQ(p.status, "converged");
        const double w = kTwoPi * p.frequency_hz;
        const Complex base = p.values[0].amplitude;
        EXPECT_NEAR(std::abs(base), kBaseAccM_s2, 1e-9 * kBaseAccM_s2);
        const Eigen::Vector2cd x = absolute_displacement_per_base_acceleration(p.frequency_hz);
        // acceleration -w^2 x, velocity i w x, displacement x; y and z.
        const Complex expected[] = {-w * w * x(1) * base, -w * w * x(0) * base, x(0) * base,
                                    1i * w * x(1) * base, x(1) * base};
        for (int c = 0; c < 5; ++c) {
            const Complex measured = p.values[static_cast<std::size_t>(c + 1)].amplitude;
            EXPECT_LT(std::abs(measured / expected[c] - 1.0), 1e-3)
                << p.frequency_hz << " Hz, channel "
                << channels[static_cast<std::size_t>(c + 1)].name << ": " << measured << " against "
                << expected[c];
        }
        // The y motion is the coupling's alone, and not small against z here.
        EXPECT_GT(std::abs(p.values[2].amplitude), 0.1 * std::abs(p.values[1].amplitude));
    }
}

TEST(Channels, ALockedDampersForceIsItsBedsInertia) {
    // A mass on a spring with a locked bed on it, driven by a fixed force: the bed moves with
    // its enclosure, so the force it applies to the mass is -m_bed a (its weight is the
    // mean, which the fundamental leaves out); read along -z it changes sign.
    const std::string text = R"(
[campaign]
name = "sdof-force"
control_point = "table"
point_start = "linear-steady-state"
[[campaign.channels]]
quantity = "damper-force"
damper = "pd"
[[campaign.channels]]
quantity = "damper-force"
damper = "pd"
direction = [0.0, 0.0, -1.0]
[campaign.drive]
kind = "fixed"
amplitudes = [0.5]
[campaign.frequencies]
values_hz = [80.0, 110.0]
refine_points = 0
[dampers.pd]
point = "table"
locked = true
[dampers.pd.particles]
count = 30
[dampers.pd.contact]
normal_stiffness = 2e5
[controller]
tolerance = 0.002
)" + test::table_on_a_spring(0.05);
    const CampaignConfig config = load_campaign_config_text(text, "sdof-force.toml");
    const CampaignResult result = test::run_on_one_thread(config);
    const auto& channels = result.recording.channels;
    ASSERT_EQ(channels.size(), 4u);
    EXPECT_EQ(channels[2].name, "force_pd");
    EXPECT_EQ(channels[2].quantity, "force");
    EXPECT_EQ(channels[2].unit, "N");
    EXPECT_EQ(channels[2].location, "damper:pd");
    EXPECT_EQ(channels[3].name, "force_pd_-z");
    const double bed_kg = particle_mass_kg(config.campaign.dampers.front(), config.campaign.seed);
    ASSERT_EQ(result.recording.points.size(), 2u);
    for (const auto& p : result.recording.points) {
        const Complex a = p.values[1].amplitude;
        const Complex force = p.values[2].amplitude;
        // The staggered coupling hands the bed's load over a step late: a phase of w dt.
        EXPECT_LT(std::abs(force / (-bed_kg * a) - 1.0), 2e-3)
            << p.frequency_hz << " Hz: " << force << " against " << -bed_kg * a;
        EXPECT_LT(std::abs(p.values[3].amplitude + force), 1e-12 * std::abs(force));
    }
}

TEST(Channels, AChannelThatReadsNothingIsAConfigErrorAtItsKey) {
    const auto with_channel = [](const std::string& lines) {
        return test::paper000_h0_with({}) + "\n[[campaign.channels]]\n" + lines + "\n";
    };
    std::string message = test::config_error(with_channel("point = \"nowhere\""), "channels.toml");
    EXPECT_NE(message.find("campaign.channels[0].point"), std::string::npos) << message;
    EXPECT_NE(message.find("must name a point of the structure"), std::string::npos) << message;

    message = test::config_error(with_channel("quantity = \"velocity\""), "channels.toml");
    EXPECT_NE(message.find("campaign.channels[0].point"), std::string::npos) << message;
    EXPECT_NE(message.find("is required for a motion channel"), std::string::npos) << message;

    message = test::config_error(with_channel("quantity = \"damper-force\"\ndamper = \"other\""),
                                 "channels.toml");
    EXPECT_NE(message.find("campaign.channels[0].damper"), std::string::npos) << message;
    EXPECT_NE(message.find("[dampers.other]"), std::string::npos) << message;

    message = test::config_error(with_channel("point = \"acc4\""),
                                 "channels.toml");  // acc_acc4 is a response already
    EXPECT_NE(message.find("campaign.channels[0].name"), std::string::npos) << message;
    EXPECT_NE(message.find("is taken by another channel"), std::string::npos) << message;

    message = test::config_error(with_channel("point = \"acc1\"\ndirection = [0.0, 0.0, 0.0]"),
                                 "channels.toml");
    EXPECT_NE(message.find("campaign.channels[0].direction"), std::string::npos) << message;

    message = test::config_error(with_channel("quantity = \"pressure\"\npoint = \"acc1\""),
                                 "channels.toml");
    EXPECT_NE(message.find("campaign.channels[0].quantity"), std::string::npos) << message;

    std::string rigid = with_channel("quantity = \"damper-force\"\ndamper = \"pd\"");
    rigid.replace(rigid.find("[dampers.pd]\n"), 13, "[dampers.pd]\nmodel = \"rigid\"\n");
    message = test::config_error(rigid, "channels.toml");
    EXPECT_NE(message.find("campaign.channels[0].damper"), std::string::npos) << message;
    EXPECT_NE(message.find("rigid damper"), std::string::npos) << message;
}

}  // namespace
}  // namespace sb::bench

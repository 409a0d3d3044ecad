// Sweep checkpoints: the exact text form, its checksum, and what a damaged file gives.
#include "bench/sweep_checkpoint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace sb::bench {
namespace {

/// A checkpoint with one DEM damper (two particles touching, one wall spring, one locked
/// particle) and one rigid attachment, after two points.
SweepCheckpoint sample_checkpoint() {
    SweepCheckpoint c;
    c.config_hash = "0123456789abcdef";
    c.numerics = "pd.normal_stiffness=424300 pd.time_step_s=3.5784e-06 step_limit_s=3.5784e-06";
    c.points_done = 2;
    c.next_amplitude = 0.1;  // not exact in binary: the hexadecimal text must keep every bit
    c.state.q = Eigen::VectorXd::LinSpaced(3, -1.0 / 3.0, 2.0);
    c.state.q_dot = Eigen::VectorXd::Constant(3, -0.0);
    dem::SolverState dem;
    dem.enclosure.position_m = {0.1, 0.2, 0.3};
    dem.positions_m = {{0.0, 0.0, 0.001}, {0.0, 0.0, 0.004}};
    dem.velocities_m_s = {{1e-300, 0.0, 0.0}, {0.0, -2.5, 0.0}};
    dem.angular_velocities_rad_s = {{0.0, 0.0, 7.0}, {0.0, 0.0, 0.0}};
    dem.radii_m = {0.0015, 0.0015};
    dem.pair_histories = {{0, 1, {1e-9, 0.0, -1e-9}}};
    dem.wall_histories = {{0, 1, {0.0, 3e-10, 0.0}}};
    dem.locked = {{1, {0.0, 0.0, 0.004}}};
    dem.time_s = 1.25;
    dem.step = 125000;
    dem.layers_up = {0.0, 0.0, 9.80665};
    AttachmentState with_particles;
    with_particles.dem = dem;
    c.state.attachments = {with_particles, AttachmentState{}};
    Eigen::Matrix<double, 6, 1> load;
    load << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0;
    c.state.loads = {load, Eigen::Matrix<double, 6, 1>::Zero()};
    for (int i = 0; i < 2; ++i) {
        identification::PointRow row;
        row.arrangement = "H-0";
        row.level_g = 2.0;
        row.frequency_hz = 6.3 + 0.1 * i;
        row.status = i == 0 ? "converged" : "closest";
        row.series = i == 0 ? "series/H-0_2g_0.csv" : "";
        identification::ChannelValue v;
        v.rms = 0.5;
        v.amplitude = {0.25, -0.75};
        v.h2_ratio = 0.01;  // h3 stays NaN: not known
        row.values = {v, v};
        c.rows.push_back(row);
        c.control_log.push_back("H-0,2,6.3,converged,7,0");
    }
    c.energy_log = {"H-0,2,6.3,pd,1e-3,2e-4,3e-4,0,1e-5"};
    return c;
}

constexpr const char* kFile = "out/checkpoints/H-0_2g.txt";

TEST(SweepCheckpoint, ReadsBackExactlyWhatWasWritten) {
    const SweepCheckpoint c = sample_checkpoint();
    const std::string text = serialize_checkpoint(c);
    const SweepCheckpoint back = parse_checkpoint(text, kFile);
    EXPECT_EQ(back.config_hash, c.config_hash);
    EXPECT_EQ(back.numerics, c.numerics);
    EXPECT_EQ(back.points_done, 2);
    EXPECT_EQ(back.next_amplitude, 0.1);
    EXPECT_EQ(back.state.q, c.state.q);
    EXPECT_TRUE(std::signbit(back.state.q_dot[0]));
    ASSERT_EQ(back.state.attachments.size(), 2u);
    ASSERT_TRUE(back.state.attachments[0].dem.has_value());
    EXPECT_FALSE(back.state.attachments[1].dem.has_value());
    const dem::SolverState& dem = *back.state.attachments[0].dem;
    EXPECT_EQ(dem.velocities_m_s[0].x(), 1e-300);
    EXPECT_EQ(dem.pair_histories.size(), 1u);
    EXPECT_EQ(dem.locked.at(0).id, 1u);
    EXPECT_EQ(dem.step, 125000);
    ASSERT_EQ(back.rows.size(), 2u);
    EXPECT_EQ(back.rows[1].frequency_hz, 6.3 + 0.1);
    EXPECT_EQ(back.rows[0].series, "series/H-0_2g_0.csv");
    EXPECT_EQ(back.rows[1].series, "");
    EXPECT_TRUE(std::isnan(back.rows[0].values[1].h3_ratio));
    EXPECT_EQ(back.control_log, c.control_log);
    EXPECT_EQ(back.energy_log, c.energy_log);
    // Written again, the same text: nothing was lost or added on the way.
    EXPECT_EQ(serialize_checkpoint(back), text);
}

/// The sample checkpoint with `extra` as a third attachment, written and read back; written
/// again, the same text.
SweepCheckpoint read_back_with(const AttachmentState& extra) {
    SweepCheckpoint c = sample_checkpoint();
    c.state.attachments.push_back(extra);
    c.state.loads.push_back(Eigen::Matrix<double, 6, 1>::Zero());
    const std::string text = serialize_checkpoint(c);
    SweepCheckpoint back = parse_checkpoint(text, kFile);
    EXPECT_EQ(serialize_checkpoint(back), text);
    return back;
}

TEST(SweepCheckpoint, AnIwanJointsSlidersComeBackBitForBit) {
    AttachmentState joint;
    joint.sliders = std::vector<double>{1.0 / 3.0, -0.0, -2.5e-7, 0.0};
    const SweepCheckpoint back = read_back_with(joint);
    ASSERT_EQ(back.state.attachments.size(), 3u);
    ASSERT_TRUE(back.state.attachments[2].sliders.has_value());
    EXPECT_FALSE(back.state.attachments[2].dem.has_value());
    EXPECT_EQ(*back.state.attachments[2].sliders, *joint.sliders);
    EXPECT_TRUE(std::signbit((*back.state.attachments[2].sliders)[1]));
    EXPECT_FALSE(back.state.attachments[1].sliders.has_value());
}

TEST(SweepCheckpoint, AShakerCoilsCurrentComesBackBitForBit) {
    AttachmentState coil;
    coil.coil_current_a = -1.0 / 3.0;
    const SweepCheckpoint back = read_back_with(coil);
    ASSERT_EQ(back.state.attachments.size(), 3u);
    ASSERT_TRUE(back.state.attachments[2].coil_current_a.has_value());
    EXPECT_EQ(*back.state.attachments[2].coil_current_a, -1.0 / 3.0);
    EXPECT_FALSE(back.state.attachments[2].sliders.has_value());
    EXPECT_FALSE(back.state.attachments[1].coil_current_a.has_value());
}

TEST(SweepCheckpoint, EndsWithTheChecksumOfEverythingBeforeIt) {
    const std::string text = serialize_checkpoint(sample_checkpoint());
    const std::string_view content = checkpoint_content(text);
    ASSERT_LT(content.size(), text.size());
    EXPECT_EQ(content.substr(content.size() - 4), "end\n");
    // 64-bit FNV-1a of the content, computed here from its definition.
    std::uint64_t h = 14695981039346656037ULL;
    for (const char ch : content) {
        h ^= static_cast<unsigned char>(ch);
        h *= 1099511628211ULL;
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    EXPECT_EQ(text.substr(content.size()), std::string("checksum fnv1a64 ") + hex + "\n");
}

TEST(SweepCheckpoint, EveryCutShortCopyIsRefusedNamingTheFile) {
    const std::string text = serialize_checkpoint(sample_checkpoint());
    const std::size_t first_line = text.find('\n') + 1;
    for (std::size_t length = 0; length < text.size(); ++length) {
        try {
            (void)parse_checkpoint(text.substr(0, length), kFile);
            ADD_FAILURE() << "a checkpoint cut to " << length << " of " << text.size()
                          << " bytes was read";
        } catch (const CheckpointError& e) {
            EXPECT_EQ(e.file(), kFile);
            EXPECT_EQ(std::string(e.what()).rfind(kFile, 0), 0u) << e.what();
            if (length > first_line) {
                EXPECT_NE(e.message().find("truncated"), std::string::npos)
                    << length << ": " << e.what();
            }
        }
    }
}

TEST(SweepCheckpoint, EveryChangedByteIsRefusedNamingTheFile) {
    const std::string text = serialize_checkpoint(sample_checkpoint());
    for (std::size_t i = 0; i < text.size(); ++i) {
        for (const int flip : {0x01, 0x20}) {
            std::string damaged = text;
            damaged[i] = static_cast<char>(static_cast<unsigned char>(damaged[i]) ^ flip);
            try {
                (void)parse_checkpoint(damaged, kFile);
                ADD_FAILURE() << "byte " << i << " changed and the checkpoint was read";
            } catch (const CheckpointError& e) {
                EXPECT_EQ(e.file(), kFile);
            }
        }
    }
}

TEST(SweepCheckpoint, AChangedNumberIsReportedAsCorruption) {
    std::string text = serialize_checkpoint(sample_checkpoint());
    const auto at = text.find("points_done 2");
    ASSERT_NE(at, std::string::npos);
    text[at + 12] = '3';
    try {
        (void)parse_checkpoint(text, kFile);
        FAIL() << "read";
    } catch (const CheckpointError& e) {
        EXPECT_NE(e.message().find("corrupted"), std::string::npos) << e.what();
    }
}

TEST(SweepCheckpoint, AnOlderFormatIsNamedAsSuch) {
    std::string text = serialize_checkpoint(sample_checkpoint());
    text.replace(0, text.find('\n'), "shakerbench-sweep-checkpoint 3");
    try {
        (void)parse_checkpoint(text, kFile);
        FAIL() << "read";
    } catch (const CheckpointError& e) {
        EXPECT_EQ(e.line(), 1);
        EXPECT_NE(e.message().find("format '3'"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)parse_checkpoint("points.csv\n", kFile), CheckpointError);
}

/// `content` with its checksum put right: what a faulty writer, or an edit by hand, gives.
std::string resealed(std::string content) { return seal_checkpoint(content); }

TEST(SweepCheckpoint, SealedContentThatDoesNotFitTogetherIsRefusedAtItsLine) {
    const std::string content(checkpoint_content(serialize_checkpoint(sample_checkpoint())));
    const auto refused = [&](std::string text, const std::string& expected) {
        try {
            (void)parse_checkpoint(resealed(std::move(text)), kFile);
            ADD_FAILURE() << "read; expected " << expected;
        } catch (const CheckpointError& e) {
            EXPECT_GT(e.line(), 0) << e.what();
            EXPECT_NE(e.message().find(expected), std::string::npos) << e.what();
        }
    };
    std::string more_points = content;
    more_points.replace(more_points.find("points_done 2"), 13, "points_done 3");
    refused(more_points, "2 rows for 3 finished points");
    std::string extra_value = content;
    extra_value.insert(extra_value.find('\n', extra_value.find("\nq_dot ")), " 0x1p+0");
    refused(extra_value, "follows the values");
    std::string pairs_as_particle = content;
    pairs_as_particle.replace(pairs_as_particle.find("particles 2"), 11, "particles 3");
    refused(pairs_as_particle, "expected 'p'");
    refused(content + "end\n", "text follows 'end'");
    std::string huge = content;
    huge.replace(huge.find("particles 2"), 11, "particles 99999999999");
    refused(huge, "implausible count");
}

}  // namespace
}  // namespace sb::bench

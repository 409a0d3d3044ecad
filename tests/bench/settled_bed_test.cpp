// A poured bed's settling progress: saved as it settles, continued bitwise after a kill.
#include "bench/settled_bed.hpp"

#include <gtest/gtest.h>

#include <string>

#include "bench/campaign_config.hpp"
#include "bench/checkpoint_store.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "core/units.hpp"
#include "killed_store.hpp"

namespace sb::bench {
namespace {

using testing::Killed;
using testing::KilledAfterSaves;

CampaignConfig poured_config() {
    return load_campaign_config_text(
        std::string(builtin_config_text()) + "\n[dampers.pd.settle]\nfill = \"pour\"\n",
        "poured.toml");
}

constexpr double kStiffness = 2e4;  // N/m
const Eigen::Vector3d kGravity(0.0, 0.0, -kStandardGravity);

TEST(SettledBed, APourKilledWhileSettlingResumesToTheBedOfAnUninterruptedOne) {
    const auto config = poured_config();
    const DamperSpec& damper = config.campaign.dampers.front();
    const Eigen::Matrix3d upright = Eigen::Matrix3d::Identity();
    const dem::ParticleSet plain =
        settled_bed(damper, kStiffness, upright, kGravity, 7, nullptr, "bed");

    KilledAfterSaves counting(0);  // a progress at every check: the most save points
    counting.open("hash", false);
    const dem::ParticleSet saved =
        settled_bed(damper, kStiffness, upright, kGravity, 7, &counting, "bed", nullptr, 0.0);
    EXPECT_EQ(saved.positions_m, plain.positions_m);               // saving changes nothing
    EXPECT_FALSE(counting.load_progress(Unfinished::bed, "bed"));  // dropped once the bed is saved
    ASSERT_GT(counting.saves, 3);

    // Killed three times over (after the first save, half-way and before the last), each
    // time resumed from what the last one saved, then left to finish: one pour's work for
    // three kills, each resume starting from another one's progress.
    KilledAfterSaves store(0);
    store.open("hash", false);
    for (const int kill_at : {1, counting.saves / 2, counting.saves - 1}) {
        SCOPED_TRACE("killed after save " + std::to_string(kill_at) + " of " +
                     std::to_string(counting.saves));
        store.kill_at(kill_at);
        EXPECT_THROW(
            settled_bed(damper, kStiffness, upright, kGravity, 7, &store, "bed", nullptr, 0.0),
            Killed);
        EXPECT_EQ(store.saves, kill_at);
        ASSERT_TRUE(store.load_progress(Unfinished::bed, "bed"));
        ASSERT_FALSE(store.load_bed("bed"));
    }
    store.kill_at(0);
    bool settled_here = false;
    const dem::ParticleSet resumed =
        settled_bed(damper, kStiffness, upright, kGravity, 7, &store, "bed", &settled_here, 0.0);
    EXPECT_TRUE(settled_here);
    EXPECT_EQ(resumed.positions_m, plain.positions_m);
    EXPECT_EQ(resumed.velocities_m_s, plain.velocities_m_s);
    EXPECT_EQ(resumed.angular_velocities_rad_s, plain.angular_velocities_rad_s);
    EXPECT_EQ(store.saves, counting.saves);  // each resume saved only what was left
    EXPECT_FALSE(store.load_progress(Unfinished::bed, "bed"));
}

TEST(SettledBed, ADamagedOrForeignSettlingProgressIsRefusedNamingIt) {
    const auto config = poured_config();
    const DamperSpec& damper = config.campaign.dampers.front();
    const Eigen::Matrix3d upright = Eigen::Matrix3d::Identity();
    KilledAfterSaves killed(2);
    killed.open("hash", false);
    EXPECT_THROW(
        settled_bed(damper, kStiffness, upright, kGravity, 7, &killed, "bed", nullptr, 0.0),
        Killed);
    const std::string progress = *killed.load_progress(Unfinished::bed, "bed");

    const auto refused = [&](const std::string& text, std::uint64_t seed, const char* why) {
        MemoryCheckpointStore store;
        store.open("hash", false);
        store.save_progress(Unfinished::bed, "bed", text);
        try {
            (void)settled_bed(damper, kStiffness, upright, kGravity, seed, &store, "bed", nullptr,
                              0.0);
            ADD_FAILURE() << why << ": resumed";
        } catch (const CheckpointError& e) {
            EXPECT_EQ(e.file(), store.progress_name(Unfinished::bed, "bed")) << why;
        }
    };
    refused(progress.substr(0, progress.size() / 2), 7, "cut short");
    std::string changed = progress;
    changed[changed.size() / 2] ^= 0x01;
    refused(changed, 7, "a changed byte");
    refused(progress, 8, "another seed's bed");
}

}  // namespace
}  // namespace sb::bench

// The file checkpoint store: what it refuses before a run starts, and what it cleans up.
#include "bench/checkpoint_store.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "bench/sweep_checkpoint.hpp"
#include "config/errors.hpp"
#include "core/text_file.hpp"

namespace sb::bench {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("store-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir / "checkpoints");
    return dir;
}

std::string checkpoint_text(const std::string& hash) {
    SweepCheckpoint c;
    c.config_hash = hash;
    c.state.q = Eigen::VectorXd::Ones(2);
    c.state.q_dot = Eigen::VectorXd::Zero(2);
    return serialize_checkpoint(c);
}

void write(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

constexpr const char* kHash = "00000000000000aa";

TEST(FileCheckpointStore, OpenRefusesDamagedAndForeignCheckpointsNamingEveryFile) {
    const fs::path dir = fresh_dir("damaged");
    const std::string good = checkpoint_text(kHash);
    write(dir / "checkpoints" / "a_good.txt", good);
    write(dir / "checkpoints" / "b_truncated.txt", good.substr(0, good.size() / 2));
    std::string corrupted = good;
    corrupted[good.find("q 2") + 2] = '3';  // one byte
    write(dir / "checkpoints" / "c_corrupted.txt", corrupted);
    write(dir / "checkpoints" / "d_foreign.txt", checkpoint_text("00000000000000bb"));

    FileCheckpointStore store(dir);
    try {
        store.open(kHash, false);
        FAIL() << "damaged checkpoints were accepted";
    } catch (const config::ConfigException& e) {
        ASSERT_EQ(e.errors().size(), 3u) << e.what();
        const auto& truncated = e.errors()[0];
        EXPECT_EQ(truncated.file, (dir / "checkpoints" / "b_truncated.txt").string());
        EXPECT_NE(truncated.constraint.find("truncated"), std::string::npos) << e.what();
        const auto& corrupt = e.errors()[1];
        EXPECT_EQ(corrupt.file, (dir / "checkpoints" / "c_corrupted.txt").string());
        EXPECT_NE(corrupt.constraint.find("corrupted"), std::string::npos) << e.what();
        for (const auto& damaged : {truncated, corrupt}) {
            // The way out: that file, or all of them.
            EXPECT_NE(damaged.meaning.find("delete " + damaged.file), std::string::npos);
            EXPECT_NE(damaged.meaning.find("--restart"), std::string::npos);
        }
        const auto& foreign = e.errors()[2];
        EXPECT_EQ(foreign.file, (dir / "checkpoints" / "d_foreign.txt").string());
        EXPECT_NE(foreign.value.find("00000000000000bb"), std::string::npos);
        EXPECT_NE(foreign.constraint.find(kHash), std::string::npos);
    }
    // Nothing was removed or changed.
    EXPECT_EQ(read_text_file(dir / "checkpoints" / "a_good.txt"), good);
    EXPECT_EQ(read_text_file(dir / "checkpoints" / "c_corrupted.txt"), corrupted);

    // --restart discards them all, and the store opens.
    store.open(kHash, true);
    EXPECT_FALSE(store.load_checkpoint("b_truncated").has_value());
}

TEST(FileCheckpointStore, OpenRemovesTheHalfWrittenFilesOfAKilledRunAndKeepsTheRest) {
    const fs::path dir = fresh_dir("partial");
    const std::string good = checkpoint_text(kHash);
    write(dir / "checkpoints" / "s.txt", good);
    write(dir / "checkpoints" / "s.txt.partial", good.substr(0, 10));
    fs::create_directories(dir / "series");
    write(dir / "series" / "s_0.csv.partial", "time_s,");
    write(dir / "series" / "s_0.csv", "time_s\n");
    FileCheckpointStore store(dir);
    store.open(kHash, false);
    EXPECT_FALSE(fs::exists(dir / "checkpoints" / "s.txt.partial"));
    EXPECT_FALSE(fs::exists(dir / "series" / "s_0.csv.partial"));
    EXPECT_TRUE(fs::exists(dir / "series" / "s_0.csv"));
    EXPECT_EQ(store.load_checkpoint("s"), good);
}

TEST(FileCheckpointStore, AFolderThatCannotHoldCheckpointsIsRefusedBeforeAnythingRuns) {
    const fs::path dir = fresh_dir("unwritable");
    // A file where the recording directory should be: no checkpoint can go below it, even for
    // root (who is not stopped by permissions).
    const fs::path blocked = dir / "file";
    write(blocked, "x");
    FileCheckpointStore store(blocked / "out");
    try {
        store.open(kHash, false);
        FAIL() << "opened";
    } catch (const FileWriteError& e) {
        EXPECT_EQ(e.file(), blocked / "out" / "checkpoints");
        EXPECT_NE(std::string(e.what()).find("cannot be written"), std::string::npos);
        EXPECT_FALSE(e.out_of_space());
    }
}

TEST(FileCheckpointStore, OpeningAFreshDirectoryLeavesNoEmptyFolderTheFirstSaveMakesIt) {
    // A characterisation keeps results and beds, never sweep checkpoints: the folder the
    // write test needed is not left behind.
    const fs::path dir = fs::temp_directory_path() / ("store-fresh-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    FileCheckpointStore store(dir);
    store.open(kHash, false);
    EXPECT_TRUE(fs::is_directory(dir));
    EXPECT_FALSE(fs::exists(dir / "checkpoints"));
    const std::string text = checkpoint_text(kHash);
    store.save_checkpoint("s", text);
    EXPECT_EQ(read_text_file(dir / "checkpoints" / "s.txt"), text);
    // a folder that was there before is kept, empty or not
    const fs::path other = fresh_dir("kept");
    FileCheckpointStore kept(other);
    kept.open(kHash, false);
    EXPECT_TRUE(fs::is_directory(other / "checkpoints"));
    fs::remove_all(dir);
    fs::remove_all(other);
}

TEST(FileCheckpointStore, NamesACheckpointByItsFile) {
    FileCheckpointStore store("out");
    EXPECT_EQ(store.checkpoint_name("H-0_2g"),
              (fs::path("out") / "checkpoints" / "H-0_2g.txt").string());
    MemoryCheckpointStore memory;
    EXPECT_EQ(memory.checkpoint_name("H-0_2g"), "H-0_2g");
}

}  // namespace
}  // namespace sb::bench

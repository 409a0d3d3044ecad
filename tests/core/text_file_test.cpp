// Whole text files: a write that fails names its file and its cause and leaves the old file.
#include "core/text_file.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <string>

namespace sb {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("text-file-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(WriteFileAtomically, AFileInAMissingFolderIsNamedWithTheReason) {
    const fs::path file = fresh_dir("missing") / "no-such-folder" / "a.txt";
    try {
        write_file_atomically(file, "text");
        FAIL() << "written";
    } catch (const FileWriteError& e) {
        EXPECT_EQ(e.file(), file);
        EXPECT_EQ(e.reason(), std::errc::no_such_file_or_directory);
        EXPECT_EQ(std::string(e.what()),
                  file.string() + ": cannot be written (" +
                      std::make_error_code(std::errc::no_such_file_or_directory).message() + ")");
    }
}

TEST(WriteFileAtomically, AFailedRenameLeavesTheOldContentAndNoPartialFile) {
    const fs::path dir = fresh_dir("rename");
    // A folder where the file should go: the temporary file is written, the rename fails.
    const fs::path target = dir / "a.txt";
    fs::create_directories(target / "inside");
    EXPECT_THROW(write_file_atomically(target, "new"), FileWriteError);
    EXPECT_TRUE(fs::is_directory(target / "inside"));
    EXPECT_FALSE(fs::exists(dir / "a.txt.partial"));
}

TEST(WriteFileAtomically, ReplacesTheWholeFile) {
    const fs::path file = fresh_dir("replace") / "a.txt";
    write_file_atomically(file, "a longer first text");
    write_file_atomically(file, "short");
    EXPECT_EQ(read_text_file(file), "short");
    EXPECT_FALSE(fs::exists(file.string() + ".partial"));
}

TEST(FileWriteError, TellsAFullDiskFromOtherCauses) {
    EXPECT_TRUE(
        FileWriteError("f", std::make_error_code(std::errc::no_space_on_device)).out_of_space());
    EXPECT_TRUE(FileWriteError("f", {EDQUOT, std::generic_category()}).out_of_space());
    EXPECT_FALSE(
        FileWriteError("f", std::make_error_code(std::errc::read_only_file_system)).out_of_space());
}

TEST(CreateDirectoriesForWriting, AFileInThePathIsNamedAsTheFolderThatCannotBeMade) {
    const fs::path dir = fresh_dir("blocked");
    { std::ofstream(dir / "file") << "x"; }
    try {
        create_directories_for_writing(dir / "file" / "sub");
        FAIL() << "created";
    } catch (const FileWriteError& e) {
        EXPECT_EQ(e.file(), dir / "file" / "sub");
    }
}

}  // namespace
}  // namespace sb

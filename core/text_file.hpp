// Whole text files: read at once, written so that an interruption never leaves half a file.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace sb {

/// A file or folder that cannot be written: no space left, a read-only file system, no
/// permission. Not bad input: what was written before is intact, and the same call succeeds
/// once the cause is gone. what() is `FILE: cannot be written (REASON)`.
class FileWriteError : public std::runtime_error {
  public:
    FileWriteError(std::filesystem::path file, std::error_code reason);
    [[nodiscard]] const std::filesystem::path& file() const noexcept { return file_; }
    [[nodiscard]] const std::error_code& reason() const noexcept { return reason_; }
    /// No space left on the device (or over quota): freeing space is the way out.
    [[nodiscard]] bool out_of_space() const noexcept;
    /// What to do about it, from the reason: "free space", "raise the file-size limit
    /// (ulimit -f)", "make it writable", else "remove the cause".
    [[nodiscard]] std::string remedy() const;

  private:
    std::filesystem::path file_;
    std::error_code reason_;
};

/// The whole content of a file; throws std::runtime_error naming the file when it cannot be
/// read.
std::string read_text_file(const std::filesystem::path& file);

/// Writes `text` to `file` through a temporary file (`FILE.partial`) and a rename, so an
/// interruption leaves either the old or the new file, never half of one. Throws
/// FileWriteError naming `file` when it cannot be written; the temporary file is removed and
/// the old file, if any, is left as it was.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

/// Creates `directory` and its parents if missing; FileWriteError naming it otherwise.
void create_directories_for_writing(const std::filesystem::path& directory);

}  // namespace sb

// Whole text files.
#include "core/text_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>

namespace sb {

FileWriteError::FileWriteError(std::filesystem::path file, std::error_code reason)
    : std::runtime_error(file.string() + ": cannot be written (" + reason.message() + ")"),
      file_(std::move(file)),
      reason_(reason) {}

bool FileWriteError::out_of_space() const noexcept {
    return reason_ == std::errc::no_space_on_device || reason_.value() == EDQUOT;
}

std::string FileWriteError::remedy() const {
    if (out_of_space()) return "free space";
    if (reason_ == std::errc::file_too_large) return "raise the file-size limit (ulimit -f)";
    if (reason_ == std::errc::permission_denied || reason_ == std::errc::read_only_file_system ||
        reason_ == std::errc::operation_not_permitted) {
        return "make it writable";
    }
    return "remove the cause";
}

std::string read_text_file(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        throw std::runtime_error(file.string() + ": cannot be read");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

namespace {

std::error_code last_error() { return {errno, std::generic_category()}; }

/// Writes all of `text` to a new `path`; the error of the first call that fails otherwise.
/// POSIX calls rather than a stream: a stream reports a full disk as a bare failure bit.
std::error_code write_whole(const std::string& path, const std::string& text) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return last_error();
    std::error_code error;
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            error = last_error();
            break;
        }
        done += static_cast<std::size_t>(n);
    }
    // Some file systems (NFS) report a failed write only when the file is closed.
    if (::close(fd) != 0 && !error) error = last_error();
    return error;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& file, const std::string& text) {
    const std::string temporary = file.string() + ".partial";
    if (const std::error_code error = write_whole(temporary, text)) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw FileWriteError(file, error);
    }
    std::error_code error;
    std::filesystem::rename(temporary, file, error);
    if (error) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw FileWriteError(file, error);
    }
}

void create_directories_for_writing(const std::filesystem::path& directory) {
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error) throw FileWriteError(directory, error);
}

}  // namespace sb

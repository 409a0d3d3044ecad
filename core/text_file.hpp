// Whole text files: read at once, written so that an interruption never leaves half a file.
#pragma once

#include <filesystem>
#include <string>

namespace sb {

/// The whole content of a file; throws std::runtime_error naming the file when it cannot be
/// read.
std::string read_text_file(const std::filesystem::path& file);

/// Writes `text` to `file` through a temporary file and a rename, so an interruption leaves
/// either the old or the new file, never half of one. Throws std::runtime_error naming the
/// file when it cannot be written.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

}  // namespace sb

// The exception every reader of this module throws for a bad file: file, line, column, message.
#pragma once

#include <stdexcept>
#include <string>

namespace sb::identification {

/// A file that cannot be read or does not follow its documented format (docs/identification.md).
/// what() is `file:line:col: message`; line and column are 1-based, 0 when they do not apply
/// (a missing file, a missing row).
class FileError : public std::runtime_error {
  public:
    FileError(std::string file, int line, int column, std::string message);

    /// Path of the offending file as given to the reader.
    const std::string& file() const noexcept { return file_; }
    /// 1-based line, 0 if the error is about the whole file.
    int line() const noexcept { return line_; }
    /// 1-based column (characters), 0 if the error is about a whole line or file.
    int column() const noexcept { return column_; }
    /// The message without the location prefix.
    const std::string& message() const noexcept { return message_; }

  private:
    std::string file_;
    int line_;
    int column_;
    std::string message_;
};

}  // namespace sb::identification

// Whole text files.
#include "core/text_file.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace sb {

std::string read_text_file(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        throw std::runtime_error(file.string() + ": cannot be read");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_file_atomically(const std::filesystem::path& file, const std::string& text) {
    const auto temporary = file.string() + ".partial";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out) {
            throw std::runtime_error(temporary + ": cannot be written");
        }
    }
    std::error_code ec;
    std::filesystem::rename(temporary, file, ec);
    if (ec) {
        throw std::runtime_error(file.string() + ": cannot be written (" + ec.message() + ")");
    }
}

}  // namespace sb

// Fortran-style number parsing for UFF readers (research note §4.5, pyuff issues #32, #64).
#include "identification/uff58_number.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

namespace sb::identification::detail {

std::string_view trim(std::string_view s) {
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string_view::npos) return {};
    const auto e = s.find_last_not_of(" \t\r\n");
    return s.substr(b, e - b + 1);
}

bool parse_fortran_double(std::string_view text, double& out) {
    const auto t = trim(text);
    if (t.empty()) return false;
    std::string s(t);
    bool has_exponent = false;
    for (auto& c : s) {
        if (c == 'D' || c == 'd') c = 'E';
        if (c == 'E' || c == 'e') has_exponent = true;
    }
    if (!has_exponent) {
        // "1.0-100": a sign after a digit or point starts the exponent.
        for (std::size_t i = 1; i < s.size(); ++i) {
            if ((s[i] == '+' || s[i] == '-') &&
                (std::isdigit(static_cast<unsigned char>(s[i - 1])) || s[i - 1] == '.')) {
                s.insert(i, 1, 'E');
                break;
            }
        }
    }
    const char* first = s.data();
    const char* last = s.data() + s.size();
    if (*first == '+') ++first;  // from_chars rejects a leading '+'
    const auto [ptr, ec] = std::from_chars(first, last, out);
    // from_chars also reads "nan" and "inf", which no UFF writer means as data.
    return ec == std::errc() && ptr == last && std::isfinite(out);
}

bool parse_int(std::string_view text, int& out) {
    auto t = trim(text);
    if (t.empty()) return false;
    if (t.front() == '+') t.remove_prefix(1);
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
    return ec == std::errc() && ptr == t.data() + t.size();
}

std::vector<std::string_view> split_blanks(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const std::size_t b = i;
        while (i < line.size() && !(line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        if (i > b) out.push_back(line.substr(b, i - b));
    }
    return out;
}

std::string_view field(std::string_view line, std::size_t begin, std::size_t width) {
    if (begin >= line.size()) return {};
    return line.substr(begin, width);
}

}  // namespace sb::identification::detail

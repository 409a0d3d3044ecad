// Parsing of Fortran-style numbers as they appear in UFF files.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace sb::identification::detail {

/// Parses a whole field as a double, accepting `E`, `e`, `D`, `d` exponents and an exponent
/// without a letter (`1.0-100`); blanks around are ignored. False if anything else remains
/// or the value is not finite (nan, inf).
bool parse_fortran_double(std::string_view field, double& out);

/// Parses a whole field as an int (blanks ignored). False on anything else.
bool parse_int(std::string_view field, int& out);

/// Splits on blanks.
std::vector<std::string_view> split_blanks(std::string_view line);

/// The field [begin, begin + width) of a line, clipped to the line.
std::string_view field(std::string_view line, std::size_t begin, std::size_t width);

/// Trims blanks (space, tab, CR, LF).
std::string_view trim(std::string_view s);

}  // namespace sb::identification::detail

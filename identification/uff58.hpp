// Universal File Format dataset 58 (ASCII read/write) and 58b (binary read).
#pragma once

#include <array>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include "identification/frf.hpp"

namespace sb::identification {

/// Records 8–11: one axis (research note §4.2).
struct Uff58Axis {
    int data_type = 0;  ///< 0 unknown, 8 displacement, 11 velocity, 12 acceleration,
                        ///< 13 excitation force, 17 time, 18 frequency, ...
    int length_exponent = 0;
    int force_exponent = 0;
    int temperature_exponent = 0;
    std::string label = "NONE";  ///< axis label (at most 20 characters)
    std::string units = "NONE";  ///< units label (at most 20 characters)
};

/// One dataset 58: a function of one abscissa (FRF, time response, ...).
struct Uff58Record {
    /// Records 1–5, at most 80 characters each.
    std::array<std::string, 5> id = {"NONE", "NONE", "NONE", "NONE", "NONE"};
    int function_type = 4;  ///< 1 time response, 4 FRF, 5 transmissibility, ...
    int function_id = 0;
    int version = 0;
    int load_case = 0;
    std::string response_name = "NONE";  ///< at most 10 characters
    int response_node = 0;
    int response_direction = 0;           ///< 0 scalar, ±1..±3 translation, ±4..±6 rotation
    std::string reference_name = "NONE";  ///< at most 10 characters
    int reference_node = 0;
    int reference_direction = 0;
    int ordinate_type = 6;  ///< 2 real single, 4 real double, 5 complex single, 6 complex double
    double z_value = 0.0;
    Uff58Axis abscissa{18, 0, 0, 0, "Frequency", "Hz"};
    Uff58Axis ordinate{12, 1, 0, 0, "Acceleration", "m/s^2"};
    Uff58Axis denominator{13, 0, 1, 0, "Force", "N"};
    Uff58Axis z_axis{};
    std::vector<double> x;                ///< abscissa per point (even spacing expanded)
    std::vector<std::complex<double>> y;  ///< ordinate per point (imag 0 for real data)

    bool is_complex() const noexcept { return ordinate_type == 5 || ordinate_type == 6; }
};

/// How numbers are written.
enum class Uff58Digits {
    /// The nominal layout: E13.5 abscissa, E20.12 ordinates (13 significant digits), even
    /// spacing kept when the abscissa is evenly spaced. What other tools expect.
    nominal,
    /// Every value as %25.16E (17 significant digits: doubles round-trip bit for bit), three
    /// per line, abscissa always explicit (spacing 0), the z value of record 7 as %23.16E.
    /// Lines stay ≤ 80 columns; readers must tokenise on blanks (pyuff and this reader do).
    exact,
};

/// Reads every dataset 58 and 58b of a file, skipping other datasets. Tolerates (note §4.5):
/// CRLF, Fortran `D` exponents and exponents without a letter (`1.0-100`), fields glued
/// together or breaking the nominal widths, rows padded past the number of points, blank or
/// Latin-1 ID lines, a wrong byte count in the 58b header (the count follows from record 7)
/// and stray CR/LF after the binary block. Throws FileError (file:line:col) otherwise, and for
/// a value that is not finite (a binary NaN or infinity) and a path that is not a regular file.
std::vector<Uff58Record> read_uff58(const std::filesystem::path& path);

/// Writes the records as ASCII dataset 58 with their ordinate data type (single-precision
/// types 2/5 keep their type; in nominal digits their values are written E13.5), LF line
/// ends. Every header field is written as it is: a name longer than its field (ID lines 80,
/// entity names 10, axis labels 20 characters) or a line break in one throws
/// std::invalid_argument instead of being cut. Throws sb::FileWriteError (core/text_file.hpp)
/// if the file cannot be written; the file is written whole or not at all.
void write_uff58(const std::filesystem::path& path, const std::vector<Uff58Record>& records,
                 Uff58Digits digits = Uff58Digits::exact);

/// An FRF as a record: function type 4, abscissa frequency, ordinate per form over force.
Uff58Record to_uff58(const Frf& frf, const std::string& description);

/// A record of function type 4 (FRF) or 5 (transmissibility) as an Frf; the form follows the
/// ordinate data type (8 receptance, 11 mobility, otherwise accelerance). Throws
/// std::invalid_argument for real or non-frequency records.
Frf to_frf(const Uff58Record& record);

}  // namespace sb::identification

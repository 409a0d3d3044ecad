// UFF dataset 58/58b reader and 58 writer, record layout of research note §4 (pyuff's spec text).
#include "identification/uff58.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "core/text_file.hpp"
#include "core/units.hpp"
#include "identification/file_error.hpp"
#include "identification/uff58_number.hpp"

namespace sb::identification {

namespace {

using detail::field;
using detail::parse_fortran_double;
using detail::parse_int;
using detail::split_blanks;
using detail::trim;

/// Relative tolerance under which an abscissa counts as evenly spaced when writing.
constexpr double kEvenSpacingTolerance = 1e-12;

/// Walks the file's bytes line by line, keeping line numbers for messages.
class Cursor {
  public:
    Cursor(std::string file, std::string bytes)
        : file_(std::move(file)), bytes_(std::move(bytes)) {}
    bool done() const { return pos_ >= bytes_.size(); }
    int line() const { return line_; }
    std::size_t pos() const { return pos_; }
    std::size_t remaining() const { return bytes_.size() - pos_; }
    /// The next line without its line end; advances past the LF.
    std::string_view next() {
        const std::size_t b = pos_;
        std::size_t e = bytes_.find('\n', b);
        if (e == std::string::npos) e = bytes_.size();
        pos_ = e < bytes_.size() ? e + 1 : e;
        ++line_;
        std::string_view l(bytes_.data() + b, e - b);
        if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
        return l;
    }
    std::string_view bytes(std::size_t count) {
        if (pos_ + count > bytes_.size()) fail(0, "binary block shorter than announced");
        std::string_view v(bytes_.data() + pos_, count);
        pos_ += count;
        return v;
    }
    [[noreturn]] void fail(int column, const std::string& message) const {
        throw FileError(file_, line_, column, message);
    }

  private:
    std::string file_;
    std::string bytes_;
    std::size_t pos_ = 0;
    int line_ = 0;
};

int get_int(Cursor& c, std::string_view line, std::size_t begin, std::size_t width,
            const char* what) {
    int v = 0;
    if (!parse_int(field(line, begin, width), v)) {
        c.fail(static_cast<int>(begin) + 1, std::string("expected an integer for ") + what);
    }
    return v;
}

std::string text(std::string_view s) { return std::string(trim(s)); }

void read_record6(Cursor& c, Uff58Record& r) {
    const auto l = c.next();
    // Fixed columns first: 2(I5,I10),2(1X,10A1,I10,I4).
    int v[8];
    if (parse_int(field(l, 0, 5), v[0]) && parse_int(field(l, 5, 10), v[1]) &&
        parse_int(field(l, 15, 5), v[2]) && parse_int(field(l, 20, 10), v[3]) &&
        parse_int(field(l, 41, 10), v[4]) && parse_int(field(l, 51, 4), v[5]) &&
        parse_int(field(l, 66, 10), v[6]) && parse_int(field(l, 76, 4), v[7])) {
        r.function_type = v[0];
        r.function_id = v[1];
        r.version = v[2];
        r.load_case = v[3];
        r.response_name = text(field(l, 31, 10));
        r.response_node = v[4];
        r.response_direction = v[5];
        r.reference_name = text(field(l, 56, 10));
        r.reference_node = v[6];
        r.reference_direction = v[7];
        return;
    }
    const auto t = split_blanks(l);  // names without blanks: 10 tokens
    if (t.size() != 10) c.fail(1, "record 6: expected 2(I5,I10),2(1X,10A1,I10,I4)");
    r.function_type = get_int(c, t[0], 0, t[0].size(), "the function type");
    r.function_id = get_int(c, t[1], 0, t[1].size(), "the function id");
    r.version = get_int(c, t[2], 0, t[2].size(), "the version");
    r.load_case = get_int(c, t[3], 0, t[3].size(), "the load case");
    r.response_name = std::string(t[4]);
    r.response_node = get_int(c, t[5], 0, t[5].size(), "the response node");
    r.response_direction = get_int(c, t[6], 0, t[6].size(), "the response direction");
    r.reference_name = std::string(t[7]);
    r.reference_node = get_int(c, t[8], 0, t[8].size(), "the reference node");
    r.reference_direction = get_int(c, t[9], 0, t[9].size(), "the reference direction");
}

struct Record7 {
    int type = 0;
    int points = 0;
    int spacing = 0;
    double min = 0.0;
    double inc = 0.0;
};

Record7 read_record7(Cursor& c, Uff58Record& r) {
    const auto l = c.next();
    Record7 s;
    // Fixed columns only when nothing follows them: a wider z value (the exact writer's) would
    // otherwise be cut at column 69 and read short.
    if (!(parse_int(field(l, 0, 10), s.type) && parse_int(field(l, 10, 10), s.points) &&
          parse_int(field(l, 20, 10), s.spacing) && parse_fortran_double(field(l, 30, 13), s.min) &&
          parse_fortran_double(field(l, 43, 13), s.inc) &&
          parse_fortran_double(field(l, 56, 13), r.z_value) && trim(field(l, 69, 80)).empty())) {
        const auto t = split_blanks(l);
        if (t.size() != 6 || !parse_int(t[0], s.type) || !parse_int(t[1], s.points) ||
            !parse_int(t[2], s.spacing) || !parse_fortran_double(t[3], s.min) ||
            !parse_fortran_double(t[4], s.inc) || !parse_fortran_double(t[5], r.z_value)) {
            c.fail(
                1,
                "record 7: expected 3I10,3E13.5 (data type, points, spacing, min, increment, z)");
        }
    }
    if (s.type != 2 && s.type != 4 && s.type != 5 && s.type != 6) {
        c.fail(1, "record 7: ordinate data type " + std::to_string(s.type) +
                      " is not 2, 4, 5 or 6 (real/complex, single/double)");
    }
    if (s.points < 0) c.fail(11, "record 7: negative number of points");
    if (s.spacing != 0 && s.spacing != 1) c.fail(21, "record 7: abscissa spacing must be 0 or 1");
    r.ordinate_type = s.type;
    return s;
}

Uff58Axis read_axis(Cursor& c, int record) {
    const auto l = c.next();
    Uff58Axis a;
    if (parse_int(field(l, 0, 10), a.data_type) && parse_int(field(l, 10, 5), a.length_exponent) &&
        parse_int(field(l, 15, 5), a.force_exponent) &&
        parse_int(field(l, 20, 5), a.temperature_exponent)) {
        a.label = text(field(l, 26, 20));
        a.units = text(field(l, 47, 20));
        return a;
    }
    const auto t = split_blanks(l);
    if (t.size() < 4 || !parse_int(t[0], a.data_type) || !parse_int(t[1], a.length_exponent) ||
        !parse_int(t[2], a.force_exponent) || !parse_int(t[3], a.temperature_exponent)) {
        c.fail(1, "record " + std::to_string(record) + ": expected I10,3I5,2(1X,20A1)");
    }
    a.label = t.size() > 4 ? std::string(t[4]) : "NONE";
    a.units = t.size() > 5 ? std::string(t[5]) : "NONE";
    return a;
}

std::size_t values_per_point(const Uff58Record& r, int spacing) {
    return (r.is_complex() ? 2u : 1u) + (spacing == 0 ? 1u : 0u);
}

/// Fills x and y from the flat value list of record 12. A value that is not finite (a binary
/// NaN or infinity, an even abscissa past the largest double) is refused: no UFF writer means
/// one as data, and it would pass through every estimate unnoticed.
void unpack(Cursor& c, const std::vector<double>& v, const Record7& s, Uff58Record& r) {
    const auto n = static_cast<std::size_t>(s.points);
    const std::size_t vpp = values_per_point(r, s.spacing);
    r.x.resize(n);
    r.y.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double* p = v.data() + i * vpp;
        std::size_t k = 0;
        r.x[i] = s.spacing == 0 ? p[k++] : s.min + static_cast<double>(i) * s.inc;
        const double re = p[k++];
        const double im = r.is_complex() ? p[k] : 0.0;
        r.y[i] = {re, im};
        if (!std::isfinite(r.x[i]) || !std::isfinite(re) || !std::isfinite(im)) {
            c.fail(0, "record 12: point " + std::to_string(i + 1) + " is not a finite number");
        }
    }
}

/// Nominal field widths of one line of record 12 (note §4.3), repeated across the line.
std::vector<std::size_t> widths(const Uff58Record& r, int spacing) {
    const bool dbl = r.ordinate_type == 4 || r.ordinate_type == 6;
    if (!dbl) return {13};
    if (spacing == 1) return {20};
    if (r.is_complex()) return {13, 20, 20};
    return {13, 20};
}

void read_ascii_data(Cursor& c, const Record7& s, Uff58Record& r) {
    const std::size_t expected =
        static_cast<std::size_t>(s.points) * values_per_point(r, s.spacing);
    const auto w = widths(r, s.spacing);
    std::vector<double> v;
    // Record 7's count is not trusted with the allocation: every value takes two bytes of text
    // at least, so the file's remaining size bounds what can really be read.
    v.reserve(std::min(expected, c.remaining() / 2));
    while (true) {
        if (c.done()) c.fail(0, "end of file inside dataset 58 (no closing -1)");
        const auto l = c.next();
        if (trim(l) == "-1") break;
        // Blank-separated first: it survives writers that ignore the nominal widths. Only a
        // line whose tokens do not parse (fields glued together) is cut at the nominal widths.
        const auto tokens = split_blanks(l);
        std::vector<double> line_values;
        bool ok = true;
        for (auto t : tokens) {
            double d = 0.0;
            if (!parse_fortran_double(t, d)) {
                ok = false;
                break;
            }
            line_values.push_back(d);
        }
        if (!ok) {
            line_values.clear();
            std::size_t col = 0;
            for (std::size_t k = 0; col < l.size(); ++k) {
                const std::size_t width = w[k % w.size()];
                const auto f = field(l, col, width);
                if (!trim(f).empty()) {
                    double d = 0.0;
                    if (!parse_fortran_double(f, d)) {
                        c.fail(static_cast<int>(col) + 1,
                               "record 12: not a number: '" + std::string(trim(f)) + "'");
                    }
                    line_values.push_back(d);
                }
                col += width;
            }
        }
        v.insert(v.end(), line_values.begin(), line_values.end());
    }
    if (v.size() < expected) {
        c.fail(0, "record 12: " + std::to_string(v.size()) + " values for " +
                      std::to_string(s.points) + " points (" + std::to_string(expected) +
                      " values expected)");
    }
    v.resize(expected);  // rows padded past num_pts (pyuff #22)
    unpack(c, v, s, r);
}

template <typename T>
T from_bytes(const char* p, bool swap) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, p, sizeof(T));
    if (swap) {
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    }
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
}

Uff58Record read_dataset(Cursor& c, bool binary, std::string_view id_line) {
    Uff58Record r;
    bool swap = false;
    if (binary) {
        // "58b" (I6,A1 as written) or "58 b", then byte order, float format, lines, bytes.
        const auto t = split_blanks(id_line);
        const std::size_t first = t.size() > 1 && t[0] == "58" ? 2 : 1;
        int order = 0, format = 0;
        if (t.size() < first + 2 || !parse_int(t[first], order) ||
            !parse_int(t[first + 1], format)) {
            c.fail(1, "58b header: expected byte order and floating-point format");
        }
        if (order != 1 && order != 2) c.fail(1, "58b: byte order must be 1 (little) or 2 (big)");
        if (format != 2) c.fail(1, "58b: only IEEE 754 floating point (format 2) is supported");
        swap = (order == 1) != (std::endian::native == std::endian::little);
    }
    for (auto& id : r.id) {
        id = text(c.next());
        if (id.empty()) id = "NONE";
    }
    read_record6(c, r);
    const Record7 s = read_record7(c, r);
    r.abscissa = read_axis(c, 8);
    r.ordinate = read_axis(c, 9);
    r.denominator = read_axis(c, 10);
    r.z_axis = read_axis(c, 11);
    if (!binary) {
        read_ascii_data(c, s, r);
        return r;
    }
    // The byte count follows from record 7; the header's n_bytes is not trusted (pyuff #91).
    const bool dbl = r.ordinate_type == 4 || r.ordinate_type == 6;
    const std::size_t size = dbl ? 8 : 4;
    const std::size_t count = static_cast<std::size_t>(s.points) * values_per_point(r, s.spacing);
    const auto block = c.bytes(count * size);
    std::vector<double> v(count);
    for (std::size_t i = 0; i < count; ++i) {
        v[i] = dbl ? from_bytes<double>(block.data() + i * size, swap)
                   : static_cast<double>(from_bytes<float>(block.data() + i * size, swap));
    }
    unpack(c, v, s, r);
    // Tolerate stray CR/LF (or the rest of a line) before the closing -1 (pyuff fix_58b).
    while (!c.done()) {
        const auto l = c.next();
        if (trim(l) == "-1") return r;
        if (!trim(l).empty()) c.fail(1, "58b: expected the closing -1 after the binary block");
    }
    c.fail(0, "end of file inside dataset 58b (no closing -1)");
}

/// Text of a fixed-width field: empty becomes NONE; longer than the field is an error rather
/// than a silent cut (a reader would see another name).
std::string fixed_text(const std::string& value, std::size_t width, std::size_t record,
                       const char* what) {
    if (value.size() > width) {
        throw std::invalid_argument("write_uff58: record " + std::to_string(record) + " " + what +
                                    " '" + value + "' is longer than " + std::to_string(width) +
                                    " characters");
    }
    if (value.find_first_of("\r\n") != std::string::npos) {
        throw std::invalid_argument("write_uff58: record " + std::to_string(record) + " " + what +
                                    " contains a line break");
    }
    return value.empty() ? "NONE" : value;
}

void put_axis(std::string& out, const Uff58Axis& a, std::size_t record) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%10d%5d%5d%5d %-20s %-20s\n", a.data_type, a.length_exponent,
                  a.force_exponent, a.temperature_exponent,
                  fixed_text(a.label, 20, record, "axis label").c_str(),
                  fixed_text(a.units, 20, record, "units label").c_str());
    out += buf;
}

}  // namespace

std::vector<Uff58Record> read_uff58(const std::filesystem::path& path) {
    std::error_code error;
    if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error)) {
        // A device or a pipe could be read forever (/dev/zero).
        throw FileError(path.string(), 0, 0, "not a regular file");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FileError(path.string(), 0, 0, "cannot open the file");
    std::ostringstream ss;
    ss << in.rdbuf();
    Cursor c(path.string(), ss.str());
    std::vector<Uff58Record> records;
    while (!c.done()) {
        const auto l = c.next();
        if (trim(l).empty()) continue;
        if (trim(l) != "-1") c.fail(1, "expected '    -1' opening a dataset");
        if (c.done()) break;
        const auto id = c.next();
        const auto t = split_blanks(id);
        if (!t.empty() && (t[0] == "58b" || (t[0] == "58" && t.size() > 1 && t[1] == "b"))) {
            records.push_back(read_dataset(c, true, id));
        } else if (!t.empty() && t[0] == "58") {
            records.push_back(read_dataset(c, false, id));
        } else {
            // Another dataset type (151, 164, 2411, ...): skip to its closing -1.
            while (!c.done() && trim(c.next()) != "-1") {
            }
        }
    }
    return records;
}

void write_uff58(const std::filesystem::path& path, const std::vector<Uff58Record>& records,
                 Uff58Digits digits) {
    std::string out;
    char buf[256];
    for (const auto& r : records) {
        if (r.x.size() != r.y.size())
            throw std::invalid_argument("write_uff58: x and y sizes differ");
        if (r.ordinate_type != 2 && r.ordinate_type != 4 && r.ordinate_type != 5 &&
            r.ordinate_type != 6) {
            throw std::invalid_argument("write_uff58: ordinate data type " +
                                        std::to_string(r.ordinate_type) + " is not 2, 4, 5 or 6");
        }
        const std::size_t n = r.x.size();
        const bool single = r.ordinate_type == 2 || r.ordinate_type == 5;
        bool even = digits == Uff58Digits::nominal && n > 1;
        const double inc = n > 1 ? (r.x[n - 1] - r.x[0]) / static_cast<double>(n - 1) : 0.0;
        for (std::size_t i = 0; even && i < n; ++i) {
            even = std::abs(r.x[i] - (r.x[0] + static_cast<double>(i) * inc)) <=
                   kEvenSpacingTolerance * std::abs(r.x[n - 1]);
        }
        out += "    -1\n    58\n";
        for (const auto& id : r.id) out += fixed_text(id, 80, 1, "ID line") + "\n";
        std::snprintf(buf, sizeof buf, "%5d%10d%5d%10d %-10s%10d%4d %-10s%10d%4d\n",
                      r.function_type, r.function_id, r.version, r.load_case,
                      fixed_text(r.response_name, 10, 6, "response name").c_str(), r.response_node,
                      r.response_direction,
                      fixed_text(r.reference_name, 10, 6, "reference name").c_str(),
                      r.reference_node, r.reference_direction);
        out += buf;
        if (digits == Uff58Digits::exact) {
            // z with 17 significant digits: 30 + 13 + 13 + 24 = 80 columns.
            std::snprintf(buf, sizeof buf, "%10d%10zu%10d%13.5E%13.5E %23.16E\n", r.ordinate_type,
                          n, 0, 0.0, 0.0, r.z_value);
        } else {
            std::snprintf(buf, sizeof buf, "%10d%10zu%10d%13.5E%13.5E%13.5E\n", r.ordinate_type, n,
                          even ? 1 : 0, even ? r.x[0] : 0.0, even ? inc : 0.0, r.z_value);
        }
        out += buf;
        put_axis(out, r.abscissa, 8);
        put_axis(out, r.ordinate, 9);
        put_axis(out, r.denominator, 10);
        put_axis(out, r.z_axis, 11);
        // Flat value list of record 12: x (uneven only), re, im (complex only) per point.
        std::vector<double> v;
        for (std::size_t i = 0; i < n; ++i) {
            if (!even) v.push_back(r.x[i]);
            v.push_back(r.y[i].real());
            if (r.is_complex()) v.push_back(r.y[i].imag());
        }
        if (digits == Uff58Digits::exact) {
            for (std::size_t i = 0; i < v.size(); ++i) {  // three %25.16E per line
                std::snprintf(buf, sizeof buf, "%25.16E", v[i]);
                out += buf;
                if (i % 3 == 2 || i + 1 == v.size()) out += "\n";
            }
        } else if (single) {
            for (std::size_t i = 0; i < v.size(); ++i) {  // cases 1-4: 6E13.5
                std::snprintf(buf, sizeof buf, "%13.5E", v[i]);
                out += buf;
                if (i % 6 == 5 || i + 1 == v.size()) out += "\n";
            }
        } else if (even) {
            for (std::size_t i = 0; i < v.size(); ++i) {  // cases 5, 7: 4E20.12
                std::snprintf(buf, sizeof buf, "%20.12E", v[i]);
                out += buf;
                if (i % 4 == 3 || i + 1 == v.size()) out += "\n";
            }
        } else {
            for (std::size_t i = 0; i < n; ++i) {
                if (r.is_complex()) {  // case 8: E13.5,2E20.12 one point per line
                    std::snprintf(buf, sizeof buf, "%13.5E%20.12E%20.12E\n", r.x[i], r.y[i].real(),
                                  r.y[i].imag());
                } else {  // case 6: 2(E13.5,E20.12)
                    std::snprintf(buf, sizeof buf, "%13.5E%20.12E", r.x[i], r.y[i].real());
                }
                out += buf;
                if (!r.is_complex() && (i % 2 == 1 || i + 1 == n)) out += "\n";
            }
        }
        out += "    -1\n";
    }
    write_file_atomically(path, out);
}

Uff58Record to_uff58(const Frf& frf, const std::string& description) {
    check_frf(frf);
    Uff58Record r;
    r.id[0] = description.empty() ? "NONE" : description;
    r.function_type = 4;
    r.ordinate_type = 6;
    switch (frf.form) {
        case FrfForm::receptance:
            r.ordinate = {8, 1, 0, 0, "Displacement", "m"};
            break;
        case FrfForm::mobility:
            r.ordinate = {11, 1, 0, 0, "Velocity", "m/s"};
            break;
        case FrfForm::accelerance:
            r.ordinate = {12, 1, 0, 0, "Acceleration", "m/s^2"};
            break;
    }
    r.x = frf.frequency_hz;
    r.y = frf.value;
    return r;
}

Frf to_frf(const Uff58Record& r) {
    if (r.function_type != 4 && r.function_type != 5) {
        throw std::invalid_argument("to_frf: function type " + std::to_string(r.function_type) +
                                    " is not an FRF (4) or transmissibility (5)");
    }
    if (!r.is_complex()) throw std::invalid_argument("to_frf: real ordinate");
    Frf frf{r.x, r.y, FrfForm::accelerance};
    if (r.ordinate.data_type == 8) frf.form = FrfForm::receptance;
    if (r.ordinate.data_type == 11) frf.form = FrfForm::mobility;
    check_frf(frf);
    return frf;
}

}  // namespace sb::identification

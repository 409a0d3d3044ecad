// The exact text form checkpoints are written in: one record per line, a key word first,
// every number a hexadecimal float (read back bitwise), sealed by a checksum line. Shared by
// the sweep checkpoints, a pour's progress and a characterisation run's progress.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>

#include "bench/sweep_checkpoint.hpp"
#include "dem/solver.hpp"
#include "dem/solver_state.hpp"

namespace sb::bench::checkpoint {

/// Sizes no checkpoint reaches: a count past them is damage, not a reason to allocate.
inline constexpr long long kMaxVectorSize = 100000;
inline constexpr long long kMaxCount = 100000000;
/// The last line: the 64-bit FNV-1a of every byte before it. A file cut short, or with a byte
/// changed on disk, fails it; the rename that writes a checkpoint never leaves half a file, but
/// a disk or a copy can.
inline constexpr std::string_view kChecksumKey = "checksum fnv1a64 ";

class Writer {
  public:
    Writer() { out_ << std::hexfloat; }
    Writer& key(const char* k) {
        out_ << k;
        return *this;
    }
    Writer& num(double v) {
        out_ << ' ' << v;
        return *this;
    }
    Writer& integer(long long v) {
        out_ << ' ' << v;
        return *this;
    }
    Writer& text(const std::string& t) {
        out_ << '\t' << t;
        return *this;
    }
    void end() { out_ << '\n'; }
    std::string str() const { return out_.str(); }

  private:
    std::ostringstream out_;
};

class Reader {
  public:
    Reader(const std::string& text, std::string file) : in_(text), file_(std::move(file)) {}

    /// Next line, which must start with the word `key`; its remaining words follow.
    std::istringstream line(const std::string& key) {
        std::string l;
        if (!std::getline(in_, l)) {
            fail("ends early, expected '" + key + "'");
        }
        ++line_;
        // The whole word: "p" (a particle) must not take a "pairs" line.
        if (l.rfind(key, 0) != 0 ||
            (l.size() > key.size() && l[key.size()] != ' ' && l[key.size()] != '\t')) {
            fail("expected '" + key + "'");
        }
        current_ = l;
        return std::istringstream(l.substr(key.size()));
    }
    /// The text after the first tab of the current line (empty when there is none).
    std::string text() const {
        const auto tab = current_.find('\t');
        return tab == std::string::npos ? std::string() : current_.substr(tab + 1);
    }
    /// Nothing may follow the values a line announces: more would be read as nothing.
    void end(std::istringstream& words) {
        std::string w;
        if (words >> w) fail("'" + w + "' follows the values of '" + first_word() + "'");
    }
    double num(std::istringstream& words) {
        std::string w;
        if (!(words >> w)) {
            fail("a number is missing");
        }
        char* end = nullptr;
        const double v = std::strtod(w.c_str(), &end);
        if (end == w.c_str() || *end != '\0') {
            fail("'" + w + "' is not a number");
        }
        return v;
    }
    long long integer(std::istringstream& words) {
        long long v = 0;
        if (!(words >> v)) {
            fail("a whole number is missing");
        }
        return v;
    }
    [[noreturn]] void fail(const std::string& message) const {
        throw CheckpointError(file_, line_, message);
    }
    const std::string& current() const { return current_; }
    /// Whatever follows the line just read.
    /// Whether the next line starts with the word `key` (nothing is read).
    bool next_is(const std::string& key) {
        const auto at = in_.tellg();
        std::string l;
        const bool found =
            static_cast<bool>(std::getline(in_, l)) && l.rfind(key, 0) == 0 &&
            (l.size() == key.size() || l[key.size()] == ' ' || l[key.size()] == '\t');
        in_.clear();
        in_.seekg(at);
        return found;
    }
    bool at_end() {
        std::string rest;
        return !std::getline(in_, rest);
    }

  private:
    std::string first_word() const { return current_.substr(0, current_.find_first_of(" \t")); }

    std::istringstream in_;
    std::string file_;
    std::string current_;
    int line_ = 0;
};

void write_vector(Writer& w, const char* key, const Eigen::VectorXd& v);
Eigen::VectorXd read_vector(Reader& r, const char* key);
void write_vector3(Writer& w, const Eigen::Vector3d& v);
Eigen::Vector3d read_vector3(Reader& r, std::istringstream& words);
/// A `key` line holding a count within kMaxCount.
long long read_count(Reader& r, const char* key);
/// A DEM solver's state whole: enclosure pose, particles, tangential springs, lock, clock.
void write_dem_state(Writer& w, const dem::SolverState& s);
dem::SolverState read_dem_state(Reader& r);
/// An energy ledger whole (cumulative works, state energies, the layers' sums).
void write_ledger(Writer& w, const dem::EnergyLedger& e);
dem::EnergyLedger read_ledger(Reader& r);

/// The checksum first: a damaged file is reported as such, not as whatever its damage makes
/// the first unreadable line look like. `magic` is the whole first line this build reads,
/// `magic_prefix` the part every format of the kind starts with.
void check_sealed(const std::string& text, const std::string& file, std::string_view magic,
                  std::string_view magic_prefix);

}  // namespace sb::bench::checkpoint

// The describing function: characterization.csv and its interpolation.
#include "bench/describing_function.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "bench/campaign_config.hpp"
#include "bench/resolved_config.hpp"
#include "config/dotted_path.hpp"
#include "config/write.hpp"
#include "core/units.hpp"
#include "identification/csv_table.hpp"
#include "identification/file_error.hpp"

namespace sb::bench {
namespace {

namespace id = identification;
using id::FileError;
using id::detail::exact_text;

constexpr const char* kFormatLine = "# shakerbench characterization 1";

/// The columns, in the order written; every one is required on reading.
const char* const kColumns[] = {"damper",
                                "arrangement",
                                "level_g",
                                "acceleration_m_s2",
                                "frequency_hz",
                                "bed_mass_kg",
                                "rotation_x_rad_m",
                                "rotation_y_rad_m",
                                "rotation_z_rad_m",
                                "seeds",
                                "apparent_mass_re_kg",
                                "apparent_mass_re_std_kg",
                                "apparent_mass_im_kg",
                                "apparent_mass_im_std_kg",
                                "power_w",
                                "power_std_w",
                                "h2",
                                "h3",
                                "kinetic_j",
                                "kinetic_std_j",
                                "periods",
                                "settled"};

/// Two grid values are the same level or frequency when they agree to this relative
/// precision (the file holds 17 significant digits; a hand-edited file may round).
constexpr double kSameValue = 1e-9;

bool same(double a, double b) {
    return std::abs(a - b) <= kSameValue * std::max(std::abs(a), std::abs(b));
}

/// Distinct values, ascending, merging those within kSameValue.
std::vector<double> distinct(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    std::vector<double> out;
    for (double v : values) {
        if (out.empty() || !same(out.back(), v)) out.push_back(v);
    }
    return out;
}

std::size_t index_of(const std::vector<double>& grid, double v) {
    for (std::size_t i = 0; i < grid.size(); ++i) {
        if (same(grid[i], v)) return i;
    }
    return grid.size();
}

/// Interval of `at` in the ascending grid: the lower index (clamped to the grid).
std::size_t lower_index(const std::vector<double>& grid, double at) {
    if (grid.size() < 2 || at <= grid.front()) return 0;
    const auto it = std::upper_bound(grid.begin(), grid.end(), at);
    const auto k = static_cast<std::size_t>(it - grid.begin()) - 1;
    return std::min(k, grid.size() - 2);
}

/// A row standing for `scale` copies of the bed characterised: every extensive quantity
/// (mass, force per acceleration, power, energy) multiplied, the ratios kept. The standard
/// deviations too: the copies are taken as moving alike, not as independent fillings.
CharacterizationRow scaled(CharacterizationRow r, double scale) {
    r.bed_mass_kg *= scale;
    r.apparent_mass_kg *= scale;
    r.apparent_mass_re_std_kg *= scale;
    r.apparent_mass_im_std_kg *= scale;
    r.power_w *= scale;
    r.power_std_w *= scale;
    r.kinetic_j *= scale;
    r.kinetic_std_j *= scale;
    return r;
}

}  // namespace

double monotone_cubic(const std::vector<double>& x, const std::vector<double>& y, double at) {
    const std::size_t n = x.size();
    if (n == 0 || y.size() != n) {
        throw std::invalid_argument("monotone_cubic: x and y must have the same size > 0");
    }
    if (n == 1 || at <= x.front()) return y.front();
    if (at >= x.back()) return y.back();
    std::vector<double> h(n - 1);
    std::vector<double> delta(n - 1);
    for (std::size_t k = 0; k + 1 < n; ++k) {
        h[k] = x[k + 1] - x[k];
        delta[k] = (y[k + 1] - y[k]) / h[k];
    }
    // Slopes: Fritsch & Carlson's weighted harmonic mean inside (zero at a local extremum of
    // the data, so the interpolant is monotone wherever the data are), the three-point
    // one-sided formula at the ends, limited to keep the end intervals monotone.
    std::vector<double> m(n, 0.0);
    if (n == 2) {
        m[0] = m[1] = delta[0];
    } else {
        for (std::size_t k = 1; k + 1 < n; ++k) {
            if (delta[k - 1] * delta[k] > 0.0) {
                const double w1 = 2.0 * h[k] + h[k - 1];
                const double w2 = h[k] + 2.0 * h[k - 1];
                m[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k]);
            }
        }
        const auto end_slope = [](double h0, double h1, double d0, double d1) {
            double s = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
            if (s * d0 <= 0.0) {
                s = 0.0;
            } else if (d0 * d1 <= 0.0 && std::abs(s) > 3.0 * std::abs(d0)) {
                s = 3.0 * d0;
            }
            return s;
        };
        m[0] = end_slope(h[0], h[1], delta[0], delta[1]);
        m[n - 1] = end_slope(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
    }
    const std::size_t k = lower_index(x, at);
    const double t = (at - x[k]) / h[k];
    const double t2 = t * t;
    const double t3 = t2 * t;
    return (2.0 * t3 - 3.0 * t2 + 1.0) * y[k] + (t3 - 2.0 * t2 + t) * h[k] * m[k] +
           (-2.0 * t3 + 3.0 * t2) * y[k + 1] + (t3 - t2) * h[k] * m[k + 1];
}

std::string characterization_csv_text(const CharacterizationTable& table) {
    std::ostringstream out;
    out << kFormatLine << '\n';
    out << "# config = " << table.config << '\n';
    out << "# config_hash = " << table.config_hash << '\n';
    for (const auto& [name, hash] : table.damper_hashes) {
        out << "# damper_hash." << name << " = " << hash << '\n';
    }
    if (!table.command.empty()) out << "# command = " << table.command << '\n';
    if (!table.criterion.empty()) out << "# steady_state = " << table.criterion << '\n';
    out << "# M = -Q1/a1 along the excitation direction, x(t) = Re{X e^{iwt}}: a rigid mass m "
           "gives m; -Im M = 2 P / (w |a1|^2)\n";
    for (std::size_t c = 0; c < std::size(kColumns); ++c) out << (c ? "," : "") << kColumns[c];
    out << '\n';
    for (const auto& r : table.rows) {
        id::detail::check_cell_text(r.damper, "damper");
        id::detail::check_cell_text(r.arrangement, "arrangement");
        out << r.damper << ',' << r.arrangement << ',' << exact_text(r.level_g) << ','
            << exact_text(r.acceleration_m_s2) << ',' << exact_text(r.frequency_hz) << ','
            << exact_text(r.bed_mass_kg);
        for (int k = 0; k < 3; ++k) out << ',' << exact_text(r.rotation_per_translation_rad_m[k]);
        out << ',' << r.seeds;
        for (double v :
             {r.apparent_mass_kg.real(), r.apparent_mass_re_std_kg, r.apparent_mass_kg.imag(),
              r.apparent_mass_im_std_kg, r.power_w, r.power_std_w, r.h2_ratio, r.h3_ratio,
              r.kinetic_j, r.kinetic_std_j, r.periods}) {
            out << ',' << exact_text(v);
        }
        out << ',' << (r.settled ? 1 : 0) << '\n';
    }
    return out.str();
}

CharacterizationTable read_characterization_csv(const std::filesystem::path& path) {
    const std::string file = path.string();
    CharacterizationTable table;
    {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw FileError(file, 0, 0, "cannot open the file");
        std::string line;
        int number = 0;
        bool format_seen = false;
        while (std::getline(in, line)) {
            ++number;
            if (!line.empty() && line.back() == '\r') line.pop_back();
            if (line.empty()) continue;
            if (line.front() != '#') break;
            if (number == 1) format_seen = line == kFormatLine;
            const auto eq = line.find(" = ");
            if (eq == std::string::npos) continue;
            const std::string key = line.substr(2, eq - 2);
            const std::string value = line.substr(eq + 3);
            if (key == "config") table.config = value;
            if (key == "config_hash") table.config_hash = value;
            if (key == "command") table.command = value;
            if (key == "steady_state") table.criterion = value;
            if (key.rfind("damper_hash.", 0) == 0) {
                table.damper_hashes.emplace_back(key.substr(12), value);
            }
        }
        if (!format_seen) {
            throw FileError(file, 1, 1,
                            std::string("not a characterisation file: the first line must be '") +
                                kFormatLine + "' (written by shakerbench characterize)");
        }
    }
    const id::detail::CsvTable t = id::detail::read_csv(path);
    std::map<std::string, std::size_t> col;
    for (std::size_t i = 0; i < t.header.size(); ++i) {
        const auto& h = t.header[i];
        if (std::find_if(std::begin(kColumns), std::end(kColumns),
                         [&](const char* c) { return h.text == c; }) == std::end(kColumns)) {
            throw FileError(file, h.line, h.column, "unknown column '" + h.text + "'");
        }
        if (!col.emplace(h.text, i).second) {
            throw FileError(file, h.line, h.column, "duplicate column '" + h.text + "'");
        }
    }
    for (const char* c : kColumns) {
        if (col.count(c) == 0) {
            throw FileError(file, t.header.front().line, 0,
                            std::string("missing column '") + c + "'");
        }
    }
    const auto number = [&](const std::vector<id::detail::CsvCell>& row, const char* name) {
        return id::detail::number(t, row[col.at(name)], name);
    };
    const auto positive = [&](const std::vector<id::detail::CsvCell>& row, const char* name) {
        const double v = number(row, name);
        if (!(v > 0.0)) {
            const auto& cell = row[col.at(name)];
            throw FileError(file, cell.line, cell.column,
                            std::string("column '") + name + "': '" + cell.text + "' must be > 0");
        }
        return v;
    };
    const auto non_negative = [&](const std::vector<id::detail::CsvCell>& row, const char* name) {
        const double v = number(row, name);
        if (v < 0.0) {
            const auto& cell = row[col.at(name)];
            throw FileError(file, cell.line, cell.column,
                            std::string("column '") + name + "': '" + cell.text + "' must be >= 0");
        }
        return v;
    };
    for (const auto& row : t.rows) {
        CharacterizationRow r;
        r.line = row.front().line;
        r.damper = row[col.at("damper")].text;
        r.arrangement = row[col.at("arrangement")].text;
        for (const char* name : {"damper", "arrangement"}) {
            const auto& cell = row[col.at(name)];
            if (cell.text.empty()) {
                throw FileError(file, cell.line, cell.column, std::string("empty ") + name);
            }
        }
        r.level_g = positive(row, "level_g");
        r.acceleration_m_s2 = positive(row, "acceleration_m_s2");
        r.frequency_hz = positive(row, "frequency_hz");
        r.bed_mass_kg = positive(row, "bed_mass_kg");
        r.rotation_per_translation_rad_m = {number(row, "rotation_x_rad_m"),
                                            number(row, "rotation_y_rad_m"),
                                            number(row, "rotation_z_rad_m")};
        const double seeds = positive(row, "seeds");
        if (seeds != std::floor(seeds)) {
            const auto& cell = row[col.at("seeds")];
            throw FileError(file, cell.line, cell.column,
                            "column 'seeds': '" + cell.text + "' must be a whole number");
        }
        r.seeds = static_cast<int>(seeds);
        r.apparent_mass_kg = {number(row, "apparent_mass_re_kg"),
                              number(row, "apparent_mass_im_kg")};
        r.apparent_mass_re_std_kg = non_negative(row, "apparent_mass_re_std_kg");
        r.apparent_mass_im_std_kg = non_negative(row, "apparent_mass_im_std_kg");
        r.power_w = number(row, "power_w");
        r.power_std_w = non_negative(row, "power_std_w");
        r.h2_ratio = non_negative(row, "h2");
        r.h3_ratio = non_negative(row, "h3");
        r.kinetic_j = non_negative(row, "kinetic_j");
        r.kinetic_std_j = non_negative(row, "kinetic_std_j");
        r.periods = non_negative(row, "periods");
        const auto& settled = row[col.at("settled")];
        if (settled.text != "0" && settled.text != "1") {
            throw FileError(file, settled.line, settled.column,
                            "column 'settled': '" + settled.text + "' must be 0 or 1");
        }
        r.settled = settled.text == "1";
        table.rows.push_back(std::move(r));
    }
    // Every damper and arrangement must form a grid: checked now, so that a bad file is bad
    // input before anything runs.
    std::set<std::pair<std::string, std::string>> groups;
    for (const auto& r : table.rows) groups.emplace(r.damper, r.arrangement);
    for (const auto& [damper, arrangement] : groups) {
        describing_function_for(table, file, damper, arrangement);
    }
    return table;
}

std::string damper_hash(const CampaignConfig& config, const std::string& damper) {
    const std::string prefix = config::join_path("dampers", damper) + ".";
    std::istringstream lines(canonical_config_text(config));
    std::string line;
    std::string kept;
    while (std::getline(lines, line)) {
        if (line.rfind(prefix, 0) != 0) continue;
        const std::string key = line.substr(prefix.size(), line.find(" = ") - prefix.size());
        // Not the physics: how the damper is represented and on how many threads.
        if (key == "model" || key == "characterization_file" || key == "characterization_scale" ||
            key == "threads") {
            continue;
        }
        kept += line.substr(prefix.size()) + "\n";
    }
    return config::fnv1a_hex(kept);
}

DescribingFunction::DescribingFunction(std::vector<CharacterizationRow> rows,
                                       const std::string& file) {
    if (rows.empty()) throw FileError(file, 0, 0, "no rows for the describing function");
    damper_ = rows.front().damper;
    arrangement_ = rows.front().arrangement;
    std::vector<double> a;
    std::vector<double> f;
    for (const auto& r : rows) {
        a.push_back(r.acceleration_m_s2);
        f.push_back(r.frequency_hz);
    }
    amplitudes_ = distinct(a);
    frequencies_ = distinct(f);
    const std::size_t nf = frequencies_.size();
    std::vector<int> filled(amplitudes_.size() * nf, 0);
    grid_.resize(amplitudes_.size() * nf);
    for (auto& r : rows) {
        const std::size_t i = index_of(amplitudes_, r.acceleration_m_s2);
        const std::size_t j = index_of(frequencies_, r.frequency_hz);
        const std::size_t at = i * nf + j;
        if (filled[at] != 0) {
            throw FileError(file, r.line, 0,
                            "damper " + damper_ + ", arrangement " + arrangement_ + ": " +
                                format_value(r.acceleration_m_s2) + " m/s^2 at " +
                                format_value(r.frequency_hz) + " Hz is given twice (also line " +
                                std::to_string(grid_[at].line) + ")");
        }
        filled[at] = 1;
        grid_[at] = std::move(r);
    }
    for (std::size_t i = 0; i < amplitudes_.size(); ++i) {
        for (std::size_t j = 0; j < nf; ++j) {
            if (filled[i * nf + j] == 0) {
                throw FileError(file, 0, 0,
                                "damper " + damper_ + ", arrangement " + arrangement_ +
                                    ": the rows do not form a grid of levels x frequencies: "
                                    "no row at " +
                                    format_value(amplitudes_[i]) + " m/s^2 and " +
                                    format_value(frequencies_[j]) + " Hz");
            }
        }
    }
    for (const auto& r : grid_) bed_mass_kg_ += r.bed_mass_kg / static_cast<double>(grid_.size());
    rotation_per_translation_ = grid_.front().rotation_per_translation_rad_m;
    for (const auto& r : grid_) {
        if (!(r.rotation_per_translation_rad_m - rotation_per_translation_)
                 .isZero(1e-9 * (1.0 + rotation_per_translation_.norm()))) {
            throw FileError(file, r.line, 0,
                            "damper " + damper_ + ", arrangement " + arrangement_ +
                                ": the rotation per translation differs from line " +
                                std::to_string(grid_.front().line) +
                                "'s (one grid is one drive shape)");
        }
    }
}

DescribingFunction::Value DescribingFunction::evaluate(double acceleration_m_s2,
                                                       double frequency_hz) const {
    const std::size_t na = amplitudes_.size();
    const std::size_t nf = frequencies_.size();
    const double tolerance = kSameValue;
    Value v;
    v.inside = acceleration_m_s2 >= amplitudes_.front() * (1.0 - tolerance) &&
               acceleration_m_s2 <= amplitudes_.back() * (1.0 + tolerance) &&
               frequency_hz >= frequencies_.front() * (1.0 - tolerance) &&
               frequency_hz <= frequencies_.back() * (1.0 + tolerance);
    // Along the frequency at every amplitude, then along log |a1|: the apparent mass of a bed
    // changes over decades of amplitude and by tens of per cent over a sweep's frequencies.
    std::vector<double> log_a(na);
    for (std::size_t i = 0; i < na; ++i) log_a[i] = std::log(amplitudes_[i]);
    std::vector<double> re(na), im(na), h2(na), h3(na);
    std::vector<double> yr(nf), yi(nf), y2(nf), y3(nf);
    for (std::size_t i = 0; i < na; ++i) {
        for (std::size_t j = 0; j < nf; ++j) {
            const auto& r = grid_[i * nf + j];
            yr[j] = r.apparent_mass_kg.real();
            yi[j] = r.apparent_mass_kg.imag();
            y2[j] = r.h2_ratio;
            y3[j] = r.h3_ratio;
        }
        re[i] = monotone_cubic(frequencies_, yr, frequency_hz);
        im[i] = monotone_cubic(frequencies_, yi, frequency_hz);
        h2[i] = monotone_cubic(frequencies_, y2, frequency_hz);
        h3[i] = monotone_cubic(frequencies_, y3, frequency_hz);
    }
    const double at = std::log(std::max(acceleration_m_s2, 1e-300));
    v.apparent_mass_kg = {monotone_cubic(log_a, re, at), monotone_cubic(log_a, im, at)};
    v.h2_ratio = monotone_cubic(log_a, h2, at);
    v.h3_ratio = monotone_cubic(log_a, h3, at);
    // The cell around the point (one row or column when the grid has one level or frequency).
    const std::size_t i0 = lower_index(amplitudes_, acceleration_m_s2);
    const std::size_t j0 = lower_index(frequencies_, frequency_hz);
    for (std::size_t i = i0; i <= std::min(i0 + 1, na - 1); ++i) {
        for (std::size_t j = j0; j <= std::min(j0 + 1, nf - 1); ++j) {
            v.settled = v.settled && grid_[i * nf + j].settled;
        }
    }
    return v;
}

DescribingFunction describing_function_for(const CharacterizationTable& table,
                                           const std::string& file, const std::string& damper,
                                           const std::string& arrangement, double scale) {
    if (!(scale > 0.0 && std::isfinite(scale))) {
        throw std::invalid_argument("describing_function_for: the scale must be positive");
    }
    std::vector<CharacterizationRow> rows;
    for (const auto& r : table.rows) {
        if (r.damper == damper && r.arrangement == arrangement) rows.push_back(scaled(r, scale));
    }
    if (rows.empty()) {
        std::set<std::string> have;
        for (const auto& r : table.rows) {
            if (r.damper == damper) have.insert(r.arrangement);
        }
        std::string list;
        for (const auto& a : have) list += (list.empty() ? "" : ", ") + a;
        throw FileError(file, 0, 0,
                        "no rows for damper " + damper + " in arrangement " + arrangement +
                            (have.empty() ? std::string(" (no rows for this damper at all)")
                                          : " (it has " + list + ")"));
    }
    return DescribingFunction(std::move(rows), file);
}

}  // namespace sb::bench

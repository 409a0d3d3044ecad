// The files of a calibration: calibration.toml, report.md, calibrated.toml, evaluations.csv,
// and the measured and simulated damping curves on one plot.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include "bench/resolved_config.hpp"
#include "core/text_file.hpp"
#include "correlation/calibration.hpp"
#include "correlation/report_text.hpp"
#include "identification/plots.hpp"

namespace sb::correlation {
namespace {

namespace fs = std::filesystem;

std::string level_name(const std::string& arrangement, double level_g) {
    return arrangement + " " + num(level_g) + " g";
}

const identification::DampingRow* row_at(const std::vector<identification::DampingRow>& rows,
                                         const std::string& arrangement, double level_g) {
    for (const auto& r : rows) {
        if (r.arrangement == arrangement && std::abs(r.level_g - level_g) <= 1e-9 * level_g) {
            return &r;
        }
    }
    return nullptr;
}

std::string calibration_toml(const CalibrationResult& r, const Measurement& m,
                             const std::string& command_line) {
    std::ostringstream out;
    out << "# shakerbench calibrate: the calibrated values, their 95 % profile intervals and\n"
        << "# whether the data identify them (docs/calibration.md).\n"
        << "[calibration]\n"
        << "command = " << toml_string(command_line) << '\n'
        << "measured = " << toml_string(m.directory.string()) << '\n'
        << "measured_depth = " << toml_string(m.depth) << '\n'
        << "mode = " << toml_string(search_mode_name(r.search.mode)) << '\n'
        << "budget = " << r.search.budget << '\n'
        << "evaluations = " << r.outcome.evaluations << '\n'
        << "simulations = " << r.simulations << '\n'
        << "stopped = " << toml_string(r.outcome.stopped) << '\n'
        << "fidelity = " << toml_string(fidelity_name(r.fidelity)) << '\n';
    if (r.fidelity == Fidelity::two_fidelity) {
        // The budget and evaluations above are the low fidelity's; simulations the coupled.
        out << "low_fidelity_evaluations = " << r.low_fidelity_history.size() << '\n'
            << "low_fidelity_simulations = " << r.low_fidelity_simulations << '\n'
            << "corrections = " << r.corrections << '\n'
            << "corrections_stopped = " << toml_string(r.corrections_stopped) << '\n';
    }
    out << "wall_time_s = " << num(r.wall_time_s, 1, true) << '\n'
        << "misfit_start = " << num(r.start.misfit) << '\n'
        << "misfit_calibrated = " << num(r.best.misfit) << '\n'
        << "features = " << m.features.size() << '\n'
        << "calibrated_config = \"calibrated.toml\"\n";
    if (!r.findings_note.empty()) out << "note = " << toml_string(r.findings_note) << '\n';
    if (!r.warnings.empty()) {
        out << "warnings = [";
        for (std::size_t i = 0; i < r.warnings.size(); ++i) {
            out << (i ? ", " : "") << toml_string(r.warnings[i]);
        }
        out << "]\n";
    }
    for (std::size_t j = 0; j < r.free.size(); ++j) {
        const auto& p = r.free[j];
        out << "\n[[parameters]]\n"
            << "key = " << toml_string(p.path) << '\n'
            << "meaning = " << toml_string(p.meaning) << '\n'
            << "search_interval = [" << num(p.lo, 17) << ", " << num(p.hi, 17) << "]\n"
            << "search_scale = " << toml_string(p.log_scale ? "log" : "linear") << '\n'
            << "start = " << num(p.start, 17) << '\n';
        if (j < r.findings.size()) {
            const auto& f = r.findings[j];
            out << "identifiable = " << (f.identifiable ? "true" : "false") << '\n';
            // A parameter the data cannot identify gets no value: the interval says what the
            // data allow.
            if (f.identifiable) out << "value = " << num(f.value, 17) << '\n';
            out << "interval_95 = [" << num(f.lo95, 17) << ", " << num(f.hi95, 17) << "]\n"
                << "finding = " << toml_string(f.reason) << '\n'
                << "information_share = [";
            for (std::size_t s = 0; s < f.information_share.size(); ++s) {
                out << (s ? ", " : "") << num(f.information_share[s], 4, true);
            }
            out << "]  # per level, in the order of [[levels]]\n";
        } else {
            out << "value = " << num(r.best.values[j], 17) << '\n';
        }
    }
    for (const auto& l : r.levels) {
        out << "\n[[levels]]\n"
            << "arrangement = " << toml_string(l.arrangement) << '\n'
            << "level_g = " << num(l.level_g, 17) << '\n'
            << "features = " << l.features << '\n'
            << "misfit_start = " << num(l.misfit_start) << '\n'
            << "misfit_calibrated = " << num(l.misfit_best) << '\n';
    }
    return out.str();
}

std::string report_md(const CalibrationResult& r, const Measurement& m,
                      const std::string& command_line) {
    std::ostringstream out;
    out << "# Calibration report\n\n"
        << "Command: `" << command_line << "`\n\n"
        << "Measured: `" << m.directory.string() << "` (" << m.depth << "; " << m.features.size()
        << " features over " << m.selection.sweeps.size()
        << " arrangement and level(s); damping by " << m.damping_method << ").\n\n"
        << "Search: " << search_mode_name(r.search.mode) << ", " << r.outcome.evaluations
        << " evaluations of a budget of " << r.search.budget << ", "
        << (r.fidelity == Fidelity::two_fidelity ? r.low_fidelity_simulations : r.simulations)
        << " simulated (the others from the cache); ended by " << r.outcome.stopped << "; "
        << num(r.wall_time_s, 1, true) << " s.\n\n";
    if (r.fidelity == Fidelity::two_fidelity) {
        out << "Two-fidelity: the search ran on the describing-function prediction ("
            << r.low_fidelity_history.size() << " evaluations, " << r.low_fidelity_simulations
            << " simulated); " << r.corrections
            << " stencil(s) of coupled simulations corrected it (" << r.corrections_stopped << "); "
            << r.simulations
            << " coupled simulations in all, the start and the confirmation included.\n\n";
    }
    out << "Misfit (½ χ², the residuals in standard deviations of the measurement and the "
           "simulation's seed scatter): "
        << num(r.start.misfit, 4) << " at the config's values, " << num(r.best.misfit, 4)
        << " calibrated.\n\n## Parameters\n\n"
        << "| key | start | calibrated | 95 % interval | identifiable |\n|---|---|---|---|---|\n";
    for (std::size_t j = 0; j < r.free.size(); ++j) {
        const auto& p = r.free[j];
        out << "| `" << p.path << "` | " << num(p.start, 4) << " | ";
        if (j < r.findings.size()) {
            const auto& f = r.findings[j];
            out << (f.identifiable ? num(f.value, 4) : std::string("not identifiable")) << " | ["
                << num(f.lo95, 4) << ", " << num(f.hi95, 4) << "] | "
                << (f.identifiable ? "yes" : "no") << " |\n";
        } else {
            out << num(r.best.values[j], 4) << " | — | not assessed |\n";
        }
    }
    out << '\n';
    for (const auto& f : r.findings) out << "- `" << f.parameter.path << "`: " << f.reason << ".\n";
    if (!r.findings_note.empty()) out << "- " << r.findings_note << '\n';
    for (const auto& w : r.warnings) out << "- **Warning**: " << w << ".\n";
    if (!r.findings.empty()) {
        out << "\n## Which levels inform which parameter\n\n"
            << "Share of each parameter's Fisher information (the squared sensitivities of the "
               "residuals, from the emulator at the calibrated values) carried by each level.\n\n"
            << "| level |";
        for (const auto& f : r.findings) out << " `" << f.parameter.path << "` |";
        out << "\n|---|";
        for (std::size_t j = 0; j < r.findings.size(); ++j) out << "---|";
        out << '\n';
        for (std::size_t s = 0; s < m.selection.sweeps.size(); ++s) {
            out << "| "
                << level_name(m.selection.sweeps[s].arrangement, m.selection.sweeps[s].level_g)
                << " |";
            for (const auto& f : r.findings) {
                out << ' ' << num(100.0 * f.information_share[s], 0, true) << " % |";
            }
            out << '\n';
        }
    }
    out << "\n## Residuals per level\n\n"
        << "| level | features | misfit at start | misfit calibrated | damping measured | "
           "start | calibrated |\n|---|---|---|---|---|---|---|\n";
    for (const auto& l : r.levels) {
        const auto* mr = row_at(m.damping, l.arrangement, l.level_g);
        const auto* sr = row_at(r.start.simulated.damping, l.arrangement, l.level_g);
        const auto* br = row_at(r.best.simulated.damping, l.arrangement, l.level_g);
        const auto pct = [](const identification::DampingRow* row) {
            return row ? num(100.0 * row->damping_ratio, 3, true) + " %" : std::string("—");
        };
        out << "| " << level_name(l.arrangement, l.level_g) << " | " << l.features << " | "
            << num(l.misfit_start, 3) << " | " << num(l.misfit_best, 3) << " | " << pct(mr) << " | "
            << pct(sr) << " | " << pct(br) << " |\n";
    }
    out << "\nPlot: `calibration-damping.svg` (measured and simulated damping against level). "
           "Every evaluation: `evaluations.csv`. The calibrated config: `calibrated.toml`.\n";
    return out.str();
}

std::string evaluations_csv(const CalibrationResult& r) {
    std::ostringstream out;
    out << "evaluation";
    for (const auto& p : r.free) out << ',' << p.path;
    out << ",misfit,from_cache,wall_time_s,error\n";
    for (std::size_t i = 0; i < r.history.size(); ++i) {
        const auto& e = r.history[i];
        out << i + 1;
        for (double v : e.values) out << ',' << num(v, 17);
        std::string error = e.error;
        std::replace(error.begin(), error.end(), ',', ';');
        std::replace(error.begin(), error.end(), '\n', ' ');
        out << ',' << num(e.misfit, 10) << ',' << (e.from_cache ? 1 : 0) << ','
            << num(e.wall_time_s, 3, true) << ',' << error << '\n';
    }
    return out.str();
}

void write_plots(const fs::path& out_dir, const CalibrationResult& r, const Measurement& m) {
    const fs::path dir = out_dir / "plots";
    fs::create_directories(dir);
    std::ostringstream data;
    data << "# level_g measured_damping_% measured_std_% start_% start_std_% calibrated_% "
            "calibrated_std_%\n";
    std::vector<std::string> arrangements;
    for (const auto& s : m.selection.sweeps) {
        if (std::find(arrangements.begin(), arrangements.end(), s.arrangement) ==
            arrangements.end()) {
            arrangements.push_back(s.arrangement);
        }
    }
    for (const auto& a : arrangements) {
        data << "# " << a << '\n';
        for (const auto& s : m.selection.sweeps) {
            if (s.arrangement != a) continue;
            const auto cell = [](const identification::DampingRow* row) {
                return row ? num(100.0 * row->damping_ratio) + ' ' +
                                 num(100.0 * row->damping_ratio_std)
                           : std::string("nan nan");
            };
            data << num(s.level_g) << ' ' << cell(row_at(m.damping, a, s.level_g)) << ' '
                 << cell(row_at(r.start.simulated.damping, a, s.level_g)) << ' '
                 << cell(row_at(r.best.simulated.damping, a, s.level_g)) << '\n';
        }
        data << "\n\n";
    }
    write_file_atomically(dir / "calibration-damping.dat", data.str());
    std::ostringstream gp;
    gp << "# Measured and simulated damping against level; run here: gnuplot calibration.gp\n"
       << "set terminal svg size 800,500 dynamic background rgb 'white'\n"
       << "set output '../calibration-damping.svg'\n"
       << "set xlabel 'level [g RMS]'\nset ylabel 'damping ratio [%]'\nset key outside right\n"
       << "set title 'Calibration: measured and simulated damping'\n"
       << "plot ";
    for (std::size_t i = 0; i < arrangements.size(); ++i) {
        const auto& a = arrangements[i];
        gp << (i ? ", \\\n     " : "") << "'calibration-damping.dat' index " << i
           << " using 1:2:3 with yerrorlines lw 2 title '" << a << " measured', \\\n"
           << "     '' index " << i << " using 1:4:5 with yerrorlines dt 2 title '" << a
           << " at the config''s values', \\\n"
           << "     '' index " << i << " using 1:6:7 with yerrorlines title '" << a
           << " calibrated'";
    }
    gp << '\n';
    identification::PlotResult plots;
    plots.script = dir / "calibration.gp";
    plots.svg = {out_dir / "calibration-damping.svg"};
    write_file_atomically(plots.script, gp.str());
    // Without gnuplot the data and the script are there to render later.
    identification::render_gnuplot(true, plots);
}

}  // namespace

void write_calibration(const fs::path& out_dir, const CalibrationResult& result,
                       const Measurement& measurement, const std::string& command_line) {
    fs::create_directories(out_dir);
    write_file_atomically(out_dir / "calibration.toml",
                          calibration_toml(result, measurement, command_line));
    write_file_atomically(out_dir / "report.md", report_md(result, measurement, command_line));
    write_file_atomically(out_dir / "calibrated.toml",
                          "# The config with the calibrated values (" + command_line + ")\n" +
                              bench::resolved_config_toml(result.calibrated));
    write_file_atomically(out_dir / "evaluations.csv", evaluations_csv(result));
    write_plots(out_dir, result, measurement);
}

}  // namespace sb::correlation

// Plot data, gnuplot script and rendering (gnuplot is a program, not a library: it is run).
#include "identification/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "core/text_file.hpp"
#include "core/units.hpp"
#include "identification/file_error.hpp"

namespace sb::identification {

namespace fs = std::filesystem;

std::string file_safe(const std::string& name) {
    std::string out = name.empty() ? "unnamed" : name;
    for (char& c : out) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                        (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
        if (!ok) c = '_';
    }
    return out;
}

std::string gnuplot_quoted(const std::string& s) {
    std::string out = "'";
    for (char c : s) {
        out += c;
        if (c == '\'') out += '\'';
    }
    return out + "'";
}

namespace {

std::string quoted(const std::string& s) { return gnuplot_quoted(s); }

/// A shell single-quoted string.
std::string shell_quoted(const std::string& s) {
    std::string out = "'";
    for (char c : s) {
        if (c == '\'') {
            out += "'\\''";
        } else {
            out += c;
        }
    }
    return out + "'";
}

std::string number(double v) {
    if (!std::isfinite(v)) return "NaN";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

std::string level_title(double level_g) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", level_g);
    return buf;
}

/// "1 g", or "1 g, filling 2" for the second and later fillings of the bed (a fixed drive's
/// level in its own unit: "0.2 V").
std::string block_title(const LevelIdentification& l, const std::string& unit) {
    std::string title = level_title(l.level_g) + " " + unit;
    if (l.filling > 0) title += ", filling " + std::to_string(l.filling);
    return title;
}

/// Copies of the levels of one arrangement, for damping_rows.
std::vector<LevelIdentification> arrangement_levels(
    const std::vector<const LevelIdentification*>& items) {
    std::vector<LevelIdentification> out;
    out.reserve(items.size());
    for (const auto* l : items) out.push_back(*l);
    return out;
}

std::string form_name(FrfForm form) {
    switch (form) {
        case FrfForm::receptance:
            return "receptance";
        case FrfForm::mobility:
            return "mobility";
        case FrfForm::accelerance:
            return "accelerance";
    }
    return "FRF";
}

void write_file(const fs::path& file, const std::string& text) {
    write_file_atomically(file, text);
}

/// True if the level's FRF has a point a log-magnitude plot can draw (a level whose points
/// were all left out, `closest` or `uncertain`, has none; gnuplot refuses a plot with no point).
bool has_drawable_point(const LevelIdentification& l) {
    for (std::size_t i = 0; i < l.frf.frequency_hz.size() && i < l.frf.value.size(); ++i) {
        const double magnitude = std::abs(l.frf.value[i]);
        if (std::isfinite(l.frf.frequency_hz[i]) && std::isfinite(magnitude) && magnitude > 0.0) {
            return true;
        }
    }
    return false;
}

}  // namespace

PlotResult write_plots(const fs::path& out_dir, const std::vector<LevelIdentification>& levels,
                       const PlotOptions& options) {
    PlotResult result;
    const fs::path dir = out_dir / "plots";
    create_directories_for_writing(dir);
    std::vector<std::string> order;
    std::map<std::string, std::vector<const LevelIdentification*>> by_arrangement;
    for (const auto& l : levels) {
        if (by_arrangement.find(l.arrangement) == by_arrangement.end()) {
            order.push_back(l.arrangement);
        }
        by_arrangement[l.arrangement].push_back(&l);
    }
    const char* const methods[] = {"half-power", "circle-fit", "rational-fraction"};
    std::ostringstream gp;
    gp << "# Plots of shakerbench identify; run from this directory: gnuplot plots.gp\n"
       << "set terminal svg size 900,700 dynamic\nset grid\nset key outside right\n"
       << "set datafile missing 'NaN'\n";
    for (const auto& arrangement : order) {
        const auto& items = by_arrangement[arrangement];
        const std::string name = file_safe(arrangement);
        std::ostringstream frf;
        std::ostringstream curve;
        frf << "# frequency_hz magnitude phase_deg; one block per level (and filling of the bed)"
               " with a point\n";
        std::vector<const LevelIdentification*> drawn;
        for (const auto* l : items) {
            if (has_drawable_point(*l)) drawn.push_back(l);
        }
        for (std::size_t b = 0; b < drawn.size(); ++b) {
            const auto* l = drawn[b];
            if (b > 0) frf << "\n\n";
            frf << "# level " << block_title(*l, options.level_unit) << '\n';
            for (std::size_t i = 0; i < l->frf.frequency_hz.size(); ++i) {
                const auto v = l->frf.value[i];
                frf << number(l->frf.frequency_hz[i]) << ' ' << number(std::abs(v)) << ' '
                    << number(std::arg(v) * 180.0 / kPi) << '\n';
            }
        }
        // The curve: per level and method the mean over the fillings of the bed and its
        // sample standard deviation (the seed scatter, drawn as error bars; 0 for one).
        curve << "# level, then per method (half-power, circle-fit, rational-fraction): "
                 "zeta_percent zeta_std_percent fn_hz fn_std_hz\n";
        const auto rows = damping_rows(arrangement_levels(items), true);
        std::vector<double> curve_levels;
        for (const auto& r : rows) {
            if (std::find(curve_levels.begin(), curve_levels.end(), r.level_g) ==
                curve_levels.end()) {
                curve_levels.push_back(r.level_g);
            }
        }
        bool method_has_value[3] = {false, false, false};
        for (double level : curve_levels) {
            curve << number(level);
            for (int k = 0; k < 3; ++k) {
                const auto row = std::find_if(rows.begin(), rows.end(), [&](const DampingRow& r) {
                    return r.level_g == level && r.method == methods[k];
                });
                if (row == rows.end()) {
                    curve << " NaN NaN NaN NaN";
                    continue;
                }
                method_has_value[k] = true;
                curve << ' ' << number(row->damping_ratio * 100.0) << ' '
                      << number(row->damping_ratio_std * 100.0) << ' '
                      << number(row->natural_frequency_hz) << ' '
                      << number(row->natural_frequency_std_hz);
            }
            curve << '\n';
        }
        const fs::path frf_file = dir / (name + "-frf.dat");
        const fs::path curve_file = dir / (name + "-damping.dat");
        write_file(frf_file, frf.str());
        write_file(curve_file, curve.str());
        result.data.push_back(frf_file);
        result.data.push_back(curve_file);

        // FRF: magnitude (log) and phase, one curve per level with a point, or as lines alone
        // on a fine grid (a random test's hundreds of lines: a marker each would make the SVG
        // tens of megabytes and hide the curve).
        if (!drawn.empty()) {
            std::size_t most_points = 0;
            for (const auto* l : drawn)
                most_points = std::max(most_points, l->frf.frequency_hz.size());
            const char* style =
                most_points > 200 ? " with lines title " : " with linespoints title ";
            const fs::path frf_svg = out_dir / (name + "-frf.svg");
            const std::string form = form_name(drawn.front()->frf.form);
            gp << "\nset output " << quoted("../" + frf_svg.filename().string()) << '\n'
               << "set multiplot layout 2,1 title " << quoted("FRF (" + form + "), " + arrangement)
               << "\nset ylabel " << quoted("|" + form + "|") << "\nset logscale y\nplot ";
            for (std::size_t b = 0; b < drawn.size(); ++b) {
                gp << (b ? ", " : "") << quoted(frf_file.filename().string()) << " index " << b
                   << " using 1:2" << style << quoted(block_title(*drawn[b], options.level_unit));
            }
            gp << "\nunset logscale y\nset ylabel 'phase [deg]'\nset xlabel 'frequency [Hz]'"
                  "\nplot ";
            for (std::size_t b = 0; b < drawn.size(); ++b) {
                gp << (b ? ", " : "") << quoted(frf_file.filename().string()) << " index " << b
                   << " using 1:3" << style << quoted(block_title(*drawn[b], options.level_unit));
            }
            gp << "\nunset multiplot\nunset xlabel\n";
            result.svg.push_back(frf_svg);
        }

        // Damping and natural frequency versus level, one curve per method with a number.
        if (!(method_has_value[0] || method_has_value[1] || method_has_value[2])) continue;
        const fs::path damping_svg = out_dir / (name + "-damping.svg");
        gp << "\nset output " << quoted("../" + damping_svg.filename().string()) << '\n'
           << "set multiplot layout 2,1 title "
           << quoted("Damping and natural frequency, " + arrangement)
           << "\nset ylabel 'damping ratio [%]'\nplot ";
        for (int pass = 0; pass < 2; ++pass) {
            bool first = true;
            for (int k = 0; k < 3; ++k) {
                if (!method_has_value[k]) continue;
                const int column = 2 + 4 * k + 2 * pass;  // the mean; its std follows
                gp << (first ? "" : ", ") << quoted(curve_file.filename().string())
                   << " using 1:" << column << ':' << column + 1 << " with yerrorlines title "
                   << quoted(methods[k]);
                first = false;
            }
            if (pass == 0) {
                gp << "\nset ylabel 'natural frequency [Hz]'\nset xlabel "
                   << quoted(options.level_axis) << "\nplot ";
            }
        }
        gp << "\nunset multiplot\nunset xlabel\n";
        result.svg.push_back(damping_svg);
    }
    result.script = dir / "plots.gp";
    write_file(result.script, gp.str());
    render_gnuplot(options.render, result);
    return result;
}

void render_gnuplot(bool render, PlotResult& result) {
    const fs::path dir = result.script.parent_path();
    // The script's name is ours (plots.gp, diagnosis.gp): no quoting needed.
    const std::string how =
        "cd " + shell_quoted(dir.string()) + " && gnuplot " + result.script.filename().string();
    if (!render) {
        result.message = "plots not rendered; to make the SVGs run: " + how;
        return;
    }
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
        result.message = "gnuplot not found on PATH; to make the SVGs run: " + how;
        return;
    }
    if (std::system((how + " >gnuplot.log 2>&1").c_str()) != 0) {
        result.message = "gnuplot failed on " + result.script.string() + " (see " +
                         (dir / "gnuplot.log").string() + ")";
        return;
    }
    result.rendered = true;
    for (const auto& svg : result.svg) {
        if (!fs::exists(svg)) {
            result.rendered = false;
            result.message = "gnuplot did not write " + svg.string() + " (see " +
                             (dir / "gnuplot.log").string() + ")";
        }
    }
}

}  // namespace sb::identification

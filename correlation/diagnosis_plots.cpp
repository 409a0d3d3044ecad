#include "correlation/diagnosis_plots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/text_file.hpp"
#include "correlation/report_text.hpp"

namespace sb::correlation {
namespace {

namespace fs = std::filesystem;

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

/// The arrangements of the measurement, in order of first appearance.
std::vector<std::string> arrangements_of(const Measurement& m) {
    std::vector<std::string> out;
    for (const auto& s : m.selection.sweeps) {
        if (std::find(out.begin(), out.end(), s.arrangement) == out.end()) {
            out.push_back(s.arrangement);
        }
    }
    return out;
}

/// The levels of one arrangement, in the measurement's order.
std::vector<double> levels_of(const Measurement& m, const std::string& arrangement) {
    std::vector<double> out;
    for (const auto& s : m.selection.sweeps) {
        if (s.arrangement == arrangement) out.push_back(s.level_g);
    }
    return out;
}

/// Value `i` of a simulation's features, NaN where it has none.
double simulated_at(const SimulatedFeatures* s, std::size_t i) {
    return s != nullptr && i < s->value.size() ? s->value[i] : kNoValue;
}

/// The row of a simulated damping curve for one level, by the measurement's estimator (any
/// estimator when it names none), over every filling; null when there is none.
const identification::DampingRow* damping_row(const SimulatedFeatures* s,
                                              const std::string& arrangement, double level_g,
                                              const std::string& method) {
    if (s == nullptr) return nullptr;
    for (const auto& r : s->damping) {
        if (r.arrangement == arrangement && same_level(r.level_g, level_g) && r.filling < 0 &&
            (method.empty() || r.method == method)) {
            return &r;
        }
    }
    return nullptr;
}

/// One arrangement's FRF blocks: per level, the |H| points sorted by frequency.
std::string frf_data(const DiagnosisResult& r, const SimulatedFeatures* improved,
                     const std::string& arrangement) {
    std::ostringstream out;
    out << "# " << arrangement
        << ": frequency_hz measured_|H| measured_sigma baseline_|H| improved_|H|\n";
    const auto& features = r.measurement.features;
    for (const double level : levels_of(r.measurement, arrangement)) {
        struct Row {
            double f, measured, sigma, baseline, improved;
        };
        std::vector<Row> rows;
        for (std::size_t i = 0; i < features.size(); ++i) {
            const auto& ft = features[i];
            if (ft.kind != FeatureKind::log_magnitude || ft.arrangement != arrangement ||
                !same_level(ft.level_g, level)) {
                continue;
            }
            // ln|H| with its standard uncertainty: |H| e^{±σ} ≈ |H| (1 ± σ).
            const double measured = std::exp(ft.value);
            rows.push_back({ft.frequency_hz, measured, measured * ft.sigma,
                            std::exp(simulated_at(&r.baseline, i)),
                            std::exp(simulated_at(improved, i))});
        }
        std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.f < b.f; });
        out << "# " << num(level) << " g\n";
        for (const auto& row : rows) {
            out << num(row.f, 10) << ' ' << num(row.measured) << ' ' << num(row.sigma) << ' '
                << num(row.baseline) << ' ' << num(row.improved) << '\n';
        }
        out << "\n\n";
    }
    return out.str();
}

/// One arrangement's damping and natural frequency per level.
std::string levels_data(const DiagnosisResult& r, const SimulatedFeatures* improved,
                        const std::string& arrangement) {
    std::ostringstream out;
    out << "# " << arrangement
        << ": level_g damping_% measured, sigma, baseline, improved; natural_frequency_hz "
           "measured, sigma, baseline, improved\n";
    const auto zeta = static_cast<std::size_t>(LevelFeature::damping_ratio);
    const auto fn = static_cast<std::size_t>(LevelFeature::natural_frequency);
    const std::string& method = r.measurement.damping_method;
    for (const double level : levels_of(r.measurement, arrangement)) {
        double measured_zeta = kNoValue, sigma_zeta = kNoValue, measured_fn = kNoValue,
               sigma_fn = kNoValue;
        for (const auto& v : r.measured) {
            if (v.arrangement == arrangement && same_level(v.level_g, level)) {
                measured_zeta = 100.0 * v.value[zeta];
                sigma_zeta = 100.0 * v.sigma[zeta];
                measured_fn = v.value[fn];
                sigma_fn = v.sigma[fn];
            }
        }
        const auto* baseline = damping_row(&r.baseline, arrangement, level, method);
        const auto* better = damping_row(improved, arrangement, level, method);
        out << num(level, 10) << ' ' << num(measured_zeta) << ' ' << num(sigma_zeta) << ' '
            << num(baseline ? 100.0 * baseline->damping_ratio : kNoValue) << ' '
            << num(better ? 100.0 * better->damping_ratio : kNoValue) << ' ' << num(measured_fn, 10)
            << ' ' << num(sigma_fn) << ' '
            << num(baseline ? baseline->natural_frequency_hz : kNoValue, 10) << ' '
            << num(better ? better->natural_frequency_hz : kNoValue, 10) << '\n';
    }
    return out.str();
}

}  // namespace

identification::PlotResult write_diagnosis_plots(const fs::path& out_dir,
                                                 const DiagnosisResult& r) {
    using identification::gnuplot_quoted;
    identification::PlotResult result;
    const fs::path dir = out_dir / "plots";
    create_directories_for_writing(dir);
    const SimulatedFeatures* improved = nullptr;
    std::string improved_name;
    if (r.hypotheses && r.hypotheses->winner >= 0) {
        const auto& w = r.hypotheses->fits[static_cast<std::size_t>(r.hypotheses->winner)];
        improved = &w.simulated;
        improved_name = "with " + w.name();
    }
    std::ostringstream gp;
    gp << "# Measured, baseline and improved (shakerbench diagnose); run here: gnuplot "
          "diagnosis.gp\nset terminal svg size 900,650 dynamic background rgb 'white'\n"
       << "set key outside right\nset offsets graph 0.03, graph 0.03, 0, 0\n";
    for (const auto& arrangement : arrangements_of(r.measurement)) {
        const std::string name = identification::file_safe(arrangement);
        const fs::path frf = dir / (name + "-frf.dat");
        const fs::path levels = dir / (name + "-levels.dat");
        write_file_atomically(frf, frf_data(r, improved, arrangement));
        write_file_atomically(levels, levels_data(r, improved, arrangement));
        result.data.push_back(frf);
        result.data.push_back(levels);

        const fs::path frf_svg = out_dir / ("diagnosis-" + name + "-frf.svg");
        gp << "\nset output " << gnuplot_quoted("../" + frf_svg.filename().string()) << '\n'
           << "set title " << gnuplot_quoted(arrangement + ": the FRF per level")
           << "\nset xlabel 'frequency [Hz]'\nset ylabel '|H|'\nplot ";
        const auto level_list = levels_of(r.measurement, arrangement);
        for (std::size_t k = 0; k < level_list.size(); ++k) {
            const std::string level = num(level_list[k]) + " g";
            const std::string colour = " lc " + std::to_string(k + 1);
            gp << (k ? ", \\\n     " : "") << gnuplot_quoted(frf.filename().string()) << " index "
               << k << " using 1:2:3 with yerrorbars pt 7 ps 0.5" << colour << " title "
               << gnuplot_quoted(level + " measured") << ", \\\n     '' index " << k
               << " using 1:4 with lines dt 2" << colour << " title "
               << gnuplot_quoted(level + " baseline");
            if (improved) {
                gp << ", \\\n     '' index " << k << " using 1:5 with lines lw 2" << colour
                   << " title " << gnuplot_quoted(level + " " + improved_name);
            }
        }
        gp << '\n';
        result.svg.push_back(frf_svg);

        const fs::path levels_svg = out_dir / ("diagnosis-" + name + "-levels.svg");
        const std::string file = gnuplot_quoted(levels.filename().string());
        gp << "\nset output " << gnuplot_quoted("../" + levels_svg.filename().string()) << '\n'
           << "set multiplot layout 2,1 title "
           << gnuplot_quoted(arrangement + ": measured, baseline and improved per level") << '\n'
           << "unset title\nset xlabel 'level [g RMS]'\n";
        for (int pass = 0; pass < 2; ++pass) {
            const int first = pass == 0 ? 2 : 6;  // damping columns 2-5, frequency 6-9
            gp << "set ylabel " << (pass == 0 ? "'damping ratio [%]'" : "'natural frequency [Hz]'")
               << "\nplot " << file << " using 1:" << first << ':' << first + 1
               << " with yerrorlines lw 2 title 'measured', '' using 1:" << first + 2
               << " with linespoints dt 2 title 'baseline'";
            if (improved) {
                gp << ", '' using 1:" << first + 3 << " with linespoints title "
                   << gnuplot_quoted(improved_name);
            }
            gp << '\n';
        }
        gp << "unset multiplot\n";
        result.svg.push_back(levels_svg);
    }
    result.script = dir / "diagnosis.gp";
    write_file_atomically(result.script, gp.str());
    identification::render_gnuplot(true, result);
    return result;
}

}  // namespace sb::correlation

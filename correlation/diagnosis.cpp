#include "correlation/diagnosis.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "bench/resolved_config.hpp"
#include "core/text_file.hpp"
#include "correlation/diagnosis_plots.hpp"
#include "correlation/report_text.hpp"
#include "identification/recording_io.hpp"

namespace sb::correlation {
namespace {

/// A recording without points (damping.csv alone): its natural frequency and damping per
/// level, with their fillings' scatter where there is some, else the stated uncertainty.
std::vector<LevelFeatureValues> from_damping_rows(
    const std::vector<identification::DampingRow>& rows, const StatedUncertainty& stated) {
    std::vector<LevelFeatureValues> out;
    constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();
    for (const auto& r : rows) {
        LevelFeatureValues v{r.arrangement, r.level_g, r.fillings, {}, {}};
        v.value.fill(kNotMeasured);
        v.sigma.fill(kNotMeasured);
        const auto f = static_cast<std::size_t>(LevelFeature::natural_frequency);
        const auto z = static_cast<std::size_t>(LevelFeature::damping_ratio);
        const double n = std::max(1, r.fillings);
        v.value[f] = r.natural_frequency_hz;
        v.value[z] = r.damping_ratio;
        v.sigma[f] = std::max(r.natural_frequency_std_hz / std::sqrt(n),
                              stated.frequency_relative * r.natural_frequency_hz);
        v.sigma[z] =
            std::max(r.damping_ratio_std / std::sqrt(n), stated.damping_relative * r.damping_ratio);
        out.push_back(v);
    }
    return out;
}

/// The head of a distributed drift evaluation's input: the drift value's and the level's
/// indices, each on its own line.
std::string drift_input_head(std::size_t parameter, std::size_t level) {
    return std::to_string(parameter) + "\n" + std::to_string(level) + "\n";
}

/// Reads an index line of `input` from `at` (moved past it); throws when it is not one below
/// `count`.
std::size_t index_line(const std::string& input, std::size_t& at, std::size_t count,
                       const char* what) {
    const auto end = input.find('\n', at);
    const std::string text = input.substr(at, end == std::string::npos ? end : end - at);
    at = end == std::string::npos ? input.size() : end + 1;
    std::size_t used = 0;
    unsigned long value = 0;
    try {
        value = std::stoul(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || value >= count) {
        throw std::invalid_argument(std::string("a diagnosis evaluation names no ") + what + " '" +
                                    text + "'");
    }
    return value;
}

}  // namespace

std::function<std::string(const std::string&, int)> diagnosis_simulator(
    const bench::CampaignConfig& config, const Measurement& measurement,
    const DiagnosisOptions& options) {
    // One calibration simulator per drift value and level, built as drift_test builds their
    // calibrations.
    std::vector<std::vector<std::function<std::string(const std::string&, int)>>> simulators;
    for (const auto& parameter : options.drift) {
        auto& per_level = simulators.emplace_back();
        for (const auto& sweep : measurement.selection.sweeps) {
            per_level.push_back(calibration_simulator(
                config, level_measurement(measurement, sweep.arrangement, sweep.level_g),
                {parameter}, options.calibration));
        }
    }
    return [simulators = std::move(simulators)](const std::string& input, int threads) {
        std::size_t at = 0;
        const auto p = index_line(input, at, simulators.size(), "drift value");
        const auto level = index_line(input, at, simulators[p].size(), "level");
        return simulators[p][level](input.substr(at), threads);
    };
}

DiagnosisResult diagnose(const bench::CampaignConfig& config, const std::filesystem::path& measured,
                         const DiagnosisOptions& options) {
    const auto started = std::chrono::steady_clock::now();
    DiagnosisResult result;
    result.measurement = read_measurement(measured, options.stated);
    const auto say = [&](const std::string& line) {
        if (options.progress) options.progress(line);
    };
    // Compare: both on the same level features.
    if (std::filesystem::exists(measured / "recording.toml")) {
        const auto recording = identification::read_recording(measured);
        result.measured = recording.points.empty()
                              ? from_damping_rows(recording.damping, options.stated)
                              : level_feature_values(recording, options.stated);
    } else {
        result.measured = from_damping_rows(result.measurement.damping, options.stated);
    }
    say("simulating the baseline on the measured points (" +
        std::to_string(result.measurement.selection.sweeps.size()) + " sweeps)");
    bench::CampaignResult baseline;
    if (options.calibration.simulate) {
        baseline = options.calibration.simulate(config, result.measurement.selection,
                                                options.calibration.threads);
    } else {
        bench::CampaignContext context;
        context.threads = options.calibration.threads;
        context.selection = result.measurement.selection;
        context.executor = options.baseline_executor;
        baseline = bench::run_campaign(config, context);
    }
    result.simulated = level_feature_values(baseline.recording, options.stated);
    result.baseline = simulated_features(baseline, result.measurement);

    // Locate: the features beyond the noise and their scaling with the level.
    result.mismatches = locate_mismatch(result.measured, result.simulated);
    for (const auto& m : result.mismatches) say(m.sentence);
    result.bands = band_residuals(result.measurement, result.baseline, result.measured);
    for (const auto& b : result.bands) {
        if (b.beyond_noise) say(b.sentence);
    }
    for (std::size_t p = 0; p < options.drift.size(); ++p) {
        const auto& parameter = options.drift[p];
        say("calibrating " + parameter.path + " level by level");
        LevelRemote level_remote;
        if (options.remote) {
            level_remote = [&options, p](std::size_t level, const std::vector<std::string>& in) {
                std::vector<std::string> inputs;
                inputs.reserve(in.size());
                for (const auto& i : in) inputs.push_back(drift_input_head(p, level) + i);
                return options.remote(inputs);
            };
        }
        result.drifts.push_back(
            drift_test(config, result.measurement, parameter, options.calibration, level_remote));
        say(result.drifts.back().sentence);
    }

    std::vector<std::string> what;
    for (const auto& m : result.mismatches) {
        if (m.beyond_noise) what.push_back(m.arrangement + " " + level_feature_name(m.feature));
    }
    // Hypothesise and test: the catalogue's physics whose signatures match, fitted.
    if (!what.empty() && options.hypotheses > 0) {
        say("fitting the catalogue's physics whose signatures match");
        HypothesisOptions ho;
        ho.candidates = options.hypotheses;
        ho.held_out_levels = options.held_out_levels;
        ho.confirm = options.confirm;
        ho.calibration = options.calibration;
        ho.calibration.simulate = options.hypothesis_simulate ? options.hypothesis_simulate
                                                              : candidate_simulation(config);
        ho.calibration.remote = {};
        ho.calibration.progress = options.progress;
        result.hypotheses = test_hypotheses(config, result.measurement, result.mismatches, ho);
        say(result.hypotheses->sentence);
    }
    for (const auto& b : result.bands) {
        if (b.beyond_noise) {
            what.push_back(b.arrangement + " " + num(b.level_g, 3) + " g FRF " +
                           frf_band_name(b.band));
        }
    }
    for (const auto& d : result.drifts) {
        if (d.drifts) what.push_back(d.parameter.path + " drifts with the level");
    }
    result.mismatch = !what.empty();
    if (!result.mismatch) {
        result.verdict = "no significant mismatch";
    } else {
        std::string list;
        for (std::size_t i = 0; i < what.size(); ++i) list += (i ? "; " : "") + what[i];
        result.verdict = "mismatch beyond the noise: " + list;
        if (result.hypotheses) result.verdict += "; " + result.hypotheses->sentence;
    }
    result.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

void write_diagnosis(const std::filesystem::path& out_dir, const DiagnosisResult& r,
                     const std::string& command_line) {
    std::ostringstream t;
    t << "# shakerbench diagnose: where the simulation and the measurement disagree\n"
      << "# (docs/diagnosis.md).\n[diagnosis]\n"
      << "command = " << toml_string(command_line) << '\n'
      << "measured = " << toml_string(r.measurement.directory.string()) << '\n'
      << "mismatch = " << (r.mismatch ? "true" : "false") << '\n'
      << "verdict = " << toml_string(r.verdict) << '\n'
      << "wall_time_s = " << num(r.wall_time_s, 1, true) << '\n';
    for (const auto& m : r.mismatches) {
        t << "\n[[features]]\n"
          << "arrangement = " << toml_string(m.arrangement) << '\n'
          << "feature = " << toml_string(level_feature_name(m.feature)) << '\n'
          << "beyond_noise = " << (m.beyond_noise ? "true" : "false") << '\n'
          << "chi2 = " << num(m.chi2) << '\n'
          << "levels_g = [";
        for (std::size_t k = 0; k < m.residuals.size(); ++k) {
            t << (k ? ", " : "") << num(m.residuals[k].level, 10);
        }
        t << "]\nresidual = [";  // measured − simulated
        for (std::size_t k = 0; k < m.residuals.size(); ++k) {
            t << (k ? ", " : "") << num(m.residuals[k].residual, 10);
        }
        t << "]\nsigma = [";
        for (std::size_t k = 0; k < m.residuals.size(); ++k) {
            t << (k ? ", " : "") << num(m.residuals[k].sigma, 10);
        }
        t << "]\nscaling = " << toml_string(scaling_shape_name(m.scaling.front().shape)) << '\n'
          << "scaling_exponent = " << num(m.scaling.front().exponent) << '\n'
          << "scaling_coefficient = " << num(m.scaling.front().coefficient) << '\n'
          << "finding = " << toml_string(m.sentence) << '\n';
    }
    for (const auto& d : r.drifts) {
        t << "\n[[drift]]\n"
          << "key = " << toml_string(d.parameter.path) << '\n'
          << "drifts = " << (d.drifts ? "true" : "false") << '\n'
          << "slope_per_g = " << num(d.slope) << '\n'
          << "slope_sigma_per_g = " << num(d.slope_sigma) << '\n'
          << "finding = " << toml_string(d.sentence) << '\n';
    }
    for (const auto& b : r.bands) {
        t << "\n[[bands]]\n"
          << "arrangement = " << toml_string(b.arrangement) << '\n'
          << "level_g = " << num(b.level_g, 10) << '\n'
          << "band = " << toml_string(frf_band_name(b.band)) << '\n'
          << "frequencies = " << b.points << '\n'
          << "chi2_magnitude = " << num(b.chi2_magnitude) << '\n'
          << "chi2_phase = " << num(b.chi2_phase) << '\n'
          << "mean_log_magnitude_ratio = " << num(b.mean_log_ratio) << '\n'
          << "mean_phase_difference_rad = " << num(b.mean_phase_rad) << '\n'
          << "beyond_noise = " << (b.beyond_noise ? "true" : "false") << '\n'
          << "finding = " << toml_string(b.sentence) << '\n';
    }
    if (r.hypotheses) {
        const auto& h = *r.hypotheses;
        t << "\n[hypotheses]\n"
          << "finding = " << toml_string(h.sentence) << '\n'
          << "winner = "
          << toml_string(h.winner >= 0 ? h.fits[static_cast<std::size_t>(h.winner)].name()
                                       : std::string())
          << '\n'
          << "held_out = [";
        for (std::size_t k = 0; k < h.held_out.size(); ++k) {
            t << (k ? ", " : "")
              << toml_string(h.held_out[k].first + " " + num(h.held_out[k].second, 10) + " g");
        }
        t << "]\n";
        t << "pairs_tried = " << (h.pairs_tried ? "true" : "false") << '\n';
        if (h.confirmation) {
            const auto& c = *h.confirmation;
            t << "\n[hypotheses.confirmation]\n"
              << "simulation = " << toml_string(c.simulation) << '\n'
              << "confirmed = " << (c.confirmed ? "true" : "false") << '\n'
              << "finding = " << toml_string(c.sentence) << '\n';
            if (c.error.empty()) {
                t << "misfit_fitted_levels = " << num(c.fit) << '\n'
                  << "baseline_misfit_fitted_levels = " << num(c.baseline_fit) << '\n'
                  << "misfit_held_out = " << num(c.held_out) << '\n'
                  << "baseline_misfit_held_out = " << num(c.baseline_held_out) << '\n';
            }
        }
        for (const auto& c : h.ranking) {
            t << "\n[[candidates]]\n"
              << "name = " << toml_string(c.entry->name) << '\n'
              << "left_out = " << toml_string(c.entry->left_out) << '\n'
              << "score = " << num(c.score) << '\n'
              << "reason = " << toml_string(c.reason) << '\n';
        }
        for (const auto& fit : h.fits) {
            t << "\n[[fits]]\n"
              << "name = " << toml_string(fit.name()) << '\n'
              << "left_out = " << toml_string(fit.left_out()) << '\n'
              << "score = " << num(fit.rank.score) << '\n';
            if (!fit.error.empty()) {
                t << "error = " << toml_string(fit.error) << '\n';
                continue;
            }
            t << "bic = " << num(fit.bic) << '\n'
              << "baseline_bic = " << num(fit.baseline_bic) << '\n'
              << "misfit_fitted_levels = " << num(fit.fit) << '\n'
              << "baseline_misfit_fitted_levels = " << num(fit.baseline_fit) << '\n'
              << "misfit_held_out = " << num(fit.held_out) << '\n'
              << "baseline_misfit_held_out = " << num(fit.baseline_held_out) << '\n'
              << "simulations = " << fit.simulations << '\n';
            for (std::size_t k = 0; k < fit.free.size(); ++k) {
                t << "\n[[fits.parameters]]\n"
                  << "key = " << toml_string(fit.free[k].path) << '\n'
                  << "value = " << num(fit.values[k], 10) << '\n';
                if (k < fit.findings.size()) {
                    t << "lo95 = " << num(fit.findings[k].lo95, 10) << '\n'
                      << "hi95 = " << num(fit.findings[k].hi95, 10) << '\n'
                      << "identifiable = " << (fit.findings[k].identifiable ? "true" : "false")
                      << '\n';
                }
            }
        }
    }
    std::ostringstream md;
    md << "# Diagnosis report\n\nCommand: `" << command_line << "`\n\n"
       << "Measured: `" << r.measurement.directory.string() << "`\n\n"
       << "**Verdict: " << r.verdict << ".**\n\n## Features per level\n\n";
    for (const auto& m : r.mismatches) md << "- " << m.sentence << ".\n";
    if (!r.bands.empty()) {
        md << "\n## The FRF per band\n\n";
        int within = 0;
        for (const auto& b : r.bands) {
            if (b.beyond_noise) {
                md << "- " << b.sentence << ".\n";
            } else {
                ++within;
            }
        }
        const int all = static_cast<int>(r.bands.size());
        if (within == all) {
            md << "All " << all << " bands";
        } else if (within > 0) {
            md << "The " << within << " other band" << (within > 1 ? "s" : "") << " of " << all;
        }
        if (within > 0) {
            md << " (each level below, around and above its resonance) agree"
               << (within > 1 ? "" : "s") << " within the noise.\n";
        }
    }
    if (!r.drifts.empty()) {
        md << "\n## Values calibrated level by level\n\n";
        for (const auto& d : r.drifts) md << "- " << d.sentence << ".\n";
    }
    if (r.hypotheses) {
        const auto& h = *r.hypotheses;
        md << "\n## The physics left out\n\n"
           << h.sentence << ".\n\n"
           << "| candidate | signature match |\n|---|---|\n";
        for (const auto& c : h.ranking) {
            md << "| " << c.entry->name << " | " << num(c.score) << ": " << c.reason << " |\n";
        }
        md << "\n| fitted | BIC (baseline → fitted) | misfit, fitted levels | misfit, held out | "
              "fitted values |\n|---|---|---|---|---|\n";
        for (const auto& fit : h.fits) {
            md << "| " << fit.name() << " | ";
            if (!fit.error.empty()) {
                md << fit.error << " | | | |\n";
                continue;
            }
            md << num(fit.baseline_bic) << " → " << num(fit.bic) << " | " << num(fit.baseline_fit)
               << " → " << num(fit.fit) << " | " << num(fit.baseline_held_out) << " → "
               << num(fit.held_out) << " | ";
            for (std::size_t k = 0; k < fit.free.size(); ++k) {
                md << (k ? ", " : "") << "`" << fit.free[k].path << "` = " << num(fit.values[k]);
            }
            md << " |\n";
        }
        md << "\nHeld out (not fitted, predicted): ";
        for (std::size_t k = 0; k < h.held_out.size(); ++k) {
            md << (k ? ", " : "") << h.held_out[k].first << " " << num(h.held_out[k].second)
               << " g";
        }
        if (h.held_out.empty()) md << "none (fewer than three levels)";
        md << ".\n";
        if (h.confirmation) {
            md << "\nThe winner, fitted on the prediction, simulated by the full model: "
               << h.confirmation->sentence << ".\n";
        }
        if (h.winner >= 0) md << "\nThe improved config: `improved.toml`.\n";
    }
    create_directories_for_writing(out_dir);
    const auto plots = write_diagnosis_plots(out_dir, r);
    md << "\n## Plots\n\n";
    for (const auto& svg : plots.svg) md << "- `" << svg.filename().string() << "`\n";
    if (!plots.message.empty()) md << "\n" << plots.message << "\n";
    write_file_atomically(out_dir / "diagnosis.toml", t.str());
    write_file_atomically(out_dir / "report.md", md.str());
    if (r.hypotheses && r.hypotheses->winner >= 0) {
        const auto& w = r.hypotheses->fits[static_cast<std::size_t>(r.hypotheses->winner)];
        write_file_atomically(out_dir / "improved.toml",
                              "# The config with " + w.left_out() + " at its fitted values (" +
                                  command_line + ")\n" + bench::resolved_config_toml(w.improved));
    }
}

}  // namespace sb::correlation

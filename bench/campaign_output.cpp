// Writing a finished campaign.
#include "bench/campaign_output.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "bench/campaign_plan.hpp"
#include "bench/resolved_config.hpp"
#include "bench/transient_run.hpp"
#include "config/value.hpp"
#include "core/significant_text.hpp"
#include "core/text_file.hpp"
#include "identification/plots.hpp"
#include "identification/recording_io.hpp"
#include "identification/uff58.hpp"

namespace sb::bench {
namespace {

namespace fs = std::filesystem;
namespace id = identification;

std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

void write_provenance(const CampaignConfig& config, const CampaignResult& result,
                      const RecordingDirectory& directory) {
    std::ostringstream text;
    text << "# How this recording was made. Not read back by ShakerBench.\n";
    text << "[provenance]\n";
    text << "version = " << config::quoted(SB_VERSION) << '\n';
    text << "date = " << config::quoted(utc_now()) << '\n';
    text << "ranks = " << result.ranks << '\n';
    text << "threads = " << result.threads << '\n';
    text << "config = " << config::quoted(config.source) << '\n';
    text << "config_hash = " << config::quoted(result.config_hash) << '\n';
    text << "command = " << config::quoted(directory.command_line) << "\n\n";
    for (const auto& sweep : result.sweeps) {
        text << "[sweeps." << config::quoted(sweep.key) << "]\n";
        text << "first_mode_hz = " << significant_text(sweep.first_mode_hz) << '\n';
        text << "frequencies_hz = [";
        for (std::size_t i = 0; i < sweep.frequencies_hz.size(); ++i) {
            text << (i ? ", " : "") << significant_text(sweep.frequencies_hz[i]);
        }
        text << "]\n";
        text << "settings = [";
        for (std::size_t i = 0; i < sweep.settings.size(); ++i) {
            text << (i ? ", " : "") << config::quoted(sweep.settings[i]);
        }
        text << "]\n\n";
    }
    write_file_atomically(directory.out_dir / "provenance.toml", text.str());
}

void write_control_log(const CampaignResult& result, const fs::path& out_dir) {
    std::string text =
        "arrangement,level_g,frequency_hz,status,periods,updates,amplitude_final,rms_final,"
        "amplitudes_tried,rms_per_period\n";
    for (const auto& sweep : result.sweeps) {
        for (const auto& line : sweep.control_log) text += line + "\n";
    }
    write_file_atomically(out_dir / "control.csv", text);
}

void write_energy_log(const CampaignConfig& config, const CampaignResult& result,
                      const fs::path& out_dir) {
    std::string text = energy_csv_header(config.campaign.output.energy_layers);
    for (const auto& sweep : result.sweeps) {
        for (const auto& line : sweep.energy_log) text += line + "\n";
    }
    write_file_atomically(out_dir / "energy.csv", text);
}

/// Random tests: random/<sweep>.csv, each line's spectra, H1 and coherence.
void write_random_spectra(const CampaignResult& result, const fs::path& out_dir) {
    for (const auto& sweep : result.sweeps) {
        if (sweep.random_spectra.empty()) continue;
        const fs::path dir = out_dir / "random";
        create_directories_for_writing(dir);
        std::string text;
        for (const auto& line : sweep.random_spectra) text += line + "\n";
        write_file_atomically(dir / (sweep.key + ".csv"), text);
    }
}

/// A run from rest: transient/<sweep>.csv (the time histories), transient/<sweep>_envelope.csv
/// (each channel's lowest and highest value per period) and, with plots, one SVG per sweep
/// of every channel's envelope against time (the reference's left out: it is the drive).
void write_transients(const CampaignConfig& config, const CampaignResult& result,
                      const fs::path& out_dir) {
    id::PlotResult plots;
    std::string script =
        "set terminal svg size 900,900 dynamic background rgb 'white'\n"
        "set datafile separator ','\nset key off\nset grid\n";
    for (const auto& sweep : result.sweeps) {
        if (sweep.transient_channels.empty()) continue;
        const fs::path dir = out_dir / "transient";
        create_directories_for_writing(dir);
        std::string series = transient_series_header(sweep.transient_channels) + "\n";
        for (const auto& line : sweep.transient_series) series += line + "\n";
        write_file_atomically(dir / (sweep.key + ".csv"), series);
        std::string envelope = transient_envelope_header(sweep.transient_channels) + "\n";
        for (const auto& line : sweep.transient_envelope) envelope += line + "\n";
        const std::string envelope_file = sweep.key + "_envelope.csv";
        write_file_atomically(dir / envelope_file, envelope);

        const std::size_t n = sweep.transient_channels.size();
        const std::string svg = id::file_safe(sweep.key) + ".svg";
        plots.svg.push_back(dir / svg);
        script += "set output " + id::gnuplot_quoted(svg) + "\nset multiplot layout " +
                  std::to_string(n - 1) + ",1 title " +
                  id::gnuplot_quoted(sweep.arrangement + " " + sweep.key +
                                     ": lowest and highest value per period") +
                  "\n";
        for (std::size_t c = 1; c < n; ++c) {
            const std::string low = std::to_string(3 + c);
            const std::string high = std::to_string(3 + n + c);
            script += "set ylabel " + id::gnuplot_quoted(sweep.transient_channels[c]) + "\n";
            script += c + 1 == n ? "set xlabel 'time [s]'\n" : "unset xlabel\n";
            script += "plot " + id::gnuplot_quoted(envelope_file) + " skip 1 using 2:" + low +
                      " with lines lc rgb '#1f77b4', '' skip 1 using 2:" + high +
                      " with lines lc rgb '#1f77b4'\n";
        }
        script += "unset multiplot\n";
    }
    if (plots.svg.empty() || !config.campaign.output.plots) return;
    plots.script = out_dir / "transient" / "plots.gp";
    write_file_atomically(plots.script, script);
    id::render_gnuplot(true, plots);
    if (!plots.message.empty()) std::fprintf(stderr, "shakerbench: %s\n", plots.message.c_str());
}

}  // namespace

std::string energy_csv_header(int layers) {
    std::string header =
        "arrangement,level_g,frequency_hz,damper,filling,wall_work_j,normal_damping_j,friction_j,"
        "rolling_j,kinetic_j";
    for (int k = 0; k < layers; ++k) header += ",layer_" + std::to_string(k + 1) + "_j";
    for (int k = 0; k < layers; ++k) header += ",layer_" + std::to_string(k + 1) + "_kinetic_j";
    return header + "\n";
}

void write_campaign_output(const CampaignConfig& config, const CampaignResult& result,
                           const RecordingDirectory& directory) {
    const fs::path& out_dir = directory.out_dir;
    create_directories_for_writing(out_dir);
    id::write_recording(out_dir, result.recording);
    if (result.recording.damping.empty()) {
        // No estimate resolved: the file is there all the same, with its header.
        id::write_damping_csv(out_dir / "damping.csv", {});
    }
    // A controlled level in g, a fixed drive's amplitude in its own unit.
    const std::string unit = level_unit(config);
    // A run from rest has no levels: no transfer function to write.
    if (config.campaign.output.uff && !result.levels.empty()) {
        std::vector<id::Uff58Record> records;
        for (const auto& level : result.levels) {
            char description[128];
            std::snprintf(description, sizeof description, "%s %.6g %s", level.arrangement.c_str(),
                          level.level_g, unit.c_str());
            records.push_back(id::to_uff58(level.frf, description));
        }
        id::write_uff58(out_dir / "frf.uff", records);
    }
    write_control_log(result, out_dir);
    if (config.campaign.seeds > 1) {
        // Each filling's own estimates, beside damping.csv's mean and scatter.
        id::write_damping_csv(out_dir / "damping_fillings.csv",
                              id::filling_damping_rows(result.levels));
    }
    if (config.campaign.output.energy) write_energy_log(config, result, out_dir);
    if (config.campaign.transient.on()) write_transients(config, result, out_dir);
    if (config.campaign.random.on()) write_random_spectra(result, out_dir);
    write_file_atomically(out_dir / "config.toml", directory.config_text);
    write_file_atomically(out_dir / "config.resolved.toml", resolved_config_toml(config));
    write_provenance(config, result, directory);
    if (config.campaign.output.plots) {
        id::PlotOptions plot_options;
        plot_options.level_unit = unit;
        if (config.campaign.drive.fixed()) {
            plot_options.level_axis = "fixed drive amplitude [" + unit + " peak]";
        }
        const auto plots = id::write_plots(out_dir, result.levels, plot_options);
        if (!plots.message.empty())
            std::fprintf(stderr, "shakerbench: %s\n", plots.message.c_str());
    }
}

}  // namespace sb::bench

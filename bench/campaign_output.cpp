// Writing a finished campaign.
#include "bench/campaign_output.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "bench/resolved_config.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "identification/damping_curve.hpp"
#include "identification/recording_io.hpp"
#include "identification/uff58.hpp"

namespace sb::bench {
namespace {

namespace fs = std::filesystem;
namespace id = identification;

id::Recording make_recording(const CampaignOutput& output) {
    const CampaignConfig& config = *output.config;
    const auto& excitation = config.structure.excitation;
    id::Recording rec;
    rec.info.name = config.name;
    rec.info.kind = "simulated";
    const bool force = excitation.kind == structure::ExcitationSpec::Kind::force;
    rec.info.excitation = force ? "force" : "base";
    rec.info.description = config.description;
    if (force) {
        rec.channels.push_back(
            {"force", "force", "N", excitation.point, id::ChannelRole::reference});
    } else {
        rec.channels.push_back(
            {"base_acc", "acceleration", "m/s^2", excitation.support, id::ChannelRole::reference});
    }
    for (std::size_t i = 0; i < output.channel_points.size(); ++i) {
        rec.channels.push_back({"acc_" + output.channel_points[i], "acceleration", "m/s^2",
                                output.channel_points[i],
                                i == 0 ? id::ChannelRole::control : id::ChannelRole::response});
    }
    for (const auto& sweep : output.sweeps) {
        rec.points.insert(rec.points.end(), sweep.rows.begin(), sweep.rows.end());
    }
    return rec;
}

std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

std::string toml_string(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

void write_provenance(const CampaignOutput& output) {
    std::ostringstream text;
    text << "# How this recording was made. Not read back by ShakerBench.\n";
    text << "[provenance]\n";
    text << "version = " << toml_string(SB_VERSION) << '\n';
    text << "date = " << toml_string(utc_now()) << '\n';
    text << "threads = " << output.threads << '\n';
    text << "config = " << toml_string(output.config->source) << '\n';
    text << "command = " << toml_string(output.options->command_line) << "\n\n";
    for (const auto& sweep : output.sweeps) {
        text << "[sweeps." << toml_string(sweep.key) << "]\n";
        char f1[64];
        std::snprintf(f1, sizeof f1, "%.9g", sweep.first_mode_hz);
        text << "first_mode_hz = " << f1 << '\n';
        text << "frequencies_hz = [";
        for (std::size_t i = 0; i < sweep.frequencies_hz.size(); ++i) {
            std::snprintf(f1, sizeof f1, "%.9g", sweep.frequencies_hz[i]);
            text << (i ? ", " : "") << f1;
        }
        text << "]\n";
        text << "settings = [";
        for (std::size_t i = 0; i < sweep.log.size(); ++i) {
            text << (i ? ", " : "") << toml_string(sweep.log[i]);
        }
        text << "]\n\n";
    }
    write_file_atomically(output.options->out_dir / "provenance.toml", text.str());
}

void write_control_log(const CampaignOutput& output) {
    std::string text =
        "arrangement,level_g,frequency_hz,status,periods,updates,amplitude_final,rms_final,"
        "amplitudes_tried,rms_per_period\n";
    for (const auto& sweep : output.sweeps) {
        for (const auto& line : sweep.control_log) {
            text += line + "\n";
        }
    }
    write_file_atomically(output.options->out_dir / "control.csv", text);
}

/// SVG plots through gnuplot: FRF magnitude and phase per level, damping and natural
/// frequency versus level. Skipped quietly when gnuplot is not installed.
void write_plots(const fs::path& out_dir, const std::vector<id::LevelIdentification>& levels) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0 || levels.empty()) {
        return;
    }
    const fs::path data = out_dir / "plots";
    fs::create_directories(data);
    std::map<std::string, std::vector<const id::LevelIdentification*>> by_arrangement;
    for (const auto& level : levels) {
        by_arrangement[level.arrangement].push_back(&level);
    }
    // gnuplot skips "NaN" points: an estimate that failed leaves a gap, not a zero.
    const double kMissing = std::numeric_limits<double>::quiet_NaN();
    std::ostringstream script;
    script << "set terminal svg size 900,600 dynamic\nset grid\nset key outside right\n";
    for (const auto& [arrangement, items] : by_arrangement) {
        std::ofstream frf(data / (arrangement + "-frf.dat"));
        std::ofstream curve(data / (arrangement + "-damping.dat"));
        for (const auto* level : items) {
            frf << "# level " << level->level_g << " g\n";
            for (std::size_t i = 0; i < level->frf.frequency_hz.size(); ++i) {
                const auto v = level->frf.value[i];
                frf << level->frf.frequency_hz[i] << ' ' << std::abs(v) << ' '
                    << std::arg(v) * 180.0 / 3.14159265358979323846 << '\n';
            }
            frf << "\n\n";
            curve << level->level_g << ' '
                  << (level->half_power.ok() ? level->half_power.damping_ratio * 100.0 : kMissing)
                  << ' '
                  << (level->circle_fit.ok() ? level->circle_fit.damping_ratio * 100.0 : kMissing)
                  << ' '
                  << (level->half_power.ok() ? level->half_power.natural_frequency_hz : kMissing)
                  << '\n';
        }
        const std::string f = (data / (arrangement + "-frf.dat")).string();
        const std::string d = (data / (arrangement + "-damping.dat")).string();
        script << "set output '" << (out_dir / (arrangement + "-frf.svg")).string() << "'\n"
               << "set multiplot layout 2,1 title 'Accelerance, " << arrangement << "'\n"
               << "set ylabel '|A| [m/s^2/N]'\nset logscale y\n"
               << "plot for [i=0:" << items.size() - 1 << "] '" << f
               << "' index i using 1:2 with linespoints title columnheader(1)\n"
               << "unset logscale y\nset ylabel 'phase [deg]'\nset xlabel 'frequency [Hz]'\n"
               << "plot for [i=0:" << items.size() - 1 << "] '" << f
               << "' index i using 1:3 with linespoints notitle\nunset multiplot\n"
               << "unset xlabel\n"
               << "set output '" << (out_dir / (arrangement + "-damping.svg")).string() << "'\n"
               << "set multiplot layout 2,1 title 'Damping and natural frequency, " << arrangement
               << "'\nset ylabel 'damping ratio [%]'\n"
               << "plot '" << d << "' using 1:2 with linespoints title 'half-power', '" << d
               << "' using 1:3 with linespoints title 'circle fit'\n"
               << "set ylabel 'natural frequency [Hz]'\nset xlabel 'level [g RMS]'\n"
               << "plot '" << d << "' using 1:4 with linespoints title 'half-power'\n"
               << "unset multiplot\nunset xlabel\n";
    }
    const fs::path script_file = data / "plots.gp";
    std::ofstream(script_file) << script.str();
    const std::string command = "gnuplot '" + script_file.string() + "' 2>/dev/null";
    if (std::system(command.c_str()) != 0) {
        std::fprintf(stderr, "shakerbench: gnuplot failed on %s; plots skipped\n",
                     script_file.c_str());
    }
}

}  // namespace

std::string write_series(const fs::path& out_dir, const std::string& key, int index,
                         const CoupledSpecimen& specimen, const SpecimenPlant& plant,
                         const control::PointResult& result) {
    id::TimeHistory history;
    history.channels = specimen.channel_names();
    history.columns.resize(history.channels.size());
    const double period_s = 1.0 / specimen.frequency_hz();
    for (int p = result.window_begin; p < result.window_end; ++p) {
        const auto& period = plant.periods()[static_cast<std::size_t>(p)];
        const std::size_t samples = period.series.front().size();
        for (std::size_t k = 0; k < samples; ++k) {
            history.time_s.push_back((p - result.window_begin) * period_s +
                                     (static_cast<double>(k) + 1.0) * period_s /
                                         static_cast<double>(samples));
            for (std::size_t c = 0; c < history.channels.size(); ++c) {
                history.columns[c].push_back(period.series[c][k]);
            }
        }
    }
    const std::string relative = "series/" + key + "_" + std::to_string(index) + ".csv";
    fs::create_directories(out_dir / "series");
    id::write_time_history_csv(out_dir / relative, history);
    return relative;
}

void write_campaign_output(const CampaignOutput& output) {
    const fs::path out_dir = output.options->out_dir;
    id::Recording rec = make_recording(output);
    id::IdentifyOptions identify;
    identify.response_channel = "acc_" + output.channel_points.front();
    const auto levels = id::identify_recording(rec, identify);
    rec.damping = id::damping_rows(levels);
    id::write_recording(out_dir, rec);

    if (output.config->campaign.output.uff) {
        std::vector<id::Uff58Record> records;
        for (const auto& level : levels) {
            char description[128];
            std::snprintf(description, sizeof description, "%s %.6g g", level.arrangement.c_str(),
                          level.level_g);
            records.push_back(id::to_uff58(level.frf, description));
        }
        id::write_uff58(out_dir / "frf.uff", records);
    }
    write_control_log(output);
    write_file_atomically(out_dir / "config.toml", output.options->config_text);
    write_file_atomically(out_dir / "config.resolved.toml",
                          resolved_config_toml(*output.config, output.options->config_text));
    write_provenance(output);
    if (output.config->campaign.output.plots) {
        write_plots(out_dir, levels);
    }
}

}  // namespace sb::bench

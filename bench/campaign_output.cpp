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
#include "core/text_file.hpp"
#include "identification/damping_curve.hpp"
#include "identification/plots.hpp"
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
    text << "config_hash = " << toml_string(output.config_hash) << '\n';
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
    write_file_atomically(out_dir / "config.resolved.toml", resolved_config_toml(*output.config));
    write_provenance(output);
    if (output.config->campaign.output.plots) {
        const auto plots = id::write_plots(out_dir, levels);
        if (!plots.message.empty())
            std::fprintf(stderr, "shakerbench: %s\n", plots.message.c_str());
    }
}

}  // namespace sb::bench

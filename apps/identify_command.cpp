// The identify subcommand: reads a recording directory or a UFF58 file of FRFs, prints a table
// of natural frequency, damping and loss factor per arrangement, level and method, and writes
// damping.csv and plots.
#include "apps/identify_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include "config/errors.hpp"
#include "core/text_file.hpp"
#include "identification/damping_curve.hpp"
#include "identification/file_error.hpp"
#include "identification/plots.hpp"
#include "identification/recording_io.hpp"
#include "identification/uff58.hpp"

namespace sb::apps {
namespace {

namespace fs = std::filesystem;
namespace id = sb::identification;

using config::kExitBadInput;

struct IdentifyArgs {
    std::string input;
    std::string out;  ///< empty: DIR/identified, or FILE's directory/<stem>-identified
    std::string channel;
    double background = 0.0;
    double mass = 0.0;
    bool no_residual = false;
    bool no_plots = false;
    std::string closest = "skip";  ///< skip | use (id::ClosestPolicy)
};

/// A command-line value that cannot be used with this input: exit 2 with the message.
struct BadArgument : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void print_row(const std::string& arrangement, double level_g, const char* method,
               const id::ModalEstimate& e) {
    if (e.ok()) {
        std::printf("%-12s %8.4g  %-18s %12.5f %12.6f %12.6f %10.3g %9.3g\n", arrangement.c_str(),
                    level_g, method, e.natural_frequency_hz, e.damping_ratio, e.loss_factor(),
                    e.damping_spread, e.residual_ratio);
    } else {
        std::printf("%-12s %8.4g  %-18s %s: %s\n", arrangement.c_str(), level_g, method,
                    std::string(id::to_string(e.status)).c_str(), e.message.c_str());
    }
}

/// Frequencies as "6.301, 6.412 Hz" (6 significant digits, enough to tell grid points apart).
std::string frequency_list(const std::vector<double>& frequency_hz) {
    std::string text;
    for (double f : frequency_hz) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.6g", f);
        text += (text.empty() ? "" : ", ") + std::string(buf);
    }
    return text + " Hz";
}

/// One line per level whose points with status `closest` were left out or, with
/// `--closest use`, kept: such points never held the target level, and a reader of the table
/// must know whether they are in it.
void print_closest(const id::LevelIdentification& l) {
    const auto line = [&l](const std::vector<double>& f, const char* what) {
        if (f.empty()) return;
        std::printf("%s %.6g g: %zu point%s with status %s %s (%s)\n", l.arrangement.c_str(),
                    l.level_g, f.size(), f.size() == 1 ? "" : "s",
                    id::flagged_status_text(l).c_str(), what, frequency_list(f).c_str());
    };
    line(l.skipped_hz, "left out of the fits");
    line(l.closest_used_hz, "kept in the fits by --closest use");
}

/// Every FRF record of a UFF58 file is one "level" (numbered from 0), named by ID line 1.
std::vector<id::LevelIdentification> identify_uff(const fs::path& input, const IdentifyArgs& args,
                                                  const id::IdentifyOptions& options) {
    const auto records = id::read_uff58(input);
    std::vector<id::LevelIdentification> levels;
    std::set<std::string> responses;
    double index = 0.0;
    for (const auto& r : records) {
        if ((r.function_type != 4 && r.function_type != 5) || !r.is_complex()) continue;
        responses.insert(r.response_name);
        if (!args.channel.empty() && r.response_name != args.channel) continue;
        // W/T needs response per newton: an FRF (type 4) over an excitation force (type 13).
        const bool force_reference = r.function_type == 4 && r.denominator.data_type == 13;
        if (args.mass > 0.0 && !force_reference) {
            throw BadArgument("--mass: record '" + r.id[0] +
                              "' is not an FRF over an excitation force (function type " +
                              std::to_string(r.function_type) + ", denominator data type " +
                              std::to_string(r.denominator.data_type) + ")");
        }
        std::string name = r.id[0];  // a CSV cell: no commas
        std::replace(name.begin(), name.end(), ',', ';');
        levels.push_back(id::identify_frf(name, index++, id::to_frf(r), options, force_reference));
        levels.back().channel = r.response_name;
    }
    if (levels.empty() && !args.channel.empty() && !responses.empty()) {
        std::string names;
        for (const auto& n : responses) names += (names.empty() ? "" : ", ") + n;
        throw BadArgument("--channel '" + args.channel + "': no FRF record of " + input.string() +
                          " has this response name (record 6; found: " + names + ")");
    }
    if (levels.empty()) {
        throw id::FileError(input.string(), 0, 0, "no complex FRF dataset 58 in the file");
    }
    return levels;
}

std::vector<id::LevelIdentification> identify_directory(const fs::path& input,
                                                        const IdentifyArgs& args,
                                                        const id::IdentifyOptions& options) {
    const id::Recording rec = id::read_recording(input);
    if (rec.points.empty()) {
        throw BadArgument(input.string() +
                          " has no points.csv rows (only damping.csv): nothing to identify");
    }
    const std::size_t ref = rec.reference_index();
    if (args.mass > 0.0 &&
        (rec.info.excitation != "force" || rec.channels[ref].quantity != "force")) {
        throw BadArgument("--mass needs force excitation with a force reference channel; " +
                          (input / "recording.toml").string() + " has excitation '" +
                          rec.info.excitation + "' and reference '" + rec.channels[ref].name +
                          "' (" + rec.channels[ref].quantity + ")");
    }
    try {
        return id::identify_recording(rec, options);
    } catch (const std::invalid_argument& e) {
        throw BadArgument(std::string(args.channel.empty() ? "" : "--channel: ") +
                          (input / "recording.toml").string() + ": " + e.what());
    }
}

fs::path output_directory(const fs::path& input, const IdentifyArgs& args, bool directory) {
    if (args.out.empty()) {
        return directory ? input / "identified"
                         : input.parent_path() / (input.stem().string() + "-identified");
    }
    const fs::path out(args.out);
    // Never write into the recording: its damping.csv (possibly its only data) would go.
    if (directory && fs::exists(out) && fs::equivalent(out, input)) {
        throw BadArgument("--out " + args.out + " is the recording directory " + input.string() +
                          ": writing damping.csv there would overwrite its input; choose another "
                          "directory (default: " +
                          (input / "identified").string() + ")");
    }
    return out;
}

int run(const IdentifyArgs& args) {
    const fs::path input(args.input);
    if (!fs::exists(input)) throw id::FileError(input.string(), 0, 0, "no such file or directory");
    const bool directory = fs::is_directory(input);
    const fs::path out = output_directory(input, args, directory);
    id::IdentifyOptions options;
    options.response_channel = args.channel;
    options.background_damping_ratio = args.background;
    options.effective_mass_kg = args.mass;
    options.residual.compensate = !args.no_residual;
    options.closest = args.closest == "use" ? id::ClosestPolicy::use : id::ClosestPolicy::skip;
    const auto levels =
        directory ? identify_directory(input, args, options) : identify_uff(input, args, options);

    std::printf("%-12s %8s  %-18s %12s %12s %12s %10s %9s\n", "arrangement",
                directory ? "level_g" : "record", "method", "f_n [Hz]", "zeta [-]", "eta [-]",
                "spread", "residual");
    for (const auto& l : levels) {
        print_row(l.arrangement, l.level_g, "half-power", l.half_power);
        print_row(l.arrangement, l.level_g, "circle-fit", l.circle_fit);
        print_row(l.arrangement, l.level_g, "rational-fraction", l.rational_fraction);
        if (!std::isnan(l.specific_damping_capacity)) {
            std::printf("%-12s %8.4g  %-18s %12.5f W/T = %.6g\n", l.arrangement.c_str(), l.level_g,
                        "energy", l.capacity_frequency_hz, l.specific_damping_capacity);
        }
        print_closest(l);
    }
    fs::create_directories(out);
    const auto csv = out / "damping.csv";
    id::write_damping_csv(csv, id::damping_rows(levels));
    std::printf("wrote %s\n", csv.string().c_str());
    if (!args.no_plots) {
        id::PlotOptions plot_options;
        if (!directory) plot_options.level_axis = "record of the UFF file";
        const auto plots = id::write_plots(out, levels, plot_options);
        if (plots.rendered) {
            for (const auto& svg : plots.svg) std::printf("wrote %s\n", svg.string().c_str());
        } else {
            std::printf("%s\n", plots.message.c_str());
        }
    }
    return 0;
}

}  // namespace

void register_identify_command(CLI::App& app, int& exit_code) {
    auto args = std::make_shared<IdentifyArgs>();
    CLI::App* sub = app.add_subcommand(
        "identify", "Natural frequency and damping per arrangement, level and method");
    sub->add_option("input", args->input, "recording directory or UFF58 file of FRFs")->required();
    sub->add_option("--out", args->out,
                    "directory for damping.csv and plots (default: DIR/identified, or "
                    "<file>-identified beside a UFF file; never the recording itself)");
    sub->add_option("--channel", args->channel,
                    "response channel (default: the control channel, else the first response); "
                    "for a UFF file the response name of record 6");
    sub->add_option("--background", args->background,
                    "damping ratio of the bare rig, subtracted from every estimate [-]")
        ->check(CLI::Range(0.0, 1.0));
    sub->add_option("--mass", args->mass,
                    "effective mass at the response point [kg] for W/T (paper 003); needs "
                    "force excitation with a force reference")
        ->check(CLI::PositiveNumber);
    sub->add_flag("--no-residual", args->no_residual,
                  "do not fit and subtract the residual of other modes before the estimates");
    sub->add_option("--closest", args->closest,
                    "points whose controller ended in status closest (it never held the target "
                    "level): skip leaves them out of the FRF and the fits, use keeps them; "
                    "either way identify names them")
        ->check(CLI::IsMember({"skip", "use"}))
        ->capture_default_str();
    sub->add_flag("--no-plots", args->no_plots, "write no plot files");
    sub->callback([args, &exit_code]() {
        try {
            exit_code = run(*args);
        } catch (const id::FileError& e) {
            std::cerr << e.what() << '\n';
            exit_code = kExitBadInput;
        } catch (const BadArgument& e) {
            std::cerr << "identify: " << e.what() << '\n';
            exit_code = kExitBadInput;
        } catch (const std::invalid_argument& e) {
            std::cerr << "identify: " << e.what() << '\n';
            exit_code = kExitBadInput;
        } catch (const fs::filesystem_error& e) {
            std::cerr << "identify: " << e.what() << '\n';
            exit_code = kExitBadInput;
        } catch (const FileWriteError& e) {
            // Not bad input: the same command succeeds once the disk has room.
            std::cerr << "identify: " << e.what() << '\n';
            exit_code = config::kExitFailure;
        }
    });
}

}  // namespace sb::apps

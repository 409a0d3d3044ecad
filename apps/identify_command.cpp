// The identify subcommand: reads a recording directory or a UFF58 file of FRFs, prints a table
// of natural frequency and damping per arrangement, level and method, and writes damping.csv.
#include "apps/identify_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "identification/damping_curve.hpp"
#include "identification/file_error.hpp"
#include "identification/recording_io.hpp"
#include "identification/uff58.hpp"

namespace sb::apps {
namespace {

namespace id = sb::identification;

struct IdentifyArgs {
    std::string input;
    std::string out = ".";
    std::string channel;
    double background = 0.0;
    double mass = 0.0;
};

void print_row(const std::string& arrangement, double level_g, const char* method,
               const id::ModalEstimate& e) {
    if (e.ok()) {
        std::printf("%-12s %8.4g  %-18s %12.5f %12.6f %10.3g\n", arrangement.c_str(), level_g,
                    method, e.natural_frequency_hz, e.damping_ratio, e.damping_spread);
    } else {
        std::printf("%-12s %8.4g  %-18s %s: %s\n", arrangement.c_str(), level_g, method,
                    std::string(id::to_string(e.status)).c_str(), e.message.c_str());
    }
}

int run(const IdentifyArgs& args) {
    const std::filesystem::path input(args.input);
    std::vector<id::LevelIdentification> levels;
    id::IdentifyOptions options;
    options.response_channel = args.channel;
    options.background_damping_ratio = args.background;
    options.effective_mass_kg = args.mass;
    if (std::filesystem::is_directory(input)) {
        levels = id::identify_recording(id::read_recording(input), options);
    } else {
        // A UFF58 file: every FRF record is one "level", named by its first ID line.
        const auto records = id::read_uff58(input);
        double index = 0.0;
        for (const auto& r : records) {
            if (r.function_type != 4 && r.function_type != 5) continue;
            if (!r.is_complex()) continue;
            id::LevelIdentification l;
            l.arrangement = r.id[0];  // a CSV cell: no commas
            std::replace(l.arrangement.begin(), l.arrangement.end(), ',', ';');
            l.level_g = index++;
            l.frf = id::to_frf(r);
            l.half_power = id::half_power(l.frf, options.half_power_form);
            l.circle_fit = id::circle_fit(l.frf, options.circle);
            l.rational_fraction = id::rational_fraction_fit(l.frf, options.rational_fraction);
            levels.push_back(std::move(l));
        }
        if (levels.empty())
            throw id::FileError(input.string(), 0, 0, "no FRF dataset 58 in the file");
    }
    std::printf("%-12s %8s  %-18s %12s %12s %10s\n", "arrangement", "level_g", "method", "f_n [Hz]",
                "zeta [-]", "spread");
    for (const auto& l : levels) {
        print_row(l.arrangement, l.level_g, "half-power", l.half_power);
        print_row(l.arrangement, l.level_g, "circle-fit", l.circle_fit);
        print_row(l.arrangement, l.level_g, "rational-fraction", l.rational_fraction);
        if (!std::isnan(l.specific_damping_capacity)) {
            std::printf("%-12s %8.4g  %-18s %12.5f W/T = %.6g\n", l.arrangement.c_str(), l.level_g,
                        "energy", l.capacity_frequency_hz, l.specific_damping_capacity);
        }
    }
    std::filesystem::create_directories(args.out);
    const auto out = std::filesystem::path(args.out) / "damping.csv";
    id::write_damping_csv(out, id::damping_rows(levels));
    std::printf("wrote %s\n", out.string().c_str());
    return 0;
}

}  // namespace

void register_identify_command(CLI::App& app, int& exit_code) {
    auto args = std::make_shared<IdentifyArgs>();
    CLI::App* sub = app.add_subcommand(
        "identify", "Natural frequency and damping per arrangement, level and method");
    sub->add_option("input", args->input, "recording directory or UFF58 file of FRFs")->required();
    sub->add_option("--out", args->out, "directory for damping.csv (default: current directory)");
    sub->add_option("--channel", args->channel,
                    "response channel (default: the control channel, else the first response)");
    sub->add_option("--background", args->background,
                    "rig background damping ratio to subtract [-]");
    sub->add_option("--mass", args->mass,
                    "effective mass at the response point [kg] for W/T (paper 003)");
    sub->callback([args, &exit_code]() {
        try {
            exit_code = run(*args);
        } catch (const id::FileError& e) {
            std::cerr << e.what() << '\n';
            exit_code = 2;
        } catch (const std::invalid_argument& e) {
            std::cerr << "identify: " << e.what() << '\n';
            exit_code = 2;
        }
    });
}

}  // namespace sb::apps

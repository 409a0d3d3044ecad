// `shakerbench modes`: natural frequencies, modal and effective masses, and mode shapes at
// the named points of a config's structure.
#include "modes_command.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "config/errors.hpp"
#include "load_config.hpp"
#include "structure/linear_model.hpp"
#include "structure/matrix_market.hpp"
#include "structure/modal_analysis.hpp"

namespace sb::apps {
namespace {

struct ModesOptions {
    std::string config;
    std::string out_dir = ".";
    int count = 0;
    std::vector<std::string> overrides;
};

void write_shapes_csv(const std::filesystem::path& file, const structure::LinearModel& model,
                      const structure::ModalBasis& basis) {
    std::ofstream out(file);
    if (!out) {
        throw std::runtime_error(file.string() + ": cannot be written");
    }
    out << "mode,frequency_hz,point,ux,uy,uz,rx,ry,rz\n";
    out << std::setprecision(10);
    for (const auto& name : model.point_names()) {
        const auto shapes = structure::point_shapes(model, basis, name);
        for (Eigen::Index m = 0; m < shapes.cols(); ++m) {
            out << (m + 1) << ',' << basis.modes[static_cast<std::size_t>(m)].frequency_hz << ','
                << name;
            for (int k = 0; k < 6; ++k) {
                out << ',' << shapes(k, m);
            }
            out << '\n';
        }
    }
}

/// An effective mass, or "n/a" when the model cannot know it (see docs/structure.md).
std::string mass_text(double kg) {
    if (std::isnan(kg)) return "n/a";
    std::ostringstream out;
    out << std::fixed << std::setprecision(5) << kg;
    return out.str();
}

void print_modes(const bench::CampaignConfig& config, const structure::LinearModel& model,
                 const structure::ModalBasis& basis) {
    std::cout << "Structure of " << config.source << " (" << config.name << "): " << model.dofs()
              << " free DOFs\n\n";
    std::cout << " mode  frequency [Hz]  damping [%]  modal mass [kg]"
                 "   effective mass x / y / z [kg]\n";
    std::cout << std::fixed;
    for (std::size_t i = 0; i < basis.modes.size(); ++i) {
        const auto& m = basis.modes[i];
        std::cout << std::setw(5) << (i + 1) << std::setw(16) << std::setprecision(4)
                  << m.frequency_hz << std::setw(13) << std::setprecision(3)
                  << 100.0 * m.damping_ratio << std::setw(17) << std::setprecision(5)
                  << m.modal_mass_kg << "   " << mass_text(m.effective_mass_kg.x()) << " / "
                  << mass_text(m.effective_mass_kg.y()) << " / "
                  << mass_text(m.effective_mass_kg.z()) << '\n';
    }
    if (!model.rigid_translation_known()) {
        std::cout << "\nEffective masses n/a: the matrix rows are not all named; give "
                     "structure.matrix.rigid_body_file.\n";
    }
}

int run_modes(const ModesOptions& options) {
    int exit_code = 0;
    const auto config = load_config_or_report(options.config, options.overrides, exit_code);
    if (!config) {
        return exit_code;
    }
    const int count = options.count > 0 ? options.count : config->structure.modes;
    structure::LinearModel model;
    try {
        model = structure::build_linear_model(config->structure, config->base_dir);
    } catch (const structure::MatrixMarketError& e) {
        std::cerr << "shakerbench modes: " << e.what() << '\n';
        return config::kExitBadInput;  // an imported matrix file that cannot be read
    } catch (const std::invalid_argument& e) {
        std::cerr << "shakerbench modes: " << e.what() << '\n';
        return config::kExitBadInput;  // a structure the config describes but cannot hold
    }
    try {
        const auto basis = structure::compute_modes(model, config->structure.damping, count);
        print_modes(*config, model, basis);
        std::filesystem::create_directories(options.out_dir);
        const auto file = std::filesystem::path(options.out_dir) / (config->name + "-modes.csv");
        write_shapes_csv(file, model, basis);
        std::cout << "\nMode shapes at the named points: " << file.string() << '\n';
    } catch (const std::exception& e) {
        std::cerr << "shakerbench modes: " << e.what() << '\n';
        return config::kExitFailure;  // the eigensolver or the output, not the input
    }
    return 0;
}

}  // namespace

void register_modes_command(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<ModesOptions>();
    CLI::App* cmd = app.add_subcommand(
        "modes",
        "Modal analysis of the structure in CONFIG (default: the built-in paper-000 beam): "
        "frequencies, damping, modal and effective masses; mode shapes at the named points "
        "written to OUT/<campaign name>-modes.csv.");
    cmd->add_option("config", options->config, "campaign config (TOML)");
    cmd->add_option("-o,--out", options->out_dir, "directory for the mode-shape CSV")
        ->capture_default_str();
    cmd->add_option("-n,--count", options->count,
                    "number of modes (default: structure.modes of the config)")
        ->check(CLI::PositiveNumber);
    add_set_option(*cmd, options->overrides);
    cmd->callback([options, &exit_code] { exit_code = run_modes(*options); });
}

}  // namespace sb::apps

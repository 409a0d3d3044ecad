// The energy files of a characterisation.
#include "bench/characterization_energy.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "identification/csv_table.hpp"

namespace sb::bench {
namespace {

using identification::detail::exact_text;

const BedEnergy& energy_of(const CharacterizedRun& run) {
    if (!run.result.energy) {
        throw std::invalid_argument("characterisation run " + run.damper + " " + run.arrangement +
                                    " carries no energy (characterize --energy)");
    }
    return *run.result.energy;
}

/// The comment lines and the columns naming the run.
void write_head(std::ostringstream& out, const CharacterizeResult& result, const char* format) {
    out << "# " << format << '\n';
    out << "# config = " << result.table.config << '\n';
    out << "# config_hash = " << result.table.config_hash << '\n';
    if (!result.table.command.empty()) out << "# command = " << result.table.command << '\n';
    if (!result.table.criterion.empty()) {
        out << "# steady_state = " << result.table.criterion << '\n';
    }
}

void write_run(std::ostringstream& out, const CharacterizedRun& run) {
    identification::detail::check_cell_text(run.damper, "damper");
    identification::detail::check_cell_text(run.arrangement, "arrangement");
    out << run.damper << ',' << run.arrangement << ',' << exact_text(run.level_g) << ','
        << exact_text(run.frequency_hz) << ',' << run.seed;
}

}  // namespace

std::string bed_energy_csv_text(const CharacterizeResult& result) {
    std::size_t layers = 0;
    for (std::size_t r = 0; r < result.runs_by_filling.size(); ++r) {
        const std::size_t n = energy_of(result.runs_by_filling[r]).layer_power_w.size();
        if (r > 0 && n != layers) {
            throw std::invalid_argument("characterisation runs with different numbers of layers");
        }
        layers = n;
    }
    std::ostringstream out;
    write_head(out, result, "shakerbench characterization energy 1");
    out << "# over the two steady windows: powers [W] are energies per window length; layers "
           "are slabs normal to gravity, fixed in the enclosure at its rest pose, bottom "
           "first; a contact's dissipation goes to the layer of its contact point\n";
    out << "damper,arrangement,level_g,frequency_hz,seed,wall_power_w,normal_damping_w,"
           "friction_w,rolling_w,mechanical_change_w,kinetic_lab_j,kinetic_relative_j";
    for (std::size_t l = 0; l < layers; ++l) out << ",layer_" << l + 1 << "_w";
    for (std::size_t l = 0; l < layers; ++l) out << ",layer_" << l + 1 << "_kinetic_j";
    out << '\n';
    for (const CharacterizedRun& run : result.runs_by_filling) {
        const BedEnergy& e = energy_of(run);
        write_run(out, run);
        for (double v : {run.result.power_w, e.normal_damping_w, e.friction_w, e.rolling_w,
                         e.mechanical_change_w, e.kinetic_lab_j, run.result.kinetic_j}) {
            out << ',' << exact_text(v);
        }
        for (double v : e.layer_power_w) out << ',' << exact_text(v);
        for (std::size_t l = 0; l < layers; ++l) {
            // empty where a run stored before this column was resumed
            out << ',' << (l < e.layer_kinetic_j.size() ? exact_text(e.layer_kinetic_j[l]) : "");
        }
        out << '\n';
    }
    return out.str();
}

std::string bed_spectrum_csv_text(const CharacterizeResult& result) {
    std::ostringstream out;
    write_head(out, result, "shakerbench characterization spectrum 1");
    out << "# one-sided amplitudes 2|X_k|/N over the two steady windows (sampled every step, "
           "mean removed, rectangular window): the drive's harmonics fall on bins\n";
    out << "damper,arrangement,level_g,frequency_hz,seed,bin_hz,kinetic_lab_j,"
           "dissipated_power_w\n";
    for (const CharacterizedRun& run : result.runs_by_filling) {
        const BedEnergy& e = energy_of(run);
        const std::size_t bins =
            std::min(e.kinetic_amplitude_j.size(), e.dissipation_amplitude_w.size());
        for (std::size_t k = 0; k < bins; ++k) {
            write_run(out, run);
            out << ',' << exact_text(static_cast<double>(k + 1) * e.bin_hz) << ','
                << exact_text(e.kinetic_amplitude_j[k]) << ','
                << exact_text(e.dissipation_amplitude_w[k]) << '\n';
        }
    }
    return out.str();
}

}  // namespace sb::bench

// A made-up characterisation of damper `pd` in arrangement H-0 (the shipped paper-000
// config's names), written as `shakerbench characterize` writes it: a describing-function
// damper whose apparent mass the test chooses.
#pragma once

#include <cmath>
#include <complex>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "bench/describing_function.hpp"
#include "core/text_file.hpp"
#include "core/units.hpp"

namespace sb::test {

/// Writes dir/characterization.csv with the apparent mass `mass(a, f)` [kg] at every level
/// [g RMS] and frequency [Hz] of the grid, a the peak acceleration [m/s^2], and the power it
/// dissipates (-Im M = 2 P / (w |a|^2)), one filling each, in `arrangement`; returns the
/// file.
inline std::filesystem::path write_described_damper(
    const std::filesystem::path& dir, const std::vector<double>& levels_g,
    const std::vector<double>& frequencies_hz, double bed_mass_kg,
    const std::function<std::complex<double>(double, double)>& mass,
    const std::string& arrangement = "H-0") {
    bench::CharacterizationTable table;
    table.config = "made-up";
    for (const double level : levels_g) {
        for (const double f : frequencies_hz) {
            bench::CharacterizationRow r;
            r.damper = "pd";
            r.arrangement = arrangement;
            r.level_g = level;
            r.acceleration_m_s2 = std::sqrt(2.0) * g_to_m_s2(level);
            r.frequency_hz = f;
            r.bed_mass_kg = bed_mass_kg;
            r.seeds = 1;
            r.apparent_mass_kg = mass(r.acceleration_m_s2, f);
            const double w = hz_to_rad_s(f);
            r.power_w =
                -r.apparent_mass_kg.imag() * w * r.acceleration_m_s2 * r.acceleration_m_s2 / 2.0;
            table.rows.push_back(r);
        }
    }
    std::filesystem::create_directories(dir);
    const auto file = dir / "characterization.csv";
    write_file_atomically(file, bench::characterization_csv_text(table));
    return file;
}

}  // namespace sb::test

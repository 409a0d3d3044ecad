// Where a characterised damper's energy goes (`characterize --energy`): the dissipated power
// per mechanism and per horizontal layer, and the spectra of the bed's kinetic energy and
// dissipated power (paper 002, Figs. 12 and 13; docs/characterisation.md).
#pragma once

#include <string>

#include "bench/characterization.hpp"

namespace sb::bench {

/// characterization_energy.csv: one row per run (grid point and filling) with the wall
/// power, the dissipated power per mechanism and per layer (bottom first) and the mean
/// kinetic energies. Throws std::invalid_argument when a run carries no energy or the runs
/// differ in their number of layers.
std::string bed_energy_csv_text(const CharacterizeResult& result);

/// energy_spectrum.csv: per run, the one-sided amplitude spectra of the laboratory kinetic
/// energy and of the dissipated power over the steady windows, one row per bin up to
/// BedEnergy::kSpectrumHarmonics times the drive. Throws as bed_energy_csv_text.
std::string bed_spectrum_csv_text(const CharacterizeResult& result);

}  // namespace sb::bench

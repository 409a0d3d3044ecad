// The diagnosis's plots: the measurement beside the baseline and the improved model (the
// winning physics at its fitted values), as data files, a gnuplot script and SVGs when gnuplot
// is installed.
#pragma once

#include <filesystem>

#include "correlation/diagnosis.hpp"
#include "identification/plots.hpp"

namespace sb::correlation {

/// Writes into out_dir/plots, per arrangement (file-safe names), `ARR-frf.dat` (one block per
/// level: frequency [Hz], measured |H|, its standard uncertainty, the baseline's |H| and the
/// improved model's, NaN where there is none) and `ARR-levels.dat` (per level: damping ratio
/// [%] measured, its standard uncertainty, the baseline's, the improved model's; then the
/// natural frequency [Hz] the same way), and one script `diagnosis.gp` that makes
/// out_dir/diagnosis-ARR-frf.svg and out_dir/diagnosis-ARR-levels.svg. Runs gnuplot when it
/// is on PATH (identification::render_gnuplot). Without a winner the improved columns are NaN
/// and not drawn. Throws sb::FileWriteError naming a file that cannot be written.
identification::PlotResult write_diagnosis_plots(const std::filesystem::path& out_dir,
                                                 const DiagnosisResult& result);

}  // namespace sb::correlation

// Plots of identified levels: data files, a gnuplot script, and SVGs when gnuplot is installed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "identification/damping_curve.hpp"

namespace sb::identification {

/// Options of write_plots.
struct PlotOptions {
    /// Label of the level axis of the damping plot (a UFF file's records are numbered).
    std::string level_axis = "level [g RMS]";
    /// Unit of a level in the FRF plot's curve titles ("g"; a fixed drive's "V", "N", ...).
    std::string level_unit = "g";
    /// Run gnuplot when it is on PATH; false only writes the data and the script.
    bool render = true;
};

/// What write_plots wrote and whether gnuplot made the SVGs.
struct PlotResult {
    std::vector<std::filesystem::path> data;  ///< data files written
    std::filesystem::path script;             ///< the gnuplot script
    std::vector<std::filesystem::path> svg;   ///< the SVGs the script makes
    bool rendered = false;                    ///< gnuplot ran and made every SVG
    std::string message;  ///< for the user: how to render, or why gnuplot failed; empty if ok
};

/// For every arrangement of `levels` (in order of first appearance) writes into
/// out_dir/plots the data files `<arrangement>-frf.dat` (frequency, |FRF|, phase in degrees;
/// one block per level and filling of the bed that has a point: a level whose points were all
/// left out has no block and no curve, and an arrangement with none no FRF plot) and
/// `<arrangement>-damping.dat` (per level and method — half-power, circle fit, rational fraction —
/// ζ [%], its seed scatter, f_n [Hz], its seed scatter: the mean and sample standard deviation over
/// the fillings, as in damping.csv; NaN where a method gave no number), and one script `plots.gp`.
/// The script makes out_dir/<arrangement>-frf.svg (magnitude and phase, one curve per level and
/// filling) and out_dir/<arrangement>-damping.svg (damping ratio and natural frequency versus
/// level, one curve per method, with the seed scatter as error bars). When gnuplot is on PATH it is
/// run (its messages go to plots/gnuplot.log); otherwise the message says how to run it.
/// Arrangement names are made file-safe (characters other than letters, digits, '-', '_', '.'
/// become '_').
PlotResult write_plots(const std::filesystem::path& out_dir,
                       const std::vector<LevelIdentification>& levels,
                       const PlotOptions& options = {});

/// Runs gnuplot on result.script in its folder when `render` and gnuplot is on PATH (its
/// messages to gnuplot.log there), and checks that every SVG of result.svg was written:
/// sets result.rendered, or result.message saying how to render or why gnuplot failed.
void render_gnuplot(bool render, PlotResult& result);

/// `name` with every character other than letters, digits, '-', '_', '.' made '_' ("unnamed"
/// when empty): for file names made of arrangement names.
std::string file_safe(const std::string& name);

/// A gnuplot single-quoted string: a quote inside is doubled.
std::string gnuplot_quoted(const std::string& s);

}  // namespace sb::identification

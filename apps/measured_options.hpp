// The options every command that reads a measured recording shares: the uncertainty of its
// values where it has no repeats (correlation/features.hpp).
#pragma once

#include <CLI/CLI.hpp>

#include "correlation/features.hpp"

namespace sb::apps {

/// Adds --damping-uncertainty, --frequency-uncertainty and --frf-uncertainty, each filling
/// its member of `stated` (whose values are the defaults shown).
void add_uncertainty_options(CLI::App& command, correlation::StatedUncertainty& stated);

}  // namespace sb::apps

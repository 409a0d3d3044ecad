// The two-fidelity search of a calibration: the whole search on a cheap simulation (the
// campaign predicted from the damper's describing functions), then the coupled simulation at
// the answer and a stencil around it, whose differences from the cheap one correct it (a
// Gaussian-process discrepancy per feature, Kennedy and O'Hagan 2001; with a stencil it gives
// the correction's slopes too, the first-order consistency of Alexandrov et al. 1998), until
// a correction no longer moves the answer (docs/calibration.md).
#pragma once

#include <string>
#include <vector>

#include "correlation/evaluator.hpp"
#include "correlation/search.hpp"

namespace sb::correlation {

/// Half-width of the coupled stencil around each answer, in the unit cube [-].
inline constexpr double kTwoFidelityStep = 0.05;
/// Corrections at most: the first a stencil of 2 d + 1 coupled simulations, each later one
/// the new answer alone (a new stencil when it moved more than two steps) [-].
inline constexpr int kTwoFidelityCorrections = 4;
/// A correction that moves the answer less than this ends them, in the unit cube [-].
inline constexpr double kTwoFidelityConverged = 0.01;

struct TwoFidelityOutcome {
    SearchOutcome low_search;         ///< the search on the low fidelity
    std::vector<double> best_values;  ///< the corrected answer (not yet confirmed)
    /// The low fidelity's evaluations with the discrepancy added: what the corrected emulator
    /// (and the intervals) are trained on.
    std::vector<Evaluation> corrected_history;
    int corrections = 0;  ///< stencils simulated on the high fidelity
    std::string stopped;  ///< why the corrections ended, in words
};

/// Searches on `low` (options' mode and budget), then corrects with `high` around the
/// answer. The caller evaluates the config's values on `high` first (the residuals before) and
/// the answer last (its confirmation). Throws std::invalid_argument when the low fidelity gave
/// fewer than 3 successful evaluations (no emulator to correct).
TwoFidelityOutcome two_fidelity_search(Evaluator& low, Evaluator& high,
                                       const SearchOptions& options);

}  // namespace sb::correlation

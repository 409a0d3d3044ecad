// The two searches of a calibration over the free parameters' unit cube, both within a budget
// of evaluations: direct (NLopt's DIRECT-L globally, then BOBYQA locally from its best) and
// surrogate (a space-filling start, then Bayesian optimisation by expected improvement on the
// feature emulator).
#pragma once

#include <string>
#include <vector>

#include "correlation/evaluator.hpp"

namespace sb::correlation {

enum class SearchMode { direct, surrogate };

/// "direct", "surrogate".
std::string search_mode_name(SearchMode mode);

struct SearchOptions {
    SearchMode mode = SearchMode::direct;
    int budget = 30;  ///< evaluations (the cached ones count too, so a rerun takes the same path)
    /// Direct: the share of the budget the global stage may use [-].
    double global_share = 0.6;
    /// Surrogate: points of the space-filling start (0: 2 d + 2 with d free parameters).
    int initial_points = 0;
    /// Surrogate: the search ends early once the expected improvement of two proposals in a
    /// row is below this (in misfit units, ½ χ²) [-].
    double improvement_tolerance = 0.05;
};

/// What the search did and where it ended.
struct SearchOutcome {
    std::vector<double> best_values;  ///< the free values of the best evaluation
    int evaluations = 0;              ///< asked for, the cached included
    std::string stopped;              ///< why the search ended, in words
};

/// Runs the search from the config's values (evaluated first) and returns the best
/// evaluation's values: the lowest misfit (direct), or the lowest emulated misfit among the
/// evaluated points (surrogate: the emulator averages the seed scatter out).
SearchOutcome search(Evaluator& evaluator, const SearchOptions& options);

}  // namespace sb::correlation

// Refining a sweep's frequency grid near its peak until its estimates are resolved, as a lab
// engineer adds points where a lightly damped peak falls between two of them.
#pragma once

#include <string>
#include <vector>

#include "identification/recording.hpp"

namespace sb::bench {

/// What the points of a sweep resolve.
struct GridVerdict {
    bool resolved = false;          ///< half-power and circle fit both give numbers
    std::vector<double> add_hz;     ///< frequencies to add next (at most `max_new`), ascending
    std::string unresolved_reason;  ///< when not resolved: the failing estimators' messages
};

/// From the points of one sweep (channel 0 the reference, channel 1 the control channel; base
/// excitation: `base_excitation`), whether its half-power and circle-fit estimates are resolved
/// and, if not, where to add points: beyond the grid's edge when the peak sits on it or a
/// half-power crossing lies outside, else halfway between the peak and each neighbour. Points
/// with status `closest` are left out as identification leaves them out. Depends only on the
/// points, so a resumed sweep adds the same frequencies.
GridVerdict assess_grid(const std::vector<identification::PointRow>& rows, bool base_excitation,
                        std::size_t max_new);

}  // namespace sb::bench

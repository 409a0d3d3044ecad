// Deterministic space-filling designs in the unit cube: the start of a surrogate calibration
// and the candidate sets its acquisition and profiles search.
#pragma once

#include <cstdint>
#include <vector>

namespace sb::correlation {

/// The first `count` points of the Halton sequence in `dimensions` (≤ 10) dimensions (bases
/// the first primes), skipping the first `skip` points: low discrepancy, no randomness.
std::vector<std::vector<double>> halton(int count, int dimensions, int skip = 1);

/// A Latin hypercube of `count` points (each dimension's `count` strata used once, the point
/// at a stratum's centre), the strata permuted by a generator seeded with `seed`: reproducible.
std::vector<std::vector<double>> latin_hypercube(int count, int dimensions, std::uint64_t seed);

/// The points at ±`step` of `centre` along each axis, clamped into the unit cube; a point that
/// clamping puts back on the centre (the centre on a face) is left out: at most 2 d points.
std::vector<std::vector<double>> axis_stencil(const std::vector<double>& centre, double step);

}  // namespace sb::correlation

// Node positions of a beam mesh: uniform spacing with nodes exactly at every feature.
#pragma once

#include <vector>

#include "structure/spec.hpp"

namespace sb::structure {

/// Positions closer than this are one node [m].
inline constexpr double kNodeMergeDistanceM = 1e-9;

/// Sorted node positions [m] from 0 to length: a node at every support, point and mass;
/// each span between such features divided into equal elements no longer than
/// length / min_elements, so there are at least min_elements elements.
std::vector<double> beam_mesh_nodes(const BeamSpec& beam);

/// Index of the node nearest to x_m [m] in sorted positions.
int nearest_node(const std::vector<double>& nodes, double x_m);

}  // namespace sb::structure

// Node positions of a beam mesh: uniform spacing with nodes exactly at every feature.
#include "structure/beam_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace sb::structure {

std::vector<double> beam_mesh_nodes(const BeamSpec& beam) {
    const double length = beam.length_m;
    std::vector<double> features{0.0, length};
    for (const auto& s : beam.supports) features.push_back(s.x_m);
    for (const auto& p : beam.points) features.push_back(p.x_m);
    for (const auto& m : beam.resolved().masses) features.push_back(m.x_m);
    std::sort(features.begin(), features.end());
    std::vector<double> merged;
    for (const double x : features) {
        if (merged.empty() || x - merged.back() > kNodeMergeDistanceM) merged.push_back(x);
    }
    const double max_element = length / std::max(1, beam.min_elements);
    std::vector<double> nodes{merged.front()};
    for (std::size_t i = 1; i < merged.size(); ++i) {
        const double a = merged[i - 1];
        const double span = merged[i] - a;
        const int count = std::max(1, static_cast<int>(std::ceil(span / max_element - 1e-9)));
        for (int k = 1; k < count; ++k) nodes.push_back(a + span * k / count);
        nodes.push_back(merged[i]);
    }
    return nodes;
}

int nearest_node(const std::vector<double>& nodes, double x_m) {
    const auto it = std::lower_bound(nodes.begin(), nodes.end(), x_m);
    auto best = it == nodes.end() ? nodes.end() - 1 : it;
    if (it != nodes.begin() && std::abs(*(it - 1) - x_m) <= std::abs(*best - x_m)) best = it - 1;
    return static_cast<int>(best - nodes.begin());
}

}  // namespace sb::structure

// A wireframe seen as a graph: the edges at each junction, and how many there are. One place for the loops
// that the post-processing, the surfaces and the experiments each wrote for themselves.
#pragma once

#include <array>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// For each junction, the indices of its edges, in edge order.
std::vector<std::vector<int>> incident_edges(const Wireframe& wf);

// For each junction, the number of its edges.
std::vector<int> junction_degrees(const Wireframe& wf);

// For each of `junctions` nodes, the connected part it belongs to, joined by `edges`: parts numbered 0, 1, ...
// in the order of their first junction.
std::vector<int> connected_parts(int junctions, const std::vector<std::array<int, 2>>& edges);

}  // namespace lc2wf

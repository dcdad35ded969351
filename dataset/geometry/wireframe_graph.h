// A wireframe seen as a graph: the edges at each junction, and how many there are. One place for the loops
// that the post-processing, the surfaces and the experiments each wrote for themselves.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// For each junction, the indices of its edges, in edge order.
std::vector<std::vector<int>> incident_edges(const Wireframe& wf);

// For each junction, the number of its edges.
std::vector<int> junction_degrees(const Wireframe& wf);

}  // namespace lc2wf

#include "dataset/geometry/wireframe_graph.h"

namespace lc2wf {

std::vector<std::vector<int>> incident_edges(const Wireframe& wf) {
  std::vector<std::vector<int>> incident(wf.junctions.size());
  for (size_t e = 0; e < wf.edges.size(); ++e) {
    incident[wf.edges[e][0]].push_back(static_cast<int>(e));
    incident[wf.edges[e][1]].push_back(static_cast<int>(e));
  }
  return incident;
}

std::vector<int> junction_degrees(const Wireframe& wf) {
  std::vector<int> degree(wf.junctions.size(), 0);
  for (const auto& [a, b] : wf.edges) ++degree[a], ++degree[b];
  return degree;
}

}  // namespace lc2wf

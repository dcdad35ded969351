#include "dataset/geometry/wireframe_graph.h"

#include <numeric>

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

std::vector<int> connected_parts(int junctions, const std::vector<std::array<int, 2>>& edges) {
  std::vector<int> parent(junctions);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& [a, b] : edges) parent[root(a)] = root(b);
  std::vector<int> part(junctions), number(junctions, -1);
  int parts = 0;
  for (int j = 0; j < junctions; ++j) {
    int& n = number[root(j)];
    if (n < 0) n = parts++;
    part[j] = n;
  }
  return part;
}

}  // namespace lc2wf

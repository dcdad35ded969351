#include "model/scored_wireframe.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lc2wf {

void ScoredWireframe::check(const std::string& what) const {
  const auto n = static_cast<int>(wireframe.junctions.size());
  if (junction_scores.size() != wireframe.junctions.size())
    throw std::invalid_argument(what + ": " + std::to_string(junction_scores.size()) + " junction scores for " +
                                std::to_string(n) + " junctions");
  if (edge_scores.size() != wireframe.edges.size())
    throw std::invalid_argument(what + ": " + std::to_string(edge_scores.size()) + " edge scores for " +
                                std::to_string(wireframe.edges.size()) + " edges");
  for (size_t k = 0; k < junction_scores.size(); ++k)
    if (!wireframe.junctions[k].allFinite() || !std::isfinite(junction_scores[k]))
      throw std::invalid_argument(what + ": junction " + std::to_string(k) + " has a non-finite coordinate or score");
  for (size_t e = 0; e < edge_scores.size(); ++e)
    if (!std::isfinite(edge_scores[e]))
      throw std::invalid_argument(what + ": edge " + std::to_string(e) + " has a non-finite score");
  for (size_t e = 0; e < wireframe.edges.size(); ++e) {
    const auto [a, b] = wireframe.edges[e];
    if (a < 0 || b < 0 || a >= n || b >= n)
      throw std::invalid_argument(what + ": edge " + std::to_string(e) + " (" + std::to_string(a) + ", " +
                                  std::to_string(b) + ") refers to a junction outside 0.." + std::to_string(n - 1));
  }
}

ScoredWireframe ScoredWireframe::with_unit_scores(Wireframe wireframe) {
  ScoredWireframe out;
  out.junction_scores.assign(wireframe.junctions.size(), 1.0);
  out.edge_scores.assign(wireframe.edges.size(), 1.0);
  out.wireframe = std::move(wireframe);
  return out;
}

ScoredWireframe referenced_junctions_only(const ScoredWireframe& in) {
  ScoredWireframe out;
  std::vector<int> new_index(in.wireframe.junctions.size(), -1);
  auto remap = [&](int old) {
    if (new_index[old] < 0) {
      new_index[old] = static_cast<int>(out.wireframe.junctions.size());
      out.wireframe.junctions.push_back(in.wireframe.junctions[old]);
      out.junction_scores.push_back(in.junction_scores[old]);
    }
    return new_index[old];
  };
  for (size_t e = 0; e < in.wireframe.edges.size(); ++e) {
    const auto [a, b] = in.wireframe.edges[e];
    const int x = remap(a), y = remap(b);
    out.wireframe.edges.push_back({std::min(x, y), std::max(x, y)});
    out.edge_scores.push_back(in.edge_scores[e]);
  }
  return out;
}

}  // namespace lc2wf

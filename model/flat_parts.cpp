#include "model/flat_parts.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dataset/geometry/plane_fit.h"
#include "dataset/geometry/wireframe_graph.h"

namespace lc2wf {

void FlatPartOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("FlatPartOptions." + what); };
  if (max_edges < 0) fail("max_edges must be >= 0 (0: off)");
  if (!(plane_tolerance_m >= 0) || !std::isfinite(plane_tolerance_m)) fail("plane_tolerance_m must be a distance >= 0 in metres");
}

namespace {

// Whether the points lie within `tolerance` of their least-squares plane. Three points or fewer always do.
bool flat(const std::vector<Vec3>& points, double tolerance) {
  if (points.size() <= 3) return true;
  const Plane plane = fit_plane(points);
  return std::all_of(points.begin(), points.end(), [&](const Vec3& p) { return std::abs(plane.distance(p)) <= tolerance; });
}

}  // namespace

FlatPartsDropped drop_flat_parts(const ScoredWireframe& in, const FlatPartOptions& options) {
  options.Check();
  in.check("drop_flat_parts");
  FlatPartsDropped out;
  if (!options.enabled() || in.wireframe.edges.empty()) {
    out.wireframe = in;
    return out;
  }
  const Wireframe& w = in.wireframe;
  const std::vector<int> part = connected_parts(static_cast<int>(w.junctions.size()), w.edges);
  const int parts = part.empty() ? 0 : *std::max_element(part.begin(), part.end()) + 1;
  std::vector<int> edges_of_part(parts, 0);
  std::vector<double> length_of_part(parts, 0.0);
  for (const auto& e : w.edges) {
    ++edges_of_part[part[e[0]]];
    length_of_part[part[e[0]]] += (w.junctions[e[1]] - w.junctions[e[0]]).norm();
  }
  // The largest part by drawn length, not by edges: a tree's zigzag of short edges outnumbers a gable's three long
  // ones (the lowest numbered on ties: deterministic).
  const int largest = static_cast<int>(std::max_element(length_of_part.begin(), length_of_part.end()) - length_of_part.begin());
  std::vector<std::vector<Vec3>> points(parts);
  for (size_t j = 0; j < w.junctions.size(); ++j) points[part[j]].push_back(w.junctions[j]);
  std::vector<char> drop(parts, 0);
  for (int p = 0; p < parts; ++p)
    if (edges_of_part[p] > 0 && p != largest && edges_of_part[p] < options.max_edges && flat(points[p], options.plane_tolerance_m))
      drop[p] = 1, ++out.dropped_parts, out.dropped_edges += edges_of_part[p];
  ScoredWireframe kept;
  kept.wireframe.junctions = w.junctions;
  kept.junction_scores = in.junction_scores;
  for (size_t e = 0; e < w.edges.size(); ++e)
    if (!drop[part[w.edges[e][0]]]) kept.wireframe.edges.push_back(w.edges[e]), kept.edge_scores.push_back(in.edge_scores[e]);
  out.wireframe = referenced_junctions_only(kept);
  return out;
}

}  // namespace lc2wf

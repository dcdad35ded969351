#include "model/flat_parts.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace lc2wf {

void FlatPartOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("FlatPartOptions." + what); };
  if (max_edges < 0) fail("max_edges must be >= 0 (0: off)");
  if (!(plane_tolerance_m >= 0) || !std::isfinite(plane_tolerance_m)) fail("plane_tolerance_m must be a distance >= 0 in metres");
}

namespace {

int root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// Whether the points lie within `tolerance` of one plane: the plane through their centroid normal to the
// direction of least spread. Three points or fewer always do.
bool flat(const std::vector<Vec3>& points, double tolerance) {
  if (points.size() <= 3) return true;
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  const Vec3 normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(0);
  return std::all_of(points.begin(), points.end(), [&](const Vec3& p) { return std::abs((p - centroid).dot(normal)) <= tolerance; });
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
  std::vector<int> parent(w.junctions.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [a, b] : w.edges) parent[root(parent, a)] = root(parent, b);
  std::vector<int> edges_of_part(w.junctions.size(), 0);
  for (const auto& e : w.edges) ++edges_of_part[root(parent, e[0])];
  // The largest part, by edges (the lowest root on ties: deterministic).
  int largest = 0;
  for (int r = 0; r < static_cast<int>(edges_of_part.size()); ++r)
    if (edges_of_part[r] > edges_of_part[largest]) largest = r;
  std::vector<std::vector<Vec3>> points(w.junctions.size());
  for (int j = 0; j < static_cast<int>(w.junctions.size()); ++j) points[root(parent, j)].push_back(w.junctions[j]);
  std::vector<char> drop(w.junctions.size(), 0);
  for (int r = 0; r < static_cast<int>(edges_of_part.size()); ++r)
    if (edges_of_part[r] > 0 && r != largest && edges_of_part[r] < options.max_edges && flat(points[r], options.plane_tolerance_m))
      drop[r] = 1, ++out.dropped_parts, out.dropped_edges += edges_of_part[r];
  ScoredWireframe kept;
  kept.wireframe.junctions = w.junctions;
  kept.junction_scores = in.junction_scores;
  for (size_t e = 0; e < w.edges.size(); ++e)
    if (!drop[root(parent, w.edges[e][0])]) kept.wireframe.edges.push_back(w.edges[e]), kept.edge_scores.push_back(in.edge_scores[e]);
  out.wireframe = referenced_junctions_only(kept);
  return out;
}

}  // namespace lc2wf

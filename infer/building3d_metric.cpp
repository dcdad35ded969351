#include "infer/building3d_metric.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include "infer/hungarian.h"

namespace lc2wf {
namespace {

using EdgeKey = std::pair<int, int>;
EdgeKey key(int a, int b) { return a < b ? EdgeKey{a, b} : EdgeKey{b, a}; }

double ratio(double num, double den) { return den > 0 ? num / den : 0.0; }
double f1(double p, double r) { return p + r > 0 ? 2 * p * r / (p + r) : 0.0; }

// The 2023 calculator's confidence cut: kept edges re-indexed onto the corners they reference.
Wireframe kept_prediction(const ScoredWireframe& pred, double confidence_threshold) {
  Wireframe out;
  std::vector<int> remap(pred.wireframe.junctions.size(), -1);
  for (size_t e = 0; e < pred.wireframe.edges.size(); ++e) {
    if (!(pred.edge_scores[e] > confidence_threshold)) continue;
    std::array<int, 2> edge{};
    for (int k = 0; k < 2; ++k) {
      int& r = remap[pred.wireframe.edges[e][k]];
      if (r < 0) r = static_cast<int>(out.junctions.size()), out.junctions.push_back(pred.wireframe.junctions[pred.wireframe.edges[e][k]]);
      edge[k] = r;
    }
    out.edges.push_back(edge);
  }
  return out;
}

int nearest(const Vec3& p, const std::vector<Vec3>& points) {
  int best = -1;
  double d = std::numeric_limits<double>::infinity();
  for (size_t j = 0; j < points.size(); ++j)
    if ((p - points[j]).norm() < d) d = (p - points[j]).norm(), best = static_cast<int>(j);
  return best;
}

// 2024 calculator's graph edit distance on the kept prediction, divided by the total GT edge length.
double normalised_wed(const Wireframe& kept, const Wireframe& gt, double gt_length) {
  if (kept.junctions.empty()) return 1.0;  // the 2024 calculator scores an edgeless result as 1
  double cost = 0.0;
  std::vector<int> to_gt(kept.junctions.size());
  for (size_t i = 0; i < kept.junctions.size(); ++i) {
    to_gt[i] = nearest(kept.junctions[i], gt.junctions);
    cost += (kept.junctions[i] - gt.junctions[to_gt[i]]).norm();
  }
  std::set<EdgeKey> gt_edges;
  for (const auto& e : gt.edges) gt_edges.insert(key(e[0], e[1]));
  std::set<EdgeKey> mapped;  // duplicates after snapping count once, as np.unique does
  for (const auto& e : kept.edges) mapped.insert(key(to_gt[e[0]], to_gt[e[1]]));
  std::set<EdgeKey> hit;
  for (const auto& m : mapped) {
    if (gt_edges.count(m)) hit.insert(m);
    else cost += (gt.junctions[m.first] - gt.junctions[m.second]).norm();  // degenerate pairs: 0
  }
  for (const auto& e : gt_edges)
    if (!hit.count(e)) cost += (gt.junctions[e.first] - gt.junctions[e.second]).norm();
  return cost / gt_length;
}

}  // namespace

NormalisationFrame frame_of_points(const std::vector<Vec3>& points) {
  NormalisationFrame f;
  if (points.empty()) return f;
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : points) c += p;
  c /= static_cast<double>(points.size());
  double r = 0.0;
  for (const Vec3& p : points) r = std::max(r, (p - c).norm());
  f.centroid = c;
  if (r > 0) f.radius = r;
  return f;
}

NormalisationFrame frame_of_segments(const std::vector<Segment3>& segments) {
  std::vector<Vec3> points;
  points.reserve(2 * segments.size());
  for (const Segment3& s : segments) points.push_back(s.a), points.push_back(s.b);
  return frame_of_points(points);
}

void Building3dOptions::Check() const {
  if (!(distance_threshold > 0) || !std::isfinite(distance_threshold))
    throw std::invalid_argument("Building3dOptions.distance_threshold must be positive, got " +
                                std::to_string(distance_threshold));
  if (!std::isfinite(confidence_threshold))
    throw std::invalid_argument("Building3dOptions.confidence_threshold must be finite");
}

Building3dCounts building3d_counts(const ScoredWireframe& pred, const Wireframe& gt, const NormalisationFrame& frame,
                                   const Building3dOptions& options) {
  options.Check();
  pred.check("Building3D prediction");
  const Wireframe kept = kept_prediction(pred, options.confidence_threshold);
  Building3dCounts c;
  c.frame_radius = frame.radius;
  c.pred_corners = static_cast<int>(kept.junctions.size());
  c.gt_corners = static_cast<int>(gt.junctions.size());
  c.pred_edges = static_cast<int>(kept.edges.size());
  c.gt_edges = static_cast<int>(gt.edges.size());

  // Corners: Hungarian matching on normalised distances, then the threshold.
  std::vector<std::vector<double>> cost(kept.junctions.size(), std::vector<double>(gt.junctions.size()));
  for (size_t i = 0; i < kept.junctions.size(); ++i)
    for (size_t j = 0; j < gt.junctions.size(); ++j)
      cost[i][j] = (kept.junctions[i] - gt.junctions[j]).norm() / frame.radius;
  const std::vector<int> assigned = min_cost_assignment(cost);
  std::vector<int> tp_gt(kept.junctions.size(), -1);
  for (size_t i = 0; i < assigned.size(); ++i) {
    const int j = assigned[i];
    if (j < 0 || !(cost[i][j] <= options.distance_threshold)) continue;
    tp_gt[i] = j;
    ++c.tp_corners;
    c.corner_offset_sum += cost[i][j] * frame.radius;  // de-normalised: metres
  }

  // Edges: both ends TP corners whose GT partners form a GT edge.
  std::set<EdgeKey> gt_edges;
  double gt_length = 0.0;
  for (const auto& e : gt.edges) {
    gt_edges.insert(key(e[0], e[1]));
    gt_length += (gt.junctions[e[0]] - gt.junctions[e[1]]).norm();
  }
  for (const auto& e : kept.edges)
    if (tp_gt[e[0]] >= 0 && tp_gt[e[1]] >= 0 && gt_edges.count(key(tp_gt[e[0]], tp_gt[e[1]]))) ++c.tp_edges;

  c.has_gt_edges = gt_length > 0;
  if (c.has_gt_edges) c.nwed = normalised_wed(kept, gt, gt_length);
  return c;
}

Building3dSummary summarize_building3d(const std::vector<Building3dCounts>& per_building, const Building3dOptions& options,
                                       const std::string& frame_source) {
  Building3dSummary s;
  s.options = options;
  s.frame_source = frame_source;
  s.buildings = static_cast<int>(per_building.size());
  Building3dCounts& t = s.totals;
  int with_edges = 0;
  double radius_sum = 0.0;
  for (const Building3dCounts& c : per_building) {
    t.tp_corners += c.tp_corners, t.pred_corners += c.pred_corners, t.gt_corners += c.gt_corners;
    t.corner_offset_sum += c.corner_offset_sum;
    t.tp_edges += c.tp_edges, t.pred_edges += c.pred_edges, t.gt_edges += c.gt_edges;
    if (c.has_gt_edges) t.nwed += c.nwed, ++with_edges;
    radius_sum += c.frame_radius;
  }
  s.cp = ratio(t.tp_corners, t.pred_corners);
  s.cr = ratio(t.tp_corners, t.gt_corners);
  s.cf1 = f1(s.cp, s.cr);
  s.ep = ratio(t.tp_edges, t.pred_edges);
  s.er = ratio(t.tp_edges, t.gt_edges);
  s.ef1 = f1(s.ep, s.er);
  s.aco = ratio(t.corner_offset_sum, t.tp_corners);
  s.nwed_mean = ratio(t.nwed, with_edges);
  s.mean_radius = ratio(radius_sum, s.buildings);
  return s;
}

}  // namespace lc2wf

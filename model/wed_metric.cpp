#include "model/wed_metric.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace lc2wf {
namespace {

// Nearest GT vertex per predicted junction (first index on ties) and its distance. Needs a non-empty GT.
void map_to_nearest(const Wireframe& pred, const Wireframe& gt, std::vector<int>& nearest, std::vector<double>& dist) {
  nearest.assign(pred.junctions.size(), -1);
  dist.assign(pred.junctions.size(), 0.0);
  for (size_t i = 0; i < pred.junctions.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < gt.junctions.size(); ++j) {
      const double d = (pred.junctions[i] - gt.junctions[j]).norm();
      // The first GT vertex is taken even when every distance overflows to inf, so the index is always valid.
      if (j == 0 || d < best) best = d, nearest[i] = static_cast<int>(j);
    }
    dist[i] = best;
  }
}

std::map<std::pair<int, int>, int> gt_edge_index(const Wireframe& gt) {
  std::map<std::pair<int, int>, int> index;
  for (size_t e = 0; e < gt.edges.size(); ++e) {
    const auto [a, b] = gt.edges[e];
    index.emplace(std::make_pair(std::min(a, b), std::max(a, b)), static_cast<int>(e));
  }
  return index;
}

double gt_length(const Wireframe& gt, int a, int b) { return (gt.junctions[a] - gt.junctions[b]).norm(); }

WedResult counts(const Wireframe& pred, const Wireframe& gt) {
  WedResult r;
  r.gt_vertices = static_cast<int>(gt.junctions.size());
  r.gt_edges = static_cast<int>(gt.edges.size());
  r.pred_vertices = static_cast<int>(pred.junctions.size());
  r.pred_edges = static_cast<int>(pred.edges.size());
  return r;
}

// Shared part of both variants: nearest mapping, +vertex, edge hits. `strict` charges every non-first hit.
WedResult wed(const Wireframe& pred, const Wireframe& gt, bool strict, double raw_per_metre) {
  WedResult r = counts(pred, gt);
  std::vector<int> nearest;
  std::vector<double> dist;
  map_to_nearest(pred, gt, nearest, dist);

  std::vector<int> claims(gt.junctions.size(), 0);
  for (size_t i = 0; i < pred.junctions.size(); ++i) {
    ++claims[nearest[i]];
    // The release takes sqrt of the raw-unit distance and divides the sum by 20 when printing.
    r.move += strict ? dist[i] : std::sqrt(dist[i] * raw_per_metre) / raw_per_metre;
  }
  for (int c : claims) {
    if (c == 0) ++r.add_vertex;
    if (strict && c > 1) r.del_vertex += c - 1;
  }

  const auto index = gt_edge_index(gt);
  std::vector<char> hit(gt.edges.size(), 0);
  for (const auto& [i, k] : pred.edges) {
    const int a = std::min(nearest[i], nearest[k]), b = std::max(nearest[i], nearest[k]);
    const auto it = index.find({a, b});
    const bool first_hit = it != index.end() && !hit[it->second];
    if (first_hit) {
      hit[it->second] = 1;
    } else if (strict || it != index.end()) {
      ++r.del_edge;
      r.del_edge_length += gt_length(gt, a, b);
    }
  }
  for (size_t e = 0; e < gt.edges.size(); ++e) {
    if (hit[e]) continue;
    ++r.add_edge;
    r.add_edge_length += gt_length(gt, gt.edges[e][0], gt.edges[e][1]);
  }
  return r;
}

}  // namespace

WedResult wed_release(const Wireframe& pred, const Wireframe& gt, double raw_per_metre) {
  if (gt.junctions.empty()) return counts(pred, gt);
  return wed(pred, gt, false, raw_per_metre);
}

WedResult wed_strict(const Wireframe& pred, const Wireframe& gt) {
  if (gt.junctions.empty()) {
    WedResult r = counts(pred, gt);
    r.del_vertex = r.pred_vertices;
    r.del_edge = r.pred_edges;
    for (const auto& [a, b] : pred.edges) r.del_edge_length += (pred.junctions[a] - pred.junctions[b]).norm();
    return r;
  }
  return wed(pred, gt, true, 1.0);
}

}  // namespace lc2wf

#include "model/post_process.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <set>
#include <stdexcept>

#include "dataset/geometry/segment_crossing.h"
#include "model/ap_metric.h"

namespace lc2wf {
namespace {

struct Edge {
  int a = 0;
  int b = 0;
  double weight = 0.0;
};

bool finite(const Vec3& p) { return p.allFinite(); }

void check_input(const PostProcessInput& in) {
  const int n = static_cast<int>(in.junctions.size());
  if (in.confidences.size() != in.junctions.size())
    throw std::invalid_argument("post_process: " + std::to_string(n) + " junctions but " +
                                std::to_string(in.confidences.size()) + " confidences");
  for (int k = 0; k < n; ++k)
    if (!finite(in.junctions[k]) || !std::isfinite(in.confidences[k]))
      throw std::invalid_argument("post_process: junction " + std::to_string(k) + " has a non-finite value");
  std::set<std::pair<int, int>> seen;
  for (size_t p = 0; p < in.pairs.size(); ++p) {
    const PairPrediction& q = in.pairs[p];
    const std::string where = "post_process: pair " + std::to_string(p) + " (" + std::to_string(q.i) + ", " +
                              std::to_string(q.j) + ")";
    if (q.i < 0 || q.j < 0 || q.i >= n || q.j >= n || q.i == q.j)
      throw std::invalid_argument(where + " needs two distinct junctions in 0.." + std::to_string(n - 1));
    if (!seen.insert({std::min(q.i, q.j), std::max(q.i, q.j)}).second)
      throw std::invalid_argument(where + " appears twice");
    for (double v : {q.merge, q.connect})
      if (!std::isfinite(v) || v < 0.0 || v > 1.0) throw std::invalid_argument(where + " has a probability outside [0, 1]");
  }
}

// Step 2: returns the deleted-junction mask.
std::vector<char> prune_identical(const PostProcessInput& in, const PostProcessOptions& o, PostProcessResult& out) {
  std::vector<char> deleted(in.junctions.size(), 0);
  std::vector<int> order;
  for (int p = 0; p < static_cast<int>(in.pairs.size()); ++p)
    if (in.pairs[p].merge > o.merge_threshold) order.push_back(p);
  if (order.empty()) out.notes.push_back("no pair with P(identical) > " + std::to_string(o.merge_threshold) + ": nothing pruned");
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return in.pairs[x].merge > in.pairs[y].merge; });
  for (int p : order) {
    int a = in.pairs[p].i, b = in.pairs[p].j;
    if (in.confidences[a] < in.confidences[b]) std::swap(a, b);
    if (deleted[a] && !o.prune_through_deleted) continue;
    if (!deleted[b]) {
      deleted[b] = 1;
      ++out.stats.pruned_junctions;
    }
  }
  return deleted;
}

std::vector<int> degrees(int n, const std::vector<Edge>& edges) {
  std::vector<int> deg(n, 0);
  for (const Edge& e : edges) ++deg[e.a], ++deg[e.b];
  return deg;
}

void sort_ascending(std::vector<Edge>& edges) {
  std::stable_sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.weight < y.weight; });
}

// Edge indices, highest score first (ties: list order): the order the greedy clean-ups keep edges in.
std::vector<int> by_descending_score(const std::vector<Edge>& edges) {
  std::vector<int> order(edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return edges[x].weight > edges[y].weight; });
  return order;
}

// Drops the edges marked in `dropped` (list order kept) and returns how many went.
int remove_marked(std::vector<Edge>& edges, const std::vector<char>& dropped) {
  std::vector<Edge> kept;
  for (size_t e = 0; e < edges.size(); ++e)
    if (!dropped[e]) kept.push_back(edges[e]);
  const int removed = static_cast<int>(edges.size() - kept.size());
  edges = std::move(kept);
  return removed;
}

// Step 5 (both endpoints of degree <= 1) and step 8 (any endpoint of degree <= 1): one pass, degrees
// computed once before it.
int remove_low_degree(int n, std::vector<Edge>& edges, bool both_endpoints) {
  const std::vector<int> deg = degrees(n, edges);
  const size_t before = edges.size();
  std::erase_if(edges, [&](const Edge& e) {
    return both_endpoints ? (deg[e.a] <= 1 && deg[e.b] <= 1) : (deg[e.a] <= 1 || deg[e.b] <= 1);
  });
  return static_cast<int>(before - edges.size());
}

// Step 6: Hamming junction merge on adjacency rows computed once.
void merge_junctions(const PostProcessInput& in, const std::vector<char>& pruned, const PostProcessOptions& o,
                     std::vector<Edge>& edges, PostProcessResult& out) {
  const int n = static_cast<int>(in.junctions.size());
  const int words = (n + 63) / 64;
  std::vector<uint64_t> rows(static_cast<size_t>(n) * words, 0);
  for (const Edge& e : edges) {
    rows[static_cast<size_t>(e.a) * words + e.b / 64] |= uint64_t{1} << (e.b % 64);
    rows[static_cast<size_t>(e.b) * words + e.a / 64] |= uint64_t{1} << (e.a % 64);
  }
  auto hamming = [&](int i, int j) {
    int d = 0;
    for (int w = 0; w < words; ++w) d += std::popcount(rows[static_cast<size_t>(i) * words + w] ^ rows[static_cast<size_t>(j) * words + w]);
    return d;
  };
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return in.confidences[x] > in.confidences[y]; });
  const double r2 = o.junction_merge_distance * o.junction_merge_distance;
  std::vector<int> survivor(n, -1);  // -1 = kept
  for (int i : order) {
    if (survivor[i] >= 0 || (pruned[i] && !o.pruned_junctions_in_merge)) continue;
    for (int j = 0; j < n; ++j) {
      if (j == i || survivor[j] >= 0 || (pruned[j] && !o.pruned_junctions_in_merge)) continue;
      if ((in.junctions[i] - in.junctions[j]).squaredNorm() < r2 && hamming(i, j) < o.hamming_threshold) {
        survivor[j] = i;
        if (!pruned[j]) ++out.stats.merged_junctions;
      }
    }
  }
  std::vector<Edge> kept;
  std::set<std::pair<int, int>> present;
  // Untouched edges first so a transferred duplicate never displaces an existing edge.
  for (const Edge& e : edges)
    if (survivor[e.a] < 0 && survivor[e.b] < 0) kept.push_back(e), present.insert({e.a, e.b});
  for (const Edge& e : edges) {
    if (survivor[e.a] < 0 && survivor[e.b] < 0) continue;
    if (!o.transfer_edges_on_merge) {
      ++out.stats.merge_removed_edges;
      continue;
    }
    const int a = survivor[e.a] < 0 ? e.a : survivor[e.a];
    const int b = survivor[e.b] < 0 ? e.b : survivor[e.b];
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    if (a == b) {
      ++out.stats.merge_removed_edges;
    } else if (!present.insert(key).second) {
      ++out.stats.merge_removed_edges;
      for (Edge& k : kept)
        if (k.a == key.first && k.b == key.second) k.weight = std::max(k.weight, e.weight);
    } else {
      kept.push_back({key.first, key.second, e.weight});
      ++out.stats.transferred_edges;
    }
  }
  sort_ascending(kept);
  edges = std::move(kept);
}

// Step 7: greedy line NMS; visiting order decides which of two near-duplicate edges stays.
int line_nms(const std::vector<Vec3>& pts, std::vector<Edge>& edges, const PostProcessOptions& o) {
  const int m = static_cast<int>(edges.size());
  std::vector<int> order(m);
  if (o.line_nms_keep_higher)
    order = by_descending_score(edges);
  else
    std::iota(order.begin(), order.end(), 0);
  std::vector<char> dropped(m, 0);
  for (int e : order) {
    if (dropped[e]) continue;
    for (int f = 0; f < m; ++f) {
      if (f == e || dropped[f]) continue;
      const double d = segment_pair_distance(pts[edges[e].a], pts[edges[e].b], pts[edges[f].a], pts[edges[f].b]);
      if (d < o.line_nms_distance) dropped[f] = 1;
    }
  }
  return remove_marked(edges, dropped);
}

// Not in the release: visited by descending score, an edge that crosses an edge already kept is dropped.
int remove_crossing_edges(const std::vector<Vec3>& pts, std::vector<Edge>& edges, const PostProcessOptions& o) {
  if (o.crossing_distance_m <= 0.0) return 0;
  constexpr double kMinCrossingAngleDeg = 10.0;  // closer to parallel is an overlap, line NMS's case
  const auto cross = [&](const Edge& a, const Edge& b) {
    const bool share_junction = a.a == b.a || a.a == b.b || a.b == b.a || a.b == b.b;
    return !share_junction && segments_cross(pts[a.a], pts[a.b], pts[b.a], pts[b.b], o.crossing_distance_m,
                                             o.crossing_end_margin_m, kMinCrossingAngleDeg);
  };
  std::vector<int> kept;  // by descending score
  std::vector<char> dropped(edges.size(), 0);
  for (int e : by_descending_score(edges)) {
    dropped[e] = std::any_of(kept.begin(), kept.end(), [&](int k) { return cross(edges[e], edges[k]); });
    if (!dropped[e]) kept.push_back(e);
  }
  return remove_marked(edges, dropped);
}

ScoredWireframe to_wireframe(const PostProcessInput& in, const std::vector<Edge>& edges) {
  ScoredWireframe all;
  all.wireframe.junctions = in.junctions;
  all.junction_scores = in.confidences;
  for (const Edge& e : edges) {
    all.wireframe.edges.push_back({e.a, e.b});
    all.edge_scores.push_back(e.weight);
  }
  return referenced_junctions_only(all);
}

}  // namespace

std::vector<std::array<int, 2>> all_pairs(int n) {
  std::vector<std::array<int, 2>> pairs;
  if (n < 2) return pairs;
  pairs.reserve(static_cast<size_t>(n) * (n - 1) / 2);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) pairs.push_back({i, j});
  return pairs;
}

PostProcessResult post_process(const PostProcessInput& in, const PostProcessOptions& o) {
  o.Check();
  check_input(in);
  PostProcessResult out;
  const int n = static_cast<int>(in.junctions.size());
  if (n < 2 || in.pairs.empty()) {
    out.notes.push_back(std::to_string(n) + " junction(s), " + std::to_string(in.pairs.size()) +
                        " pair(s): empty wireframe");
    return out;
  }
  const std::vector<char> pruned = prune_identical(in, o, out);

  std::vector<Edge> edges;
  for (const PairPrediction& q : in.pairs)
    if (q.connect > o.connect_threshold && !pruned[q.i] && !pruned[q.j])
      edges.push_back({std::min(q.i, q.j), std::max(q.i, q.j), q.connect});
  out.stats.candidate_edges = static_cast<int>(edges.size());
  sort_ascending(edges);
  out.candidates = to_wireframe(in, edges);
  if (edges.empty()) {
    out.notes.push_back("no pair with P(connected) > " + std::to_string(o.connect_threshold) + ": empty wireframe");
    return out;
  }

  out.stats.isolated_edges = remove_low_degree(n, edges, /*both_endpoints=*/true);
  merge_junctions(in, pruned, o, edges, out);
  out.stats.line_nms_edges = line_nms(in.junctions, edges, o);
  out.stats.crossing_edges = remove_crossing_edges(in.junctions, edges, o);
  out.stats.dangling_edges = remove_low_degree(n, edges, /*both_endpoints=*/false);
  if (edges.empty()) out.notes.push_back("every candidate edge was removed by the clean-up: empty wireframe");
  out.wireframe = to_wireframe(in, edges);
  return out;
}

}  // namespace lc2wf

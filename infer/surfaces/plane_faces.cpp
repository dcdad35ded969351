#include "infer/surfaces/plane_faces.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "dataset/geometry/wireframe_graph.h"

namespace lc2wf {
namespace {

// The plane's edges as local adjacency lists with 2D positions.
struct LocalGraph {
  std::vector<int> ids;                 // local -> junction id
  std::vector<Vec2> pos;                // local 2D positions in the plane's frame
  std::vector<std::vector<int>> adj;    // local neighbours
  std::vector<std::array<int, 2>> edges;  // local edges
};

LocalGraph local_graph(const Wireframe& wf, const CandidatePlane& cp) {
  LocalGraph g;
  std::map<int, int> local;
  const auto id_of = [&](int j) {
    const auto [it, fresh] = local.emplace(j, static_cast<int>(g.ids.size()));
    if (fresh) g.ids.push_back(j);
    return it->second;
  };
  for (int e : cp.edges) g.edges.push_back({id_of(wf.edges[e][0]), id_of(wf.edges[e][1])});
  const PlaneFrame frame = plane_frame(cp.plane.normal, wf.junctions[g.ids.empty() ? 0 : g.ids[0]]);
  for (int j : g.ids) g.pos.push_back(frame.to_2d(wf.junctions[j]));
  g.adj.assign(g.ids.size(), {});
  for (const auto& e : g.edges) {
    g.adj[e[0]].push_back(e[1]);
    g.adj[e[1]].push_back(e[0]);
  }
  return g;
}

// Edges on the shortest path from v to w (breadth first), 0 when w cannot be reached.
int hops(const LocalGraph& g, int v, int w) {
  std::vector<int> dist(g.ids.size(), -1);
  std::vector<int> queue{v};
  dist[v] = 0;
  for (size_t q = 0; q < queue.size(); ++q)
    for (int x : g.adj[queue[q]])
      if (dist[x] < 0) {
        dist[x] = dist[queue[q]] + 1;
        if (x == w) return dist[x];
        queue.push_back(x);
      }
  return 0;
}

}  // namespace

std::vector<std::vector<int>> plane_cycles(const Wireframe& wf, const CandidatePlane& cp, double eps, WorkBudget* budget) {
  constexpr const char* kStep = "faces per plane";
  // The local graph (a map), the angular sorting (atan2) and the walks: about ten junction tests per edge.
  if (budget && !budget->charge(10 * static_cast<long>(cp.edges.size()), kStep)) return {};
  LocalGraph g = local_graph(wf, cp);
  const int n = static_cast<int>(g.ids.size());
  // Prune dangling edges: they bound no face and would make a face walk out and back.
  std::vector<int> degree(n);
  for (int v = 0; v < n; ++v) degree[v] = static_cast<int>(g.adj[v].size());
  std::vector<bool> removed(n, false);
  std::vector<int> stack;
  for (int v = 0; v < n; ++v)
    if (degree[v] <= 1) stack.push_back(v);
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    if (removed[v]) continue;
    removed[v] = true;
    for (int w : g.adj[v])
      if (!removed[w] && --degree[w] <= 1) stack.push_back(w);
  }
  // Neighbours in counter-clockwise order of direction.
  for (int v = 0; v < n; ++v) {
    auto& a = g.adj[v];
    a.erase(std::remove_if(a.begin(), a.end(), [&](int w) { return removed[w]; }), a.end());
    std::sort(a.begin(), a.end(), [&](int x, int y) {
      const Vec2 dx = g.pos[x] - g.pos[v], dy = g.pos[y] - g.pos[v];
      return std::atan2(dx.y(), dx.x()) < std::atan2(dy.y(), dy.x());
    });
  }
  std::set<std::pair<int, int>> visited;
  std::vector<std::vector<int>> out;
  for (int u = 0; u < n; ++u) {
    for (int v0 : g.adj[u]) {
      if (visited.count({u, v0})) continue;
      // Walk with the face on the left: at each junction turn to the neighbour just clockwise of where we came from.
      std::vector<int> ring;
      int a = u, b = v0;
      bool ok = true;
      while (!visited.count({a, b})) {
        visited.insert({a, b});
        ring.push_back(a);
        const auto& nb = g.adj[b];
        const int k = static_cast<int>(std::find(nb.begin(), nb.end(), a) - nb.begin());
        const int c = nb[(k + static_cast<int>(nb.size()) - 1) % nb.size()];
        a = b;
        b = c;
        if (ring.size() > g.edges.size() + 1) {
          ok = false;
          break;
        }
      }
      if (!ok || a != u || b != v0 || ring.size() < 3) continue;
      if (budget && !budget->charge(static_cast<long>(ring.size() * ring.size()), kStep)) return out;
      std::vector<Vec2> poly;
      for (int v : ring) poly.push_back(g.pos[v]);
      if (signed_area(poly) <= eps * eps || polygon_self_intersects(poly, eps)) continue;
      std::vector<int> ids;
      for (int v : ring) ids.push_back(g.ids[v]);
      out.push_back(std::move(ids));
    }
  }
  return out;
}

std::vector<ClosingEdge> closing_edges(const Wireframe& wf, const CandidatePlane& cp, double eps, WorkBudget* budget) {
  constexpr const char* kStep = "gaps";
  if (budget && !budget->charge(8 * static_cast<long>(cp.edges.size()), kStep)) return {};  // the local graph
  const LocalGraph g = local_graph(wf, cp);
  const int n = static_cast<int>(g.ids.size());
  const std::vector<int> part = connected_parts(n, g.edges);
  std::vector<int> open;
  for (int v = 0; v < n; ++v)
    if (g.adj[v].size() == 1) open.push_back(v);
  const long ends = static_cast<long>(open.size());
  if (budget && !budget->charge(2 * ends * ends, kStep)) return {};  // nearest ends, partners of each end
  // Bounded work on graphs with many loose ends: only the nearest few partners of each end are tried.
  constexpr size_t kMaxPartners = 6;
  std::vector<ClosingEdge> out;
  std::vector<int> nearest(n, -1);
  for (int v : open) {
    double best = INFINITY;
    for (int w : open)
      if (w != v && (g.pos[w] - g.pos[v]).norm() < best) best = (g.pos[w] - g.pos[v]).norm(), nearest[v] = w;
  }
  std::set<std::pair<int, int>> tried;
  for (int v : open) {
    std::vector<int> partners;
    for (int w : open)
      if (w != v && part[w] == part[v]) partners.push_back(w);
    std::sort(partners.begin(), partners.end(), [&](int x, int y) {
      return (g.pos[x] - g.pos[v]).norm() < (g.pos[y] - g.pos[v]).norm();
    });
    if (partners.size() > kMaxPartners) partners.resize(kMaxPartners);
    for (int w : partners) {
      if (!tried.insert({std::min(v, w), std::max(v, w)}).second) continue;
      // The crossing test against every edge of the plane and the path between the ends.
      if (budget && !budget->charge(2 * static_cast<long>(g.edges.size()) + n, kStep)) return out;
      if (std::find(g.adj[v].begin(), g.adj[v].end(), w) != g.adj[v].end()) continue;
      bool crosses = false;
      for (const auto& e : g.edges)
        if (segments_cross(g.pos[v], g.pos[w], g.pos[e[0]], g.pos[e[1]], eps)) {
          crosses = true;
          break;
        }
      if (crosses) continue;
      const int a = g.ids[v], b = g.ids[w];
      out.push_back({{std::min(a, b), std::max(a, b)}, nearest[v] == w && nearest[w] == v, hops(g, v, w)});
    }
  }
  return out;
}

}  // namespace lc2wf

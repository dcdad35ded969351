#include "infer/surfaces/shell_assembly.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>

#include "infer/surfaces/polygon_geometry.h"

namespace lc2wf {
namespace {

using EdgeKey = std::pair<int, int>;
EdgeKey key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

std::vector<Vec3> points_of(const std::vector<int>& ring, const std::vector<Vec3>& vertices) {
  std::vector<Vec3> out;
  for (int v : ring) out.push_back(vertices[v]);
  return out;
}

// Direction (+1 / -1) in which a ring runs the side a-b, 0 when it does not contain it.
int direction(const std::vector<int>& ring, int a, int b) {
  for (size_t i = 0; i < ring.size(); ++i) {
    const int p = ring[i], q = ring[(i + 1) % ring.size()];
    if (p == a && q == b) return 1;
    if (p == b && q == a) return -1;
  }
  return 0;
}

// Faces grouped by the sides they share (each side shared by exactly two faces links them).
std::map<EdgeKey, std::vector<int>> faces_by_side(const std::vector<std::vector<int>>& rings) {
  std::map<EdgeKey, std::vector<int>> out;
  for (size_t f = 0; f < rings.size(); ++f)
    for (size_t i = 0; i < rings[f].size(); ++i) out[key(rings[f][i], rings[f][(i + 1) % rings[f].size()])].push_back(static_cast<int>(f));
  return out;
}

// Consistent orientation inside each group of faces linked by two-face sides: flips[f] says whether f is
// reversed; `component[f]` the group. False when a side cannot be run in opposite directions.
bool propagate_orientation(const std::vector<std::vector<int>>& rings, std::vector<bool>& flip, std::vector<int>& component) {
  const auto sides = faces_by_side(rings);
  std::vector<std::vector<std::pair<int, EdgeKey>>> links(rings.size());
  for (const auto& [side, fs] : sides)
    if (fs.size() == 2) {
      links[fs[0]].push_back({fs[1], side});
      links[fs[1]].push_back({fs[0], side});
    }
  flip.assign(rings.size(), false);
  component.assign(rings.size(), -1);
  bool consistent = true;
  int next = 0;
  for (size_t s = 0; s < rings.size(); ++s) {
    if (component[s] >= 0) continue;
    std::vector<int> queue{static_cast<int>(s)};
    component[s] = next;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      for (const auto& [g, side] : links[f]) {
        const int df = direction(rings[f], side.first, side.second) * (flip[f] ? -1 : 1);
        const int dg_raw = direction(rings[g], side.first, side.second);
        if (component[g] < 0) {
          component[g] = next;
          flip[g] = dg_raw == df;  // g must run the side against f
          queue.push_back(g);
        } else if (dg_raw * (flip[g] ? -1 : 1) == df) {
          consistent = false;
        }
      }
    }
    ++next;
  }
  return consistent;
}

}  // namespace

std::vector<int> select_shell_faces(const std::vector<CandidateFace>& faces, const std::set<std::pair<int, int>>& added) {
  std::map<EdgeKey, int> edge_id;
  std::vector<std::vector<int>> face_edges(faces.size());
  std::vector<bool> is_added;
  for (size_t f = 0; f < faces.size(); ++f) {
    const auto& r = faces[f].ring;
    for (size_t i = 0; i < r.size(); ++i) {
      const EdgeKey k = key(r[i], r[(i + 1) % r.size()]);
      const auto [it, fresh] = edge_id.emplace(k, static_cast<int>(edge_id.size()));
      if (fresh) is_added.push_back(added.count(k) > 0);
      face_edges[f].push_back(it->second);
    }
  }
  std::vector<int> count(edge_id.size(), 0);
  for (const auto& fe : face_edges)
    for (int e : fe) ++count[e];
  std::vector<bool> kept(faces.size(), true);
  const auto gain = [&](size_t f) {
    int g = 0;
    for (int e : face_edges[f]) {
      if (count[e] >= 3) g += 1;
      else if (count[e] == 2) g -= 1;
      else if (is_added[e]) g += 1;  // an added side only this face uses: the gap it closed was no face's
    }
    return g;
  };
  // The face whose removal lowers the defects most goes first; on ties the later candidate (from a plane with
  // fewer votes). A removal changes the gains of the faces sharing its sides only: a heap with the current
  // gain of each face (stale entries skipped) finds the same face as a scan of all faces would.
  std::vector<std::vector<int>> faces_of_edge(edge_id.size());
  for (size_t f = 0; f < faces.size(); ++f)
    for (int e : face_edges[f]) faces_of_edge[e].push_back(static_cast<int>(f));
  std::vector<int> current(faces.size());
  std::priority_queue<std::pair<int, int>> heap;  // (gain, face): largest gain, then largest index
  for (size_t f = 0; f < faces.size(); ++f) {
    current[f] = gain(f);
    heap.push({current[f], static_cast<int>(f)});
  }
  while (!heap.empty()) {
    const auto [g, best] = heap.top();
    heap.pop();
    if (!kept[best] || g != current[best]) continue;  // removed, or its gain changed since
    if (g <= 0) break;
    kept[best] = false;
    for (int e : face_edges[best]) --count[e];
    for (int e : face_edges[best])
      for (int f : faces_of_edge[e])
        if (kept[f]) {
          const int now = gain(f);
          if (now != current[f]) current[f] = now, heap.push({now, f});
        }
  }
  std::vector<int> out;
  for (size_t f = 0; f < faces.size(); ++f)
    if (kept[f]) out.push_back(static_cast<int>(f));
  return out;
}

std::vector<CandidateFace> merge_coplanar_faces(const std::vector<CandidateFace>& faces, const std::vector<Vec3>& vertices,
                                                double max_angle_deg) {
  const int n = static_cast<int>(faces.size());
  std::vector<Vec3> normals;
  for (const auto& f : faces) normals.push_back(newell_normal(points_of(f.ring, vertices)));
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<std::vector<int>> rings;
  for (const auto& f : faces) rings.push_back(f.ring);
  for (const auto& [side, fs] : faces_by_side(rings))
    if (fs.size() == 2 && plane_angle_deg(normals[fs[0]], normals[fs[1]]) < max_angle_deg) parent[root(fs[0])] = root(fs[1]);
  std::map<int, std::vector<int>> groups;
  for (int f = 0; f < n; ++f) groups[root(f)].push_back(f);

  std::vector<CandidateFace> out;
  std::vector<bool> emitted(n, false);
  for (int f = 0; f < n; ++f) {
    if (emitted[f]) continue;
    const std::vector<int>& group = groups[root(f)];
    for (int g : group) emitted[g] = true;
    if (group.size() == 1) {
      out.push_back(faces[f]);
      continue;
    }
    std::vector<std::vector<int>> local;
    for (int g : group) local.push_back(faces[g].ring);
    std::vector<bool> flip;
    std::vector<int> component;
    propagate_orientation(local, flip, component);
    // Sides run both ways cancel; the rest is the union's boundary.
    std::map<EdgeKey, int> directed;  // (from, to) -> times
    for (size_t k = 0; k < local.size(); ++k) {
      std::vector<int> r = local[k];
      if (flip[k]) std::reverse(r.begin(), r.end());
      for (size_t i = 0; i < r.size(); ++i) ++directed[{r[i], r[(i + 1) % r.size()]}];
    }
    std::map<int, std::vector<int>> next;
    int boundary = 0;
    for (const auto& [he, times] : directed)
      if (!directed.count({he.second, he.first})) {
        for (int t = 0; t < times; ++t) next[he.first].push_back(he.second), ++boundary;
      }
    bool single = boundary >= 3 && std::all_of(next.begin(), next.end(), [](const auto& kv) { return kv.second.size() == 1; });
    std::vector<int> ring;
    if (single) {
      int v = next.begin()->first;
      do {
        ring.push_back(v);
        const auto out_of = next.find(v);  // a side may end at a vertex no side leaves: no single loop then
        if (out_of == next.end()) break;
        v = out_of->second[0];
      } while (v != ring.front() && ring.size() <= static_cast<size_t>(boundary));
      single = v == ring.front() && static_cast<int>(ring.size()) == boundary;
    }
    if (!single) {
      for (int g : group) out.push_back(faces[g]);
      continue;
    }
    out.push_back({ring, faces[f].plane});
  }
  return out;
}

bool orient_faces(std::vector<std::vector<int>>& rings, const std::vector<Vec3>& vertices, std::vector<std::string>* reasons) {
  std::vector<bool> flip;
  std::vector<int> component;
  const bool consistent = propagate_orientation(rings, flip, component);
  for (size_t f = 0; f < rings.size(); ++f)
    if (flip[f]) std::reverse(rings[f].begin(), rings[f].end());
  if (!consistent && reasons) reasons->push_back("the faces cannot be oriented consistently");
  // Outward: the signed volume about the part's centroid is positive for a closed part (and a fair vote for an open one).
  const int parts = rings.empty() ? 0 : *std::max_element(component.begin(), component.end()) + 1;
  for (int c = 0; c < parts; ++c) {
    Vec3 centre = Vec3::Zero();
    int count = 0;
    for (size_t f = 0; f < rings.size(); ++f)
      if (component[f] == c)
        for (int v : rings[f]) centre += vertices[v], ++count;
    centre /= std::max(1, count);
    double volume = 0;
    for (size_t f = 0; f < rings.size(); ++f) {
      if (component[f] != c) continue;
      const auto& r = rings[f];
      for (size_t i = 1; i + 1 < r.size(); ++i)
        volume += (vertices[r[0]] - centre).dot((vertices[r[i]] - centre).cross(vertices[r[i + 1]] - centre));
    }
    if (volume < 0)
      for (size_t f = 0; f < rings.size(); ++f)
        if (component[f] == c) std::reverse(rings[f].begin(), rings[f].end());
  }
  return consistent;
}

void snap_vertices_to_planes(std::vector<Vec3>& vertices, const std::vector<std::vector<int>>& rings, double max_move,
                             int iterations) {
  constexpr double kAnchor = 1e-3;  // keeps vertices on fewer than three planes near where they were
  std::vector<std::vector<int>> faces_of(vertices.size());
  for (size_t f = 0; f < rings.size(); ++f)
    for (int v : rings[f]) faces_of[v].push_back(static_cast<int>(f));
  for (int it = 0; it < iterations; ++it) {
    std::vector<Plane> planes;
    for (const auto& r : rings) planes.push_back(fit_plane(points_of(r, vertices)));
    std::vector<Vec3> moved = vertices;
    for (size_t v = 0; v < vertices.size(); ++v) {
      if (faces_of[v].empty()) continue;
      Eigen::Matrix3d A = kAnchor * Eigen::Matrix3d::Identity();
      Vec3 b = kAnchor * vertices[v];
      for (int f : faces_of[v]) {
        const Plane& p = planes[f];
        A += p.normal * p.normal.transpose();
        b += p.normal * p.offset;
      }
      moved[v] = A.ldlt().solve(b);
      if (!moved[v].allFinite() || (moved[v] - vertices[v]).norm() > max_move) {
        Vec3 mean = Vec3::Zero();
        for (int f : faces_of[v]) mean += vertices[v] - planes[f].normal * planes[f].distance(vertices[v]);
        moved[v] = mean / static_cast<double>(faces_of[v].size());
      }
    }
    vertices = std::move(moved);
  }
}

}  // namespace lc2wf

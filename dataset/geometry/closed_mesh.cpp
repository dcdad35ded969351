#include "dataset/geometry/closed_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "dataset/geometry/building.h"

namespace lc2wf {
namespace {

using EdgeKey = std::pair<int, int>;
EdgeKey undirected(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// Distance of p from segment ab when p projects strictly inside it, else infinity.
double distance_inside_segment(const Vec3& p, const Vec3& a, const Vec3& b, double tol, double* t_out = nullptr) {
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  if (len2 <= 0) return std::numeric_limits<double>::infinity();
  const double t = (p - a).dot(d) / len2;
  const double len = std::sqrt(len2);
  if (t * len <= tol || (1 - t) * len <= tol) return std::numeric_limits<double>::infinity();
  if (t_out) *t_out = t;
  return (a + t * d - p).norm();
}

std::set<EdgeKey> unique_edges(const PolyMesh& m) {
  std::set<EdgeKey> edges;
  for (const auto& f : m.faces)
    for (size_t k = 0; k < f.size(); ++k) edges.insert(undirected(f[k], f[(k + 1) % f.size()]));
  return edges;
}

// Inserts into every face edge the vertices lying strictly inside it, in order along the edge.
void split_edges_at_vertices(PolyMesh& m, double tol) {
  for (auto& f : m.faces) {
    std::vector<int> out;
    for (size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      out.push_back(a);
      std::vector<std::pair<double, int>> inner;
      for (size_t v = 0; v < m.vertices.size(); ++v) {
        double t = 0;
        if (static_cast<int>(v) != a && static_cast<int>(v) != b &&
            distance_inside_segment(m.vertices[v], m.vertices[a], m.vertices[b], tol, &t) <= tol)
          inner.emplace_back(t, static_cast<int>(v));
      }
      std::sort(inner.begin(), inner.end());
      for (const auto& [t, v] : inner) out.push_back(v);
    }
    f = std::move(out);
  }
}

// Removes vertices with exactly two neighbours in line with them (they only continue a straight edge).
void drop_straight_vertices(PolyMesh& m) {
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::set<int>> neighbours(m.vertices.size());
    for (const auto& [a, b] : unique_edges(m)) {
      neighbours[a].insert(b);
      neighbours[b].insert(a);
    }
    for (size_t v = 0; v < m.vertices.size(); ++v) {
      if (neighbours[v].size() != 2) continue;
      const Vec3 p = m.vertices[*neighbours[v].begin()] - m.vertices[v];
      const Vec3 q = m.vertices[*neighbours[v].rbegin()] - m.vertices[v];
      if (p.dot(q) >= 0 || p.cross(q).norm() > 1e-9 * p.norm() * q.norm()) continue;
      for (auto& f : m.faces) f.erase(std::remove(f.begin(), f.end(), static_cast<int>(v)), f.end());
      changed = true;
      break;
    }
  }
}

void drop_unused_vertices(PolyMesh& m) {
  std::vector<int> new_id(m.vertices.size(), -1);
  std::vector<Vec3> kept;
  for (auto& f : m.faces)
    for (int& v : f) {
      if (new_id[v] < 0) {
        new_id[v] = static_cast<int>(kept.size());
        kept.push_back(m.vertices[v]);
      }
      v = new_id[v];
    }
  m.vertices = std::move(kept);
}

}  // namespace

PolyMesh mesh_from_faces(const std::vector<PointFace>& faces, double tol) {
  PolyMesh m;
  const double tol2 = tol * tol;
  for (const PointFace& pf : faces) {
    std::vector<int> f;
    for (const Vec3& p : pf.points) {
      int id = -1;
      for (size_t i = 0; i < m.vertices.size() && id < 0; ++i)
        if ((m.vertices[i] - p).squaredNorm() <= tol2) id = static_cast<int>(i);
      if (id < 0) {
        id = static_cast<int>(m.vertices.size());
        m.vertices.push_back(p);
      }
      if (f.empty() || f.back() != id) f.push_back(id);
    }
    while (f.size() > 1 && f.front() == f.back()) f.pop_back();
    if (f.size() < 3) continue;
    m.faces.push_back(std::move(f));
    m.labels.push_back(pf.label);
  }
  split_edges_at_vertices(m, tol);
  drop_straight_vertices(m);
  drop_unused_vertices(m);
  return m;
}

ClosedMeshReport inspect_closed_mesh(const PolyMesh& m, double tol) {
  ClosedMeshReport r;
  const MeshReport base = analyse_mesh(m, tol);
  r.duplicate_vertex_pairs = base.duplicate_vertex_pairs;
  r.max_planarity_deviation = base.max_planarity_deviation;
  std::map<EdgeKey, std::vector<int>> directions;  // +1: walked from the smaller id, -1: from the larger
  std::vector<bool> used(m.vertices.size(), false);
  for (const auto& f : m.faces) {
    std::vector<int> sorted = f;
    std::sort(sorted.begin(), sorted.end());
    if (f.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) ++r.degenerate_faces;
    for (size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      used[a] = true;
      directions[undirected(a, b)].push_back(a < b ? 1 : -1);
      // Signed volume by a fan of triangles from the face's first corner.
      if (k >= 2) r.volume += m.vertices[f[0]].dot(m.vertices[f[k - 1]].cross(m.vertices[f[k]])) / 6.0;
    }
  }
  for (const auto& [e, dirs] : directions) {
    if (dirs.size() != 2) ++r.edges_not_shared_by_two;
    else if (dirs[0] == dirs[1]) ++r.edges_same_direction;
    for (size_t v = 0; v < m.vertices.size(); ++v)
      if (static_cast<int>(v) != e.first && static_cast<int>(v) != e.second &&
          distance_inside_segment(m.vertices[v], m.vertices[e.first], m.vertices[e.second], tol) <= tol)
        ++r.vertices_inside_edges;
  }
  r.unused_vertices = static_cast<int>(std::count(used.begin(), used.end(), false));
  r.min_vertex_distance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < m.vertices.size(); ++i)
    for (size_t j = i + 1; j < m.vertices.size(); ++j)
      r.min_vertex_distance = std::min(r.min_vertex_distance, (m.vertices[i] - m.vertices[j]).norm());
  return r;
}

}  // namespace lc2wf

#include "dataset/geometry/closed_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "dataset/geometry/building.h"

namespace lc2wf {
namespace {

// Whether point p lies on face f: within `tol` of its plane and inside its outline (even-odd rule in the
// plane of the two axes the face is least steep to).
bool on_face(const std::vector<Vec3>& v, const Ring& f, const Vec3& p, double tol) {
  const Vec3 nv = newell_vector(v, f);
  if (nv.norm() <= 0) return false;
  const Vec3 n = nv.normalized();
  if (std::abs(n.dot(p - ring_centroid(v, f))) > tol) return false;
  int drop = 0;
  n.cwiseAbs().maxCoeff(&drop);
  const int u = (drop + 1) % 3, w = (drop + 2) % 3;
  bool inside = false;
  for (size_t i = 0, j = f.size() - 1; i < f.size(); j = i++) {
    const Vec3 &a = v[f[i]], &b = v[f[j]];
    if ((a[w] > p[w]) != (b[w] > p[w]) && p[u] < (b[u] - a[u]) * (p[w] - a[w]) / (b[w] - a[w]) + a[u]) inside = !inside;
  }
  return inside;
}

// Whether the edge (a, b) of one face lies on a face that does not have both its ends.
bool edge_on_other_face(const PolyMesh& m, int a, int b, double tol) {
  const Vec3 mid = 0.5 * (m.vertices[a] + m.vertices[b]);
  for (const Ring& f : m.faces) {
    const bool has_edge = std::find(f.begin(), f.end(), a) != f.end() && std::find(f.begin(), f.end(), b) != f.end();
    if (!has_edge && on_face(m.vertices, f, mid, tol)) return true;
  }
  return false;
}

}  // namespace

PolyMesh mesh_from_faces(const std::vector<PointFace>& faces, const MeshRepairOptions& options) {
  options.Check();
  PolyMesh m;
  VertexWelder welder(options.weld_m);
  for (const PointFace& pf : faces) {
    Ring f = welder.add_ring(pf.points);
    if (f.empty()) continue;
    m.faces.push_back(std::move(f));
    m.labels.push_back(pf.label);
  }
  m.vertices = welder.take_vertices();
  conform_t_junctions(m.vertices, m.faces, options.on_edge_m);
  std::vector<int> kept;
  remove_collinear_vertices(m.vertices, m.faces, options.collinear_m, &kept);
  std::vector<FaceLabel> labels;
  for (int f : kept) labels.push_back(m.labels[f]);
  m.labels = std::move(labels);
  drop_unused_vertices(m.vertices, m.faces);
  return m;
}

void ClosedMeshOptions::Check() const {
  if (!(tol >= 0) || !std::isfinite(tol)) throw std::invalid_argument("ClosedMeshOptions.tol must be >= 0");
  if (!(on_face_tol >= 0) || !std::isfinite(on_face_tol)) throw std::invalid_argument("ClosedMeshOptions.on_face_tol must be >= 0");
}

ClosedMeshReport inspect_closed_mesh(const PolyMesh& m, const ClosedMeshOptions& options) {
  options.Check();
  ClosedMeshReport r;
  const MeshReport base = analyse_mesh(m, options.tol);
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
      directions[undirected_edge(a, b)].push_back(a < b ? 1 : -1);
      // Signed volume by a fan of triangles from the face's first corner.
      if (k >= 2) r.volume += m.vertices[f[0]].dot(m.vertices[f[k - 1]].cross(m.vertices[f[k]])) / 6.0;
    }
  }
  std::vector<int> all(m.vertices.size());
  std::iota(all.begin(), all.end(), 0);
  const EdgeInteriorIndex index(m.vertices, std::move(all), options.tol);
  for (const auto& [e, dirs] : directions) {
    if (dirs.size() != 2) ++r.edges_not_shared_by_two;
    else if (dirs[0] == dirs[1]) ++r.edges_same_direction;
    if (dirs.size() == 1) {
      ++r.edges_used_once;
      if (options.on_face_tol > 0 && edge_on_other_face(m, e.first, e.second, options.on_face_tol)) {
        ++r.edges_on_faces;
      } else {
        ++r.open_edges;
        r.open_length += (m.vertices[e.first] - m.vertices[e.second]).norm();
      }
    }
    r.vertices_inside_edges += static_cast<int>(index.inside(e.first, e.second).size());
  }
  r.unused_vertices = static_cast<int>(std::count(used.begin(), used.end(), false));
  r.min_vertex_distance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < m.vertices.size(); ++i)
    for (size_t j = i + 1; j < m.vertices.size(); ++j)
      r.min_vertex_distance = std::min(r.min_vertex_distance, (m.vertices[i] - m.vertices[j]).norm());
  return r;
}

}  // namespace lc2wf

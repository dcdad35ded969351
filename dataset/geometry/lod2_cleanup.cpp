#include "dataset/geometry/lod2_cleanup.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

#include "dataset/geometry/closed_mesh.h"
#include "dataset/geometry/mesh_repair.h"

namespace lc2wf {
namespace {

using Edge = EdgeKey;

int used_vertex_count(const Lod2Mesh& m) {
  std::vector<char> used(m.vertices.size(), 0);
  for (const auto& f : m.faces)
    for (int id : f) used[id] = 1;
  return static_cast<int>(std::count(used.begin(), used.end(), 1));
}

void erase_faces(Lod2Mesh& m, const std::vector<char>& drop) {
  Lod2Mesh out;
  out.vertices = std::move(m.vertices);
  for (size_t f = 0; f < m.faces.size(); ++f) {
    if (drop[f]) continue;
    out.faces.push_back(std::move(m.faces[f]));
    out.kinds.push_back(m.kinds[f]);
    out.parts.push_back(m.parts[f]);
  }
  m = std::move(out);
}

}  // namespace

void Lod2CleanupOptions::Check() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument(std::string("Lod2CleanupOptions.") + name + " must be > 0");
  };
  positive(weld_tol_m, "weld_tol_m");
  positive(coplanar_distance_m, "coplanar_distance_m");
  positive(sliver_height_m, "sliver_height_m");
  positive(on_edge_tol_m, "on_edge_tol_m");
  positive(collinear_tol_m, "collinear_tol_m");
  positive(ground_tol_m, "ground_tol_m");
  if (!(coplanar_angle_deg >= 0 && coplanar_angle_deg < 90))
    throw std::invalid_argument("Lod2CleanupOptions.coplanar_angle_deg must be in [0, 90)");
}

int drop_inner_rings(std::vector<CityPolygon>& polygons) {
  int n = 0;
  for (auto& p : polygons) {
    n += static_cast<int>(p.interiors.size());
    p.interiors.clear();
  }
  return n;
}

Lod2Mesh weld_polygons(const std::vector<CityPolygon>& polygons, double tol, Lod2CleanupReport* report) {
  Lod2Mesh m;
  VertexWelder welder(tol);
  for (const CityPolygon& p : polygons) {
    Ring f = welder.add_ring(p.exterior);
    if (f.empty()) {
      if (report) ++report->degenerate_faces_dropped;
      continue;
    }
    m.faces.push_back(std::move(f));
    m.kinds.push_back(p.kind);
    m.parts.push_back(p.part);
  }
  m.vertices = welder.take_vertices();
  if (report && tol > 0) {
    // Welded = distinct input positions that became another vertex.
    VertexWelder exact(0);
    for (const CityPolygon& p : polygons)
      for (const Vec3& v : p.exterior) exact.add(v);
    report->welded_vertices = static_cast<int>(exact.vertices().size() - m.vertices.size());
  }
  return m;
}

int classify_unlabelled_faces(Lod2Mesh& m, const Lod2CleanupOptions& o) {
  if (m.faces.empty()) return 0;
  double zmin = std::numeric_limits<double>::infinity();
  Vec3 centre = Vec3::Zero();
  int n = 0;
  for (const auto& f : m.faces)
    for (int id : f) {
      zmin = std::min(zmin, m.vertices[id].z());
      centre += m.vertices[id];
      ++n;
    }
  centre /= n;
  double volume = 0;  // signed, times 6
  for (const auto& f : m.faces)
    for (size_t k = 1; k + 1 < f.size(); ++k)
      volume += (m.vertices[f[0]] - centre).dot((m.vertices[f[k]] - centre).cross(m.vertices[f[k + 1]] - centre));
  const double sign = volume < 0 ? -1.0 : 1.0;
  const double vertical = std::sin(10.0 * M_PI / 180);
  int count = 0;
  for (size_t fi = 0; fi < m.faces.size(); ++fi) {
    if (m.kinds[fi] != CitySurface::kUnknown) continue;
    ++count;
    const Vec3 nrm = sign * newell_vector(m.vertices, m.faces[fi]).normalized();
    double ztop = -std::numeric_limits<double>::infinity();
    for (int id : m.faces[fi]) ztop = std::max(ztop, m.vertices[id].z());
    if (std::abs(nrm.z()) < vertical) m.kinds[fi] = CitySurface::kWall;
    else if (nrm.z() < 0) m.kinds[fi] = ztop <= zmin + o.ground_tol_m ? CitySurface::kGround : CitySurface::kWall;
    else m.kinds[fi] = CitySurface::kRoof;
  }
  return count;
}

namespace {

struct Plane {
  Vec3 normal_sum = Vec3::Zero();  // area-weighted
  Vec3 point_sum = Vec3::Zero();
  double area = 0;
  Vec3 normal() const { return normal_sum.normalized(); }
  Vec3 point() const { return point_sum / area; }
  void add(const Vec3& newell_vec, const Vec3& centroid) {
    const double a = 0.5 * newell_vec.norm();
    normal_sum += 0.5 * newell_vec;
    point_sum += a * centroid;
    area += a;
  }
};

// Boundary loops of a group of consistently oriented faces: directed edges that no opposite edge cancels,
// chained. Empty when they do not chain into closed loops.
std::vector<std::vector<int>> boundary_loops(const Lod2Mesh& m, const std::vector<int>& group) {
  std::map<Edge, int> directed;
  for (int f : group) {
    const auto& ring = m.faces[f];
    for (size_t k = 0; k < ring.size(); ++k) {
      const Edge e{ring[k], ring[(k + 1) % ring.size()]};
      auto rev = directed.find({e.second, e.first});
      if (rev != directed.end() && rev->second > 0) {
        if (--rev->second == 0) directed.erase(rev);
      } else {
        ++directed[e];
      }
    }
  }
  std::map<int, std::vector<int>> out;  // vertex -> successors (sorted: deterministic)
  size_t remaining = 0;
  for (const auto& [e, n] : directed)
    for (int k = 0; k < n; ++k) {
      out[e.first].push_back(e.second);
      ++remaining;
    }
  std::vector<std::vector<int>> loops;
  while (remaining > 0) {
    int start = -1;
    for (auto& [v, succ] : out)
      if (!succ.empty()) {
        start = v;
        break;
      }
    std::vector<int> loop{start};
    int cur = start;
    for (;;) {
      auto& succ = out[cur];
      if (succ.empty()) return {};  // an open chain: not a clean union
      const int next = succ.front();
      succ.erase(succ.begin());
      --remaining;
      if (next == start) break;
      loop.push_back(next);
      cur = next;
      if (loop.size() > 4 * m.vertices.size() + 8) return {};
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace

int merge_coplanar_faces(Lod2Mesh& m, const Lod2CleanupOptions& o) {
  conform_t_junctions(m.vertices, m.faces, o.weld_tol_m);
  const size_t nf = m.faces.size();
  std::vector<Vec3> nv(nf), cen(nf);
  std::vector<double> area(nf), thickness(nf);
  for (size_t f = 0; f < nf; ++f) {
    nv[f] = newell_vector(m.vertices, m.faces[f]);
    cen[f] = ring_centroid(m.vertices, m.faces[f]);
    area[f] = 0.5 * nv[f].norm();
    thickness[f] = 2 * area[f] / std::max(longest_edge(m.vertices, m.faces[f]), 1e-12);  // height under the longest edge
  }
  std::map<Edge, std::vector<int>> faces_of;
  for (size_t f = 0; f < nf; ++f) {
    const auto& r = m.faces[f];
    for (size_t k = 0; k < r.size(); ++k) faces_of[undirected_edge(r[k], r[(k + 1) % r.size()])].push_back(static_cast<int>(f));
  }
  // Whether face h runs along edge (a, b) from b to a (the opposite of its neighbour's direction).
  auto runs_opposite = [&](int h, int a, int b) {
    const auto& r = m.faces[h];
    for (size_t k = 0; k < r.size(); ++k)
      if (r[k] == b && r[(k + 1) % r.size()] == a) return true;
    return false;
  };
  const double cos_tol = std::cos(o.coplanar_angle_deg * M_PI / 180);
  std::vector<int> order(nf);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return area[x] > area[y]; });
  std::vector<int> group_of(nf, -1);
  std::vector<std::vector<int>> groups;
  for (int seed : order) {
    if (group_of[seed] >= 0) continue;
    const int g = static_cast<int>(groups.size());
    groups.push_back({seed});
    group_of[seed] = g;
    Plane plane;
    plane.add(nv[seed], cen[seed]);
    for (size_t q = 0; q < groups[g].size(); ++q) {
      const int f = groups[g][q];
      const auto& r = m.faces[f];
      for (size_t k = 0; k < r.size(); ++k) {
        const int a = r[k], b = r[(k + 1) % r.size()];
        for (int h : faces_of[undirected_edge(a, b)]) {
          if (group_of[h] >= 0 || m.kinds[h] != m.kinds[seed] || area[h] <= 0 || !runs_opposite(h, a, b)) continue;
          const Vec3 n = plane.normal(), p0 = plane.point();
          const double cosang = n.dot(nv[h].normalized());
          if (cosang <= 0) continue;
          if (cosang < cos_tol && thickness[h] > o.sliver_height_m) continue;
          bool near = true;
          for (int id : m.faces[h]) near = near && std::abs(n.dot(m.vertices[id] - p0)) <= o.coplanar_distance_m;
          if (!near) continue;
          group_of[h] = g;
          groups[g].push_back(h);
          plane.add(nv[h], cen[h]);
        }
      }
    }
  }
  Lod2Mesh out;
  out.vertices = m.vertices;
  int absorbed = 0;
  std::vector<int> first_of_group(groups.size());
  for (size_t g = 0; g < groups.size(); ++g) first_of_group[g] = *std::min_element(groups[g].begin(), groups[g].end());
  // Output in the order of each group's first face, so the result does not depend on the seed order.
  std::vector<int> gorder(groups.size());
  std::iota(gorder.begin(), gorder.end(), 0);
  std::sort(gorder.begin(), gorder.end(), [&](int x, int y) { return first_of_group[x] < first_of_group[y]; });
  for (int g : gorder) {
    std::vector<int> members = groups[g];
    std::sort(members.begin(), members.end());
    const int first = members.front();
    std::vector<std::vector<int>> faces;
    if (members.size() > 1) {
      Plane plane;
      for (int f : members) plane.add(nv[f], cen[f]);
      const Vec3 n = plane.normal();
      for (auto& loop : boundary_loops(m, members)) {
        if (loop.size() < 3) continue;
        const double signed_area = 0.5 * n.dot(newell_vector(m.vertices, loop));
        if (signed_area > 0) faces.push_back(std::move(loop));  // holes (negative) are dropped like inner rings
      }
    }
    if (faces.empty()) {
      for (int f : members) faces.push_back(m.faces[f]);  // not one clean union: kept as they are
    } else {
      absorbed += static_cast<int>(members.size() - faces.size());
    }
    for (auto& f : faces) {
      out.faces.push_back(std::move(f));
      out.kinds.push_back(m.kinds[first]);
      out.parts.push_back(m.parts[first]);
    }
  }
  m = std::move(out);
  return absorbed;
}

int remove_coincident_faces(Lod2Mesh& m) {
  std::map<std::vector<int>, std::vector<int>> by_set;
  for (size_t f = 0; f < m.faces.size(); ++f) {
    std::vector<int> key = m.faces[f];
    std::sort(key.begin(), key.end());
    key.erase(std::unique(key.begin(), key.end()), key.end());
    by_set[key].push_back(static_cast<int>(f));
  }
  // Direction of a face relative to another with the same vertices: the successor of the first's first vertex.
  auto successor = [&](int f, int v) {
    const auto& r = m.faces[f];
    for (size_t k = 0; k < r.size(); ++k)
      if (r[k] == v) return r[(k + 1) % r.size()];
    return -1;
  };
  std::vector<char> drop(m.faces.size(), 0);
  int removed = 0;
  for (const auto& [key, fs] : by_set) {
    if (fs.size() < 2) continue;
    const int v = m.faces[fs[0]][0];
    const int s = successor(fs[0], v);
    bool opposite = false;
    for (size_t k = 1; k < fs.size(); ++k) opposite = opposite || successor(fs[k], v) != s;
    for (size_t k = opposite ? 0 : 1; k < fs.size(); ++k) {
      drop[fs[k]] = 1;
      ++removed;
    }
  }
  if (removed) erase_faces(m, drop);
  return removed;
}

namespace {

// Step 6 on the LoD2 form: the faces it erases take their kind and part along.
int remove_collinear_vertices_with_kinds(Lod2Mesh& m, double tol) {
  std::vector<int> kept;
  const int removed = remove_collinear_vertices(m.vertices, m.faces, tol, &kept);
  std::vector<CitySurface> kinds;
  std::vector<int> parts;
  for (int f : kept) {
    kinds.push_back(m.kinds[f]);
    parts.push_back(m.parts[f]);
  }
  m.kinds = std::move(kinds);
  m.parts = std::move(parts);
  return removed;
}

}  // namespace

std::string closure_problem(const Lod2Mesh& m, std::string* reason, double on_face_tol) {
  auto fail = [&](const char* key, const std::string& text) {
    if (reason) *reason = key;
    return text;
  };
  if (m.faces.size() < 4) return fail("too_few_faces", std::to_string(m.faces.size()) + " faces after clean-up (a closed building needs at least 4)");
  ClosedMeshOptions closure;
  closure.on_face_tol = on_face_tol;
  const ClosedMeshReport r = inspect_closed_mesh(PolyMesh{m.vertices, m.faces, {}}, closure);
  if (r.open_edges > 0) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f", r.open_length);
    return fail("not_closed", "does not close: " + std::to_string(r.open_edges) + " edges belong to one face only (" + buf + " m)");
  }
  if (std::find(m.kinds.begin(), m.kinds.end(), CitySurface::kRoof) == m.kinds.end()) return fail("no_roof", "no roof face");
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& f : m.faces)
    for (int id : f) {
      lo = lo.cwiseMin(m.vertices[id]);
      hi = hi.cwiseMax(m.vertices[id]);
    }
  if ((hi - lo).minCoeff() <= 0) return fail("flat", "all vertices lie in one axis plane (no volume)");
  if (reason) reason->clear();
  return {};
}

PolyMesh to_poly_mesh(const Lod2Mesh& m) {
  PolyMesh out{m.vertices, m.faces, {}};
  drop_unused_vertices(out.vertices, out.faces);
  for (CitySurface k : m.kinds)
    out.labels.push_back(k == CitySurface::kRoof ? FaceLabel::Roof : k == CitySurface::kGround ? FaceLabel::Base : FaceLabel::Wall);
  return out;
}

Lod2CleanupResult cleanup_lod2(std::vector<CityPolygon> polygons, const Lod2CleanupOptions& o) {
  o.Check();
  Lod2CleanupResult res;
  Lod2CleanupReport& rep = res.report;
  rep.input_polygons = static_cast<int>(polygons.size());
  {
    // Before: every ring, exact coordinates.
    std::vector<CityPolygon> rings;
    for (const auto& p : polygons) {
      rings.push_back({p.exterior, {}, p.kind, p.part});
      for (const auto& r : p.interiors) rings.push_back({r, {}, p.kind, p.part});
    }
    Lod2Mesh exact;
    VertexWelder w0(0);
    for (const auto& r : rings) {
      Ring f;
      for (const Vec3& v : r.exterior) f.push_back(w0.add(v));
      f = tidy_ring(f);
      if (!f.empty()) exact.faces.push_back(std::move(f));
    }
    exact.vertices = w0.take_vertices();
    rep.vertices_before = used_vertex_count(exact);
    rep.edges_before = static_cast<int>(unique_edges(exact.faces).size());
  }
  if (polygons.empty()) {
    res.skip_reason = "no_polygons";
    res.skip_detail = "no LoD2 polygons";
    return res;
  }
  rep.inner_rings_dropped = drop_inner_rings(polygons);
  Lod2Mesh m = weld_polygons(polygons, o.weld_tol_m, &rep);
  rep.unlabelled_faces = classify_unlabelled_faces(m, o);
  rep.faces_merged = merge_coplanar_faces(m, o);
  rep.coincident_faces_removed = remove_coincident_faces(m);
  rep.t_junction_vertices = conform_t_junctions(m.vertices, m.faces, o.on_edge_tol_m);
  rep.collinear_vertices_removed = remove_collinear_vertices_with_kinds(m, o.collinear_tol_m);
  rep.vertices_after = used_vertex_count(m);
  rep.edges_after = static_cast<int>(unique_edges(m.faces).size());
  rep.faces_after = static_cast<int>(m.faces.size());
  rep.roof_faces_after = static_cast<int>(std::count(m.kinds.begin(), m.kinds.end(), CitySurface::kRoof));
  res.skip_detail = closure_problem(m, &res.skip_reason, o.coplanar_distance_m);
  if (res.skip_reason.empty()) res.mesh = to_poly_mesh(m);
  return res;
}

}  // namespace lc2wf

#include "dataset/geometry/lod2_cleanup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace lc2wf {
namespace {

using Edge = std::pair<int, int>;
Edge undirected(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// Newell vector: twice the area times the unit normal (robust for non-convex, slightly non-planar rings).
Vec3 newell(const std::vector<Vec3>& v, const std::vector<int>& f) {
  Vec3 n = Vec3::Zero();
  for (size_t k = 0; k < f.size(); ++k) n += v[f[k]].cross(v[f[(k + 1) % f.size()]]);
  return n;
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b, double* t_out = nullptr) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  if (t_out) *t_out = t;
  return (p - (a + t * ab)).norm();
}

double longest_edge(const std::vector<Vec3>& v, const std::vector<int>& f) {
  double l = 0;
  for (size_t k = 0; k < f.size(); ++k) l = std::max(l, (v[f[k]] - v[f[(k + 1) % f.size()]]).norm());
  return l;
}

std::set<Edge> unique_edges(const Lod2Mesh& m) {
  std::set<Edge> e;
  for (const auto& f : m.faces)
    for (size_t k = 0; k < f.size(); ++k)
      if (f[k] != f[(k + 1) % f.size()]) e.insert(undirected(f[k], f[(k + 1) % f.size()]));
  return e;
}

int used_vertex_count(const Lod2Mesh& m) {
  std::vector<char> used(m.vertices.size(), 0);
  for (const auto& f : m.faces)
    for (int id : f) used[id] = 1;
  return static_cast<int>(std::count(used.begin(), used.end(), 1));
}

// Removes repeated consecutive ids (and a closing repeat); empty when fewer than 3 distinct ids remain.
std::vector<int> tidy_ring(const std::vector<int>& f) {
  std::vector<int> out;
  for (int id : f)
    if (out.empty() || out.back() != id) out.push_back(id);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  std::vector<int> distinct = out;
  std::sort(distinct.begin(), distinct.end());
  if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() < 3) return {};
  return out;
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

// Vertex welding by a hash grid of cell `tol`: a point joins the first earlier vertex within tol.
class Welder {
 public:
  explicit Welder(double tol) : tol_(tol) {}
  int add(const Vec3& p, std::vector<Vec3>& vertices) {
    if (tol_ > 0) {
      const auto c = cell(p);
      int best = -1;
      for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy)
          for (long long dz = -1; dz <= 1; ++dz) {
            const auto it = grid_.find(key(c[0] + dx, c[1] + dy, c[2] + dz));
            if (it == grid_.end()) continue;
            for (int id : it->second)
              if ((vertices[id] - p).norm() <= tol_ && (best < 0 || id < best)) best = id;
          }
      if (best >= 0) return best;
      grid_[key(c[0], c[1], c[2])].push_back(static_cast<int>(vertices.size()));
    } else {
      const auto it = exact_.find({p.x(), p.y(), p.z()});
      if (it != exact_.end()) return it->second;
      exact_.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, static_cast<int>(vertices.size()));
    }
    vertices.push_back(p);
    return static_cast<int>(vertices.size()) - 1;
  }

 private:
  std::array<long long, 3> cell(const Vec3& p) const {
    return {static_cast<long long>(std::floor(p.x() / tol_)), static_cast<long long>(std::floor(p.y() / tol_)),
            static_cast<long long>(std::floor(p.z() / tol_))};
  }
  static unsigned long long key(long long x, long long y, long long z) {
    return (static_cast<unsigned long long>(x) * 73856093ull) ^ (static_cast<unsigned long long>(y) * 19349663ull) ^
           (static_cast<unsigned long long>(z) * 83492791ull);
  }
  double tol_;
  std::unordered_map<unsigned long long, std::vector<int>> grid_;
  std::map<std::array<double, 3>, int> exact_;
};

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
  Welder welder(tol);
  int raw_points = 0;
  for (const CityPolygon& p : polygons) {
    std::vector<int> f;
    for (const Vec3& v : p.exterior) {
      f.push_back(welder.add(v, m.vertices));
      ++raw_points;
    }
    f = tidy_ring(f);
    // No area: every vertex within tol of the line of its longest edge (a sliver of zero width).
    if (f.empty() || newell(m.vertices, f).norm() <= tol * longest_edge(m.vertices, f)) {
      if (report) ++report->degenerate_faces_dropped;
      continue;
    }
    m.faces.push_back(std::move(f));
    m.kinds.push_back(p.kind);
    m.parts.push_back(p.part);
  }
  if (report && tol > 0) {
    // Welded = distinct input positions that became another vertex.
    Lod2Mesh exact;
    Welder w0(0);
    for (const CityPolygon& p : polygons)
      for (const Vec3& v : p.exterior) w0.add(v, exact.vertices);
    report->welded_vertices = static_cast<int>(exact.vertices.size() - m.vertices.size());
  }
  (void)raw_points;
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
    const Vec3 nrm = sign * newell(m.vertices, m.faces[fi]).normalized();
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

Vec3 centroid(const std::vector<Vec3>& v, const std::vector<int>& f) {
  Vec3 c = Vec3::Zero();
  for (int id : f) c += v[id];
  return c / static_cast<double>(f.size());
}

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
  conform_t_junctions(m, o.weld_tol_m);
  const size_t nf = m.faces.size();
  std::vector<Vec3> nv(nf), cen(nf);
  std::vector<double> area(nf), thickness(nf);
  for (size_t f = 0; f < nf; ++f) {
    nv[f] = newell(m.vertices, m.faces[f]);
    cen[f] = centroid(m.vertices, m.faces[f]);
    area[f] = 0.5 * nv[f].norm();
    thickness[f] = 2 * area[f] / std::max(longest_edge(m.vertices, m.faces[f]), 1e-12);  // height under the longest edge
  }
  std::map<Edge, std::vector<int>> faces_of;
  for (size_t f = 0; f < nf; ++f) {
    const auto& r = m.faces[f];
    for (size_t k = 0; k < r.size(); ++k) faces_of[undirected(r[k], r[(k + 1) % r.size()])].push_back(static_cast<int>(f));
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
        for (int h : faces_of[undirected(a, b)]) {
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
        const double signed_area = 0.5 * n.dot(newell(m.vertices, loop));
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

int conform_t_junctions(Lod2Mesh& m, double tol) {
  std::vector<int> used;
  {
    std::vector<char> u(m.vertices.size(), 0);
    for (const auto& f : m.faces)
      for (int id : f) u[id] = 1;
    for (size_t i = 0; i < u.size(); ++i)
      if (u[i]) used.push_back(static_cast<int>(i));
  }
  std::sort(used.begin(), used.end(), [&](int a, int b) { return m.vertices[a].x() < m.vertices[b].x() || (m.vertices[a].x() == m.vertices[b].x() && a < b); });
  std::vector<double> xs;
  for (int id : used) xs.push_back(m.vertices[id].x());
  int inserted = 0;
  for (auto& f : m.faces) {
    std::vector<int> out;
    for (size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      out.push_back(a);
      const Vec3 &pa = m.vertices[a], &pb = m.vertices[b];
      const double len = (pb - pa).norm();
      if (len <= 2 * tol) continue;
      const double lo = std::min(pa.x(), pb.x()) - tol, hi = std::max(pa.x(), pb.x()) + tol;
      std::vector<std::pair<double, int>> on;
      for (size_t i = std::lower_bound(xs.begin(), xs.end(), lo) - xs.begin(); i < xs.size() && xs[i] <= hi; ++i) {
        const int v = used[i];
        if (v == a || v == b) continue;
        double t = 0;
        if (point_segment_distance(m.vertices[v], pa, pb, &t) > tol) continue;
        if (t * len <= tol || (1 - t) * len <= tol) continue;  // at an end: a near-duplicate, not a T
        on.push_back({t, v});
      }
      std::sort(on.begin(), on.end());
      for (const auto& [t, v] : on) {
        out.push_back(v);
        ++inserted;
      }
    }
    f = tidy_ring(out).empty() ? f : tidy_ring(out);
  }
  return inserted;
}

int remove_collinear_vertices(Lod2Mesh& m, double tol) {
  int removed_total = 0;
  for (;;) {
    std::vector<std::set<int>> nbrs(m.vertices.size());
    for (const Edge& e : unique_edges(m)) {
      nbrs[e.first].insert(e.second);
      nbrs[e.second].insert(e.first);
    }
    std::vector<char> remove(m.vertices.size(), 0), blocked(m.vertices.size(), 0);
    int removed = 0;
    for (size_t v = 0; v < m.vertices.size(); ++v) {
      if (nbrs[v].size() != 2 || blocked[v]) continue;
      const int a = *nbrs[v].begin(), b = *nbrs[v].rbegin();
      if (point_segment_distance(m.vertices[v], m.vertices[a], m.vertices[b]) > tol) continue;
      remove[v] = 1;
      blocked[a] = blocked[b] = 1;  // one of two neighbouring candidates per pass: errors do not add up
      ++removed;
    }
    if (removed == 0) break;
    removed_total += removed;
    std::vector<char> drop(m.faces.size(), 0);
    for (size_t f = 0; f < m.faces.size(); ++f) {
      std::vector<int> r;
      for (int id : m.faces[f])
        if (!remove[id]) r.push_back(id);
      r = tidy_ring(r);
      if (r.empty()) drop[f] = 1;
      m.faces[f] = std::move(r);
    }
    if (std::count(drop.begin(), drop.end(), 1)) erase_faces(m, drop);
  }
  return removed_total;
}

namespace {

// Whether point p lies on face f: within `tol` of its plane and inside its outline (even-odd rule in the
// plane of the two axes the face is least steep to).
bool on_face(const Lod2Mesh& m, const std::vector<int>& f, const Vec3& p, double tol) {
  const Vec3 nv = newell(m.vertices, f);
  if (nv.norm() <= 0) return false;
  const Vec3 n = nv.normalized();
  if (std::abs(n.dot(p - centroid(m.vertices, f))) > tol) return false;
  int drop = 0;
  n.cwiseAbs().maxCoeff(&drop);
  const int u = (drop + 1) % 3, w = (drop + 2) % 3;
  bool inside = false;
  for (size_t i = 0, j = f.size() - 1; i < f.size(); j = i++) {
    const Vec3 &a = m.vertices[f[i]], &b = m.vertices[f[j]];
    if ((a[w] > p[w]) != (b[w] > p[w]) && p[u] < (b[u] - a[u]) * (p[w] - a[w]) / (b[w] - a[w]) + a[u]) inside = !inside;
  }
  return inside;
}

}  // namespace

std::string closure_problem(const Lod2Mesh& m, std::string* reason, double on_face_tol) {
  auto fail = [&](const char* key, const std::string& text) {
    if (reason) *reason = key;
    return text;
  };
  if (m.faces.size() < 4) return fail("too_few_faces", std::to_string(m.faces.size()) + " faces after clean-up (a closed building needs at least 4)");
  std::map<Edge, int> uses;
  for (const auto& f : m.faces)
    for (size_t k = 0; k < f.size(); ++k) ++uses[undirected(f[k], f[(k + 1) % f.size()])];
  int open = 0;
  double open_length = 0;
  for (const auto& [e, n] : uses)
    if (n == 1) {
      // An edge on another face (the outline of a dropped inner ring, e.g. a courtyard's walls meeting the
      // ground or a dormer in a roof opening) is closed by that face.
      const Vec3 mid = 0.5 * (m.vertices[e.first] + m.vertices[e.second]);
      bool covered = false;
      for (const auto& f : m.faces) {
        const bool has_edge = std::find(f.begin(), f.end(), e.first) != f.end() && std::find(f.begin(), f.end(), e.second) != f.end();
        if (!covered && !has_edge && on_face(m, f, mid, on_face_tol)) covered = true;
      }
      if (covered) continue;
      ++open;
      open_length += (m.vertices[e.first] - m.vertices[e.second]).norm();
    }
  if (open > 0) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f", open_length);
    return fail("not_closed", "does not close: " + std::to_string(open) + " edges belong to one face only (" + buf + " m)");
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
  PolyMesh out;
  std::vector<int> id(m.vertices.size(), -1);
  for (const auto& f : m.faces) {
    std::vector<int> r;
    for (int v : f) {
      if (id[v] < 0) {
        id[v] = static_cast<int>(out.vertices.size());
        out.vertices.push_back(m.vertices[v]);
      }
      r.push_back(id[v]);
    }
    out.faces.push_back(std::move(r));
  }
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
    Welder w0(0);
    for (const auto& r : rings) {
      std::vector<int> f;
      for (const Vec3& v : r.exterior) f.push_back(w0.add(v, exact.vertices));
      f = tidy_ring(f);
      if (!f.empty()) exact.faces.push_back(std::move(f));
    }
    rep.vertices_before = used_vertex_count(exact);
    rep.edges_before = static_cast<int>(unique_edges(exact).size());
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
  rep.t_junction_vertices = conform_t_junctions(m, o.on_edge_tol_m);
  rep.collinear_vertices_removed = remove_collinear_vertices(m, o.collinear_tol_m);
  rep.vertices_after = used_vertex_count(m);
  rep.edges_after = static_cast<int>(unique_edges(m).size());
  rep.faces_after = static_cast<int>(m.faces.size());
  rep.roof_faces_after = static_cast<int>(std::count(m.kinds.begin(), m.kinds.end(), CitySurface::kRoof));
  res.skip_detail = closure_problem(m, &res.skip_reason, o.coplanar_distance_m);
  if (res.skip_reason.empty()) res.mesh = to_poly_mesh(m);
  return res;
}

}  // namespace lc2wf

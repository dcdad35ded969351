#include "dataset/geometry/mesh_repair.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lc2wf {
namespace {

std::array<long long, 3> grid_cell(const Vec3& p, double cell) {
  return {static_cast<long long>(std::floor(p.x() / cell)), static_cast<long long>(std::floor(p.y() / cell)),
          static_cast<long long>(std::floor(p.z() / cell))};
}

unsigned long long grid_key(long long x, long long y, long long z) {
  return (static_cast<unsigned long long>(x) * 73856093ull) ^ (static_cast<unsigned long long>(y) * 19349663ull) ^
         (static_cast<unsigned long long>(z) * 83492791ull);
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b, double* t_out = nullptr) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  if (t_out) *t_out = t;
  return (p - (a + t * ab)).norm();
}

}  // namespace

void MeshRepairOptions::Check() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument(std::string("MeshRepairOptions.") + name + " must be > 0");
  };
  positive(weld_m, "weld_m");
  positive(on_edge_m, "on_edge_m");
  positive(collinear_m, "collinear_m");
}

Vec3 newell_vector(const std::vector<Vec3>& v, const Ring& f) {
  Vec3 n = Vec3::Zero();
  for (size_t k = 0; k < f.size(); ++k) n += v[f[k]].cross(v[f[(k + 1) % f.size()]]);
  return n;
}

double longest_edge(const std::vector<Vec3>& v, const Ring& f) {
  double l = 0;
  for (size_t k = 0; k < f.size(); ++k) l = std::max(l, (v[f[k]] - v[f[(k + 1) % f.size()]]).norm());
  return l;
}

Vec3 ring_centroid(const std::vector<Vec3>& v, const Ring& f) {
  Vec3 c = Vec3::Zero();
  for (int id : f) c += v[id];
  return c / static_cast<double>(f.size());
}

std::set<EdgeKey> unique_edges(const std::vector<Ring>& faces) {
  std::set<EdgeKey> e;
  for (const Ring& f : faces)
    for (size_t k = 0; k < f.size(); ++k)
      if (f[k] != f[(k + 1) % f.size()]) e.insert(undirected_edge(f[k], f[(k + 1) % f.size()]));
  return e;
}

Ring tidy_ring(const Ring& f) {
  Ring out;
  for (int id : f)
    if (out.empty() || out.back() != id) out.push_back(id);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  Ring distinct = out;
  std::sort(distinct.begin(), distinct.end());
  if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() < 3) return {};
  return out;
}

int VertexWelder::add(const Vec3& p) {
  if (tol_ > 0) {
    const auto c = grid_cell(p, tol_);
    int best = -1;
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid_.find(grid_key(c[0] + dx, c[1] + dy, c[2] + dz));
          if (it == grid_.end()) continue;
          for (int id : it->second)
            if ((vertices_[id] - p).norm() <= tol_ && (best < 0 || id < best)) best = id;
        }
    if (best >= 0) return best;
    grid_[grid_key(c[0], c[1], c[2])].push_back(static_cast<int>(vertices_.size()));
  } else {
    const std::array<double, 3> key{p.x(), p.y(), p.z()};
    if (const auto it = exact_.find(key); it != exact_.end()) return it->second;
    exact_.emplace(key, static_cast<int>(vertices_.size()));
  }
  vertices_.push_back(p);
  return static_cast<int>(vertices_.size()) - 1;
}

Ring VertexWelder::add_ring(const std::vector<Vec3>& points) {
  Ring ids;
  for (const Vec3& p : points) ids.push_back(add(p));
  ids = tidy_ring(ids);
  if (ids.empty() || newell_vector(vertices_, ids).norm() <= tol_ * longest_edge(vertices_, ids)) return {};
  return ids;
}

EdgeInteriorIndex::EdgeInteriorIndex(const std::vector<Vec3>& vertices, std::vector<int> candidates, double tol)
    : vertices_(vertices), ids_(std::move(candidates)), tol_(tol) {
  std::sort(ids_.begin(), ids_.end(), [&](int a, int b) {
    return vertices[a].x() < vertices[b].x() || (vertices[a].x() == vertices[b].x() && a < b);
  });
  for (int id : ids_) xs_.push_back(vertices[id].x());
}

std::vector<std::pair<double, int>> EdgeInteriorIndex::inside(int a, int b) const {
  std::vector<std::pair<double, int>> on;
  const Vec3 &pa = vertices_[a], &pb = vertices_[b];
  const double len = (pb - pa).norm();
  if (len <= 2 * tol_) return on;
  const double lo = std::min(pa.x(), pb.x()) - tol_, hi = std::max(pa.x(), pb.x()) + tol_;
  for (size_t i = std::lower_bound(xs_.begin(), xs_.end(), lo) - xs_.begin(); i < xs_.size() && xs_[i] <= hi; ++i) {
    const int v = ids_[i];
    if (v == a || v == b) continue;
    double t = 0;
    if (point_segment_distance(vertices_[v], pa, pb, &t) > tol_) continue;
    if (t * len <= tol_ || (1 - t) * len <= tol_) continue;
    on.push_back({t, v});
  }
  std::sort(on.begin(), on.end());
  return on;
}

int conform_t_junctions(const std::vector<Vec3>& vertices, std::vector<Ring>& faces, double tol) {
  std::vector<char> used(vertices.size(), 0);
  for (const Ring& f : faces)
    for (int id : f) used[id] = 1;
  std::vector<int> candidates;
  for (size_t i = 0; i < used.size(); ++i)
    if (used[i]) candidates.push_back(static_cast<int>(i));
  const EdgeInteriorIndex index(vertices, std::move(candidates), tol);
  int inserted = 0;
  for (Ring& f : faces) {
    Ring out;
    for (size_t k = 0; k < f.size(); ++k) {
      out.push_back(f[k]);
      for (const auto& [t, v] : index.inside(f[k], f[(k + 1) % f.size()])) {
        out.push_back(v);
        ++inserted;
      }
    }
    if (Ring tidy = tidy_ring(out); !tidy.empty()) f = std::move(tidy);
  }
  return inserted;
}

int remove_collinear_vertices(const std::vector<Vec3>& vertices, std::vector<Ring>& faces, double tol,
                              std::vector<int>* kept_faces) {
  std::vector<int> kept(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) kept[f] = static_cast<int>(f);
  int removed_total = 0;
  for (;;) {
    std::vector<std::set<int>> nbrs(vertices.size());
    for (const EdgeKey& e : unique_edges(faces)) {
      nbrs[e.first].insert(e.second);
      nbrs[e.second].insert(e.first);
    }
    std::vector<char> remove(vertices.size(), 0), blocked(vertices.size(), 0);
    int removed = 0;
    for (size_t v = 0; v < vertices.size(); ++v) {
      if (nbrs[v].size() != 2 || blocked[v]) continue;
      const int a = *nbrs[v].begin(), b = *nbrs[v].rbegin();
      if (point_segment_distance(vertices[v], vertices[a], vertices[b]) > tol) continue;
      remove[v] = 1;
      blocked[a] = blocked[b] = 1;
      ++removed;
    }
    if (removed == 0) break;
    removed_total += removed;
    std::vector<Ring> out;
    std::vector<int> out_kept;
    for (size_t f = 0; f < faces.size(); ++f) {
      Ring r;
      for (int id : faces[f])
        if (!remove[id]) r.push_back(id);
      r = tidy_ring(r);
      if (r.empty()) continue;
      out.push_back(std::move(r));
      out_kept.push_back(kept[f]);
    }
    faces = std::move(out);
    kept = std::move(out_kept);
  }
  if (kept_faces) *kept_faces = std::move(kept);
  return removed_total;
}

void drop_unused_vertices(std::vector<Vec3>& vertices, std::vector<Ring>& faces) {
  std::vector<int> new_id(vertices.size(), -1);
  std::vector<Vec3> kept;
  for (Ring& f : faces)
    for (int& v : f) {
      if (new_id[v] < 0) {
        new_id[v] = static_cast<int>(kept.size());
        kept.push_back(vertices[v]);
      }
      v = new_id[v];
    }
  vertices = std::move(kept);
}

}  // namespace lc2wf

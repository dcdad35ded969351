#include "infer/surfaces/plane_candidates.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>

#include "dataset/geometry/wireframe_graph.h"

namespace lc2wf {
namespace {

struct Cluster {
  Vec3 normal_sum = Vec3::Zero();
  double offset_sum = 0;
  int votes = 0;
  Vec3 unit = Vec3::Zero();  // normal_sum.normalized(), kept up to date (it is what new normals are compared with)
  Vec3 normal() const { return unit; }
  double offset() const { return offset_sum / votes; }
};

// The clusters indexed by their normal and offset on a grid whose cells are at least four times the largest
// difference that still matches, so the clusters a normal may join lie in the one or two cells per axis that
// its match box overlaps. Each cluster is filed under both signs of its plane, (n, d) and (-n, -d), so one
// query finds the clusters of either sign. A query returns a superset of the matching clusters; the caller
// applies the exact test and keeps the first cluster in creation order, as a scan of all clusters would.
// Cells live in an open-addressing table (most looked-up cells are empty).
class ClusterGrid {
 public:
  ClusterGrid(double normal_radius, double offset_radius)
      : r_n_(normal_radius * 1.01 + 1e-9), r_o_(offset_radius * 1.01 + 1e-9), h_n_(4 * r_n_), h_o_(4 * r_o_) {
    slots_.assign(1024, Slot{});
  }

  void insert(int id, const Vec3& n, double offset) {
    lists_[slot_for(cell_of(n, offset), true)].push_back(id);
    lists_[slot_for(cell_of(-n, -offset), true)].push_back(id);
  }
  void erase(int id, const Vec3& n, double offset) {
    for (const Key k : {cell_of(n, offset), cell_of(-n, -offset)}) {
      auto& v = lists_[slot_for(k, false)];
      v.erase(std::find(v.begin(), v.end(), id));
    }
  }
  bool same_cell(const Vec3& a, double oa, const Vec3& b, double ob) const {
    return cell_of(a, oa) == cell_of(b, ob) && cell_of(-a, -oa) == cell_of(-b, -ob);
  }

  // Calls f(id) for every cluster filed in a cell that the box around (n, offset) overlaps (some more than once).
  template <typename F>
  void for_each_near(const Vec3& n, double offset, F&& f) const {
    long lo[4], hi[4];
    for (int k = 0; k < 3; ++k) lo[k] = index(n(k) - r_n_, h_n_), hi[k] = index(n(k) + r_n_, h_n_);
    lo[3] = index(offset - r_o_, h_o_), hi[3] = index(offset + r_o_, h_o_);
    for (long x = lo[0]; x <= hi[0]; ++x)
      for (long y = lo[1]; y <= hi[1]; ++y)
        for (long z = lo[2]; z <= hi[2]; ++z)
          for (long o = lo[3]; o <= hi[3]; ++o) {
            const int list = find(key(x, y, z, o));
            if (list >= 0)
              for (int id : lists_[list]) f(id);
          }
  }

 private:
  // A cell as one number. Cells that share a number (offsets beyond 2^40 cells) only add candidates.
  using Key = uint64_t;
  struct Slot {
    Key key = 0;
    int list = -1;  // index into lists_, -1: empty slot
  };
  static Key key(long x, long y, long z, long o) {
    return (static_cast<uint64_t>(x) & 0xFF) | (static_cast<uint64_t>(y) & 0xFF) << 8 | (static_cast<uint64_t>(z) & 0xFF) << 16 |
           static_cast<uint64_t>(o) << 24;
  }
  static size_t hash(Key k) {  // splitmix64's finaliser
    k = (k ^ (k >> 30)) * 0xBF58476D1CE4E5B9ull;
    k = (k ^ (k >> 27)) * 0x94D049BB133111EBull;
    return static_cast<size_t>(k ^ (k >> 31));
  }
  int find(Key k) const {
    const size_t mask = slots_.size() - 1;
    for (size_t i = hash(k) & mask;; i = (i + 1) & mask) {
      if (slots_[i].list < 0) return -1;
      if (slots_[i].key == k) return slots_[i].list;
    }
  }
  int slot_for(Key k, bool create) {
    const int found = find(k);
    if (found >= 0 || !create) return found;
    if (2 * (lists_.size() + 1) > slots_.size()) {  // keep the table at most half full
      std::vector<Slot> old = std::move(slots_);
      slots_.assign(2 * old.size(), Slot{});
      for (const Slot& s : old)
        if (s.list >= 0) place(s);
    }
    lists_.emplace_back();
    place({k, static_cast<int>(lists_.size()) - 1});
    return static_cast<int>(lists_.size()) - 1;
  }
  void place(const Slot& s) {
    const size_t mask = slots_.size() - 1;
    size_t i = hash(s.key) & mask;
    while (slots_[i].list >= 0) i = (i + 1) & mask;
    slots_[i] = s;
  }
  static long index(double x, double h) { return static_cast<long>(std::floor(x / h)); }
  Key cell_of(const Vec3& n, double offset) const {
    return key(index(n.x(), h_n_), index(n.y(), h_n_), index(n.z(), h_n_), index(offset, h_o_));
  }
  double r_n_, r_o_, h_n_, h_o_;
  std::vector<Slot> slots_;
  std::vector<std::vector<int>> lists_;
};

// The edges whose both ends lie within `distance` of a plane, found from the junctions near it (a plane holds
// few of a graph's junctions, so this reads the junctions once and the edges of the near ones only).
class PlaneEdgeFinder {
 public:
  explicit PlaneEdgeFinder(const Wireframe& wf) : wf_(wf), from_(wf.junctions.size()), near_(wf.junctions.size(), 0) {
    for (size_t e = 0; e < wf.edges.size(); ++e) from_[wf.edges[e][0]].push_back(static_cast<int>(e));
  }
  std::vector<int> operator()(const Plane& plane, double distance) {
    ++stamp_;
    for (size_t j = 0; j < wf_.junctions.size(); ++j)
      if (std::abs(plane.distance(wf_.junctions[j])) <= distance) near_[j] = stamp_;
    std::vector<int> out;
    for (size_t j = 0; j < wf_.junctions.size(); ++j)
      if (near_[j] == stamp_)
        for (int e : from_[j])
          if (near_[wf_.edges[e][1]] == stamp_) out.push_back(e);
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  const Wireframe& wf_;
  std::vector<std::vector<int>> from_;  // junction -> edges whose first end it is
  std::vector<int> near_;               // == stamp_: within the distance of the current plane
  int stamp_ = 0;
};

// An edge pair (its normal, the grid cells, the clusters there) costs about as much as this many junctions
// tested against a plane, the unit of the work budget.
constexpr long kStepsPerPair = 24;

}  // namespace

std::vector<int> edges_in_plane(const Wireframe& wf, const Plane& plane, double distance) {
  return PlaneEdgeFinder(wf)(plane, distance);
}

std::vector<CandidatePlane> candidate_planes(const Wireframe& wf, const SurfaceOptions& o, WorkBudget* budget) {
  const int n = static_cast<int>(wf.junctions.size());
  const std::vector<std::vector<int>> incident = incident_edges(wf);
  const double min_sin = std::sin(o.min_edge_angle_deg * M_PI / 180);
  const double cos_merge = std::cos(o.plane_angle_deg * M_PI / 180);
  // Two unit normals within the merge angle (up to sign) differ by at most this chord in each coordinate.
  ClusterGrid grid(std::sqrt(2 - 2 * cos_merge), o.plane_distance_m);
  std::vector<Cluster> clusters;
  for (int j = 0; j < n; ++j) {
    const long degree = static_cast<long>(incident[j].size());
    if (budget && !budget->charge(kStepsPerPair * (degree * (degree - 1) / 2), "candidate planes")) return {};
    const Vec3& p = wf.junctions[j];
    for (size_t x = 0; x < incident[j].size(); ++x) {
      for (size_t y = x + 1; y < incident[j].size(); ++y) {
        const auto& ex = wf.edges[incident[j][x]];
        const auto& ey = wf.edges[incident[j][y]];
        const Vec3 dx = (wf.junctions[ex[0] == j ? ex[1] : ex[0]] - p).normalized();
        const Vec3 dy = (wf.junctions[ey[0] == j ? ey[1] : ey[0]] - p).normalized();
        Vec3 normal = dx.cross(dy);
        if (normal.norm() < min_sin) continue;
        normal.normalize();
        const double offset = normal.dot(p);
        // The first cluster (in creation order) that the normal and offset match.
        int first = -1;
        const auto consider = [&](int id) {
          if (first >= 0 && id > first) return;
          const Cluster& c = clusters[id];
          const double cos = c.normal().dot(normal);
          if (std::abs(cos) < cos_merge) return;
          const double sign = cos < 0 ? -1 : 1;
          if (std::abs(sign * offset - c.offset()) > o.plane_distance_m) return;
          first = id;
        };

        grid.for_each_near(normal, offset, consider);
        if (first < 0) {
          clusters.push_back({normal, offset, 1, normal.normalized()});
          grid.insert(static_cast<int>(clusters.size()) - 1, clusters.back().unit, clusters.back().offset());
          continue;
        }
        Cluster& c = clusters[first];
        const Vec3 old_unit = c.unit;
        const double old_offset = c.offset();
        const double sign = c.normal().dot(normal) < 0 ? -1 : 1;
        c.normal_sum += sign * normal;
        c.offset_sum += sign * offset;
        ++c.votes;
        c.unit = c.normal_sum.normalized();
        if (!grid.same_cell(old_unit, old_offset, c.unit, c.offset())) {
          grid.erase(first, old_unit, old_offset);
          grid.insert(first, c.unit, c.offset());
        }
      }
    }
  }
  std::stable_sort(clusters.begin(), clusters.end(), [](const Cluster& a, const Cluster& b) { return a.votes > b.votes; });

  PlaneEdgeFinder in_plane(wf);
  std::vector<CandidatePlane> out;
  std::set<std::vector<int>> seen;
  std::vector<int> mark(n, -1), ids;
  std::vector<Vec3> pts;
  int marked = 0;

  for (const Cluster& c : clusters) {
    // Up to three planes' junction tests and two plane fits (an eigen solve costs about 32 junction tests).
    if (budget && !budget->charge(3L * n + 64, "candidate planes")) break;
    CandidatePlane cp;
    cp.plane.normal = c.normal();
    cp.plane.offset = c.offset();
    // Refit to the junctions of the edges in the plane (twice: the first fit may gather one more edge).
    bool current = false;  // cp.edges are the edges of cp.plane
    for (int pass = 0; pass < 2; ++pass) {
      cp.edges = in_plane(cp.plane, o.plane_distance_m);
      current = true;
      // The junctions of those edges, in increasing id order.
      ids.clear();
      ++marked;
      for (int e : cp.edges)
        for (int id : wf.edges[e])
          if (mark[id] != marked) mark[id] = marked, ids.push_back(id);
      if (ids.size() < 3) break;
      std::sort(ids.begin(), ids.end());
      pts.clear();
      for (int id : ids) pts.push_back(wf.junctions[id]);
      const Plane fitted = fit_plane(pts);
      if (plane_angle_deg(fitted.normal, cp.plane.normal) > 2 * o.plane_angle_deg) break;  // the points lie on a line
      cp.plane = fitted;
      current = false;
    }
    if (!current) cp.edges = in_plane(cp.plane, o.plane_distance_m);
    if (cp.edges.size() < 2 || !seen.insert(cp.edges).second) continue;
    out.push_back(std::move(cp));
  }
  return out;
}

}  // namespace lc2wf

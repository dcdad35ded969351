#include "infer/surfaces/plane_candidates.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace lc2wf {
namespace {

struct Cluster {
  Vec3 normal_sum = Vec3::Zero();
  double offset_sum = 0;
  int votes = 0;
  Vec3 normal() const { return normal_sum.normalized(); }
  double offset() const { return offset_sum / votes; }
};

}  // namespace

std::vector<int> edges_in_plane(const Wireframe& wf, const Plane& plane, double distance) {
  std::vector<int> out;
  for (size_t e = 0; e < wf.edges.size(); ++e)
    if (std::abs(plane.distance(wf.junctions[wf.edges[e][0]])) <= distance &&
        std::abs(plane.distance(wf.junctions[wf.edges[e][1]])) <= distance)
      out.push_back(static_cast<int>(e));
  return out;
}

std::vector<CandidatePlane> candidate_planes(const Wireframe& wf, const SurfaceOptions& o) {
  const int n = static_cast<int>(wf.junctions.size());
  std::vector<std::vector<int>> incident(n);
  for (size_t e = 0; e < wf.edges.size(); ++e) {
    incident[wf.edges[e][0]].push_back(static_cast<int>(e));
    incident[wf.edges[e][1]].push_back(static_cast<int>(e));
  }
  const double min_sin = std::sin(o.min_edge_angle_deg * M_PI / 180);
  const double cos_merge = std::cos(o.plane_angle_deg * M_PI / 180);
  std::vector<Cluster> clusters;
  for (int j = 0; j < n; ++j) {
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
        bool added = false;
        for (Cluster& c : clusters) {
          const Vec3 cn = c.normal();
          const double cos = cn.dot(normal);
          if (std::abs(cos) < cos_merge) continue;
          const double sign = cos < 0 ? -1 : 1;
          if (std::abs(sign * offset - c.offset()) > o.plane_distance_m) continue;
          c.normal_sum += sign * normal;
          c.offset_sum += sign * offset;
          ++c.votes;
          added = true;
          break;
        }
        if (!added) clusters.push_back({normal, offset, 1});
      }
    }
  }
  std::stable_sort(clusters.begin(), clusters.end(), [](const Cluster& a, const Cluster& b) { return a.votes > b.votes; });

  std::vector<CandidatePlane> out;
  std::set<std::vector<int>> seen;
  for (const Cluster& c : clusters) {
    CandidatePlane cp;
    cp.plane.normal = c.normal();
    cp.plane.offset = c.offset();
    // Refit to the junctions of the edges in the plane (twice: the first fit may gather one more edge).
    for (int pass = 0; pass < 2; ++pass) {
      cp.edges = edges_in_plane(wf, cp.plane, o.plane_distance_m);
      std::set<int> ids;
      for (int e : cp.edges) ids.insert({wf.edges[e][0], wf.edges[e][1]});
      if (ids.size() < 3) break;
      std::vector<Vec3> pts;
      for (int id : ids) pts.push_back(wf.junctions[id]);
      const Plane fitted = fit_plane(pts);
      if (plane_angle_deg(fitted.normal, cp.plane.normal) > 2 * o.plane_angle_deg) break;  // the points lie on a line
      cp.plane = fitted;
    }
    cp.edges = edges_in_plane(wf, cp.plane, o.plane_distance_m);
    if (cp.edges.size() < 2 || !seen.insert(cp.edges).second) continue;
    out.push_back(std::move(cp));
  }
  return out;
}

}  // namespace lc2wf

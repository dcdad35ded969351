#include "dataset/labels/labelling.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "dataset/labels/visibility.h"

namespace lc2wf {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kMinDepth = 1e-6;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// 2D closeness of a support segment to a projected edge; returns the max endpoint distance or -1.
double support_fit(const Segment2& s, const ProjectedEdge& e, const SupportLabelOptions& o) {
  const Vec2 d = e.p1 - e.p0;
  const double len = d.norm();
  const double slen = s.length();
  if (len < 1e-9 || slen < 1e-9 || e.visible.empty()) return -1;
  const Vec2 u = d / len;
  const double da = std::abs(cross2(u, s.a - e.p0));
  const double db = std::abs(cross2(u, s.b - e.p0));
  if (da > o.pixel_tol || db > o.pixel_tol) return -1;
  const double cos_angle = std::abs(u.dot((s.b - s.a) / slen));
  if (cos_angle < std::cos(o.angle_tol_deg * kDeg)) return -1;
  const double ua = u.dot(s.a - e.p0) / len, ub = u.dot(s.b - e.p0) / len;
  const double lo = std::min(ua, ub), hi = std::max(ua, ub);
  double inside = 0;
  for (const auto& iv : e.visible) inside += std::max(0.0, std::min(hi, iv[1]) - std::max(lo, iv[0]));
  if (inside * len < o.min_overlap * slen * cos_angle) return -1;
  return std::max(da, db);
}

}  // namespace

void SupportLabelOptions::Check() const {
  if (!(pixel_tol > 0)) throw std::invalid_argument("SupportLabelOptions.pixel_tol must be > 0");
  if (!(angle_tol_deg > 0 && angle_tol_deg < 90)) throw std::invalid_argument("SupportLabelOptions.angle_tol_deg must be in (0, 90)");
  if (!(min_overlap > 0 && min_overlap <= 1)) throw std::invalid_argument("SupportLabelOptions.min_overlap must be in (0, 1]");
  if (!(min_vote_fraction > 0 && min_vote_fraction <= 1)) throw std::invalid_argument("SupportLabelOptions.min_vote_fraction must be in (0, 1]");
  if (min_views < 1) throw std::invalid_argument("SupportLabelOptions.min_views must be >= 1");
  if (visibility_samples < 1) throw std::invalid_argument("SupportLabelOptions.visibility_samples must be >= 1");
  if (!(depth_tolerance_m >= 0)) throw std::invalid_argument("SupportLabelOptions.depth_tolerance_m must be >= 0");
}

void GeometricLabelOptions::Check() const {
  if (!(max_distance_m > 0)) throw std::invalid_argument("GeometricLabelOptions.max_distance_m must be > 0");
  if (!(angle_tol_deg > 0 && angle_tol_deg < 90)) throw std::invalid_argument("GeometricLabelOptions.angle_tol_deg must be in (0, 90)");
  if (!(min_overlap > 0 && min_overlap <= 1)) throw std::invalid_argument("GeometricLabelOptions.min_overlap must be in (0, 1]");
}

ProjectedEdge project_edge(const Camera& cam, const Vec3& a, const Vec3& b, const MeshOccluder& occ, int samples,
                           double depth_tolerance) {
  ProjectedEdge e;
  if (cam.to_camera(a).z() <= kMinDepth || cam.to_camera(b).z() <= kMinDepth) return e;  // crosses the image plane
  e.p0 = cam.project(a);
  e.p1 = cam.project(b);
  const Vec2 d = e.p1 - e.p0;
  const double len2 = d.squaredNorm();
  if (len2 < 1e-18) return e;
  const Vec3 eye = cam.center();
  auto u_of = [&](double t) { return d.dot(cam.project(a + t * (b - a)) - e.p0) / len2; };
  for (int k = 0; k < samples; ++k) {
    const double t = (k + 0.5) / samples;
    if (occ.occluded(eye, a + t * (b - a), depth_tolerance)) continue;
    const double u0 = u_of(static_cast<double>(k) / samples), u1 = u_of(static_cast<double>(k + 1) / samples);
    if (!e.visible.empty() && std::abs(e.visible.back()[1] - u0) < 1e-12) {
      e.visible.back()[1] = u1;
    } else {
      e.visible.push_back({u0, u1});
    }
  }
  return e;
}

std::vector<SegmentLabel> label_by_support(const LineCloud& cloud, const PolyMesh& mesh, const SupportLabelOptions& o) {
  o.Check();
  const auto& wf = cloud.wireframe;
  std::vector<SegmentLabel> labels(cloud.segments.size());
  if (cloud.support.empty() || wf.edges.empty()) return labels;
  const MeshOccluder occ(mesh);
  // Projected GT edges for each view that some segment uses (computed once per view).
  std::map<int, std::vector<ProjectedEdge>> per_view;
  for (const auto& list : cloud.support) {
    for (const auto& obs : list) per_view.emplace(obs.view, std::vector<ProjectedEdge>{});
  }
  for (auto& [view, edges] : per_view) {
    const Camera& cam = cloud.cameras.at(view);
    for (const auto& ed : wf.edges) {
      edges.push_back(project_edge(cam, wf.junctions[ed[0]], wf.junctions[ed[1]], occ, o.visibility_samples, o.depth_tolerance_m));
    }
  }
  for (size_t i = 0; i < cloud.segments.size(); ++i) {
    const auto& list = cloud.support[i];
    if (list.empty()) continue;
    std::map<int, std::set<int>> views_of_edge;
    std::map<int, int> votes;
    for (const auto& obs : list) {
      const auto& edges = per_view.at(obs.view);
      int best = -1;
      double best_fit = 0;
      for (size_t e = 0; e < edges.size(); ++e) {
        const double fit = support_fit(obs.seg, edges[e], o);
        if (fit >= 0 && (best < 0 || fit < best_fit)) {
          best = static_cast<int>(e);
          best_fit = fit;
        }
      }
      if (best >= 0) {
        ++votes[best];
        views_of_edge[best].insert(obs.view);
      }
    }
    int winner = -1, winner_votes = 0;
    for (const auto& [e, v] : votes) {
      if (v > winner_votes) {
        winner = e;
        winner_votes = v;
      }
    }
    if (winner < 0 || winner_votes < o.min_vote_fraction * static_cast<double>(list.size()) ||
        static_cast<int>(views_of_edge[winner].size()) < o.min_views) {
      continue;
    }
    labels[i] = make_edge_label(cloud.segments[i], wf, wf.edges[winner][0], wf.edges[winner][1]);
  }
  return labels;
}

std::vector<SegmentLabel> label_by_geometry(const std::vector<Segment3>& segments, const Wireframe& wf,
                                            const GeometricLabelOptions& o) {
  o.Check();
  std::vector<SegmentLabel> labels(segments.size());
  const double cos_tol = std::cos(o.angle_tol_deg * kDeg);
  for (size_t i = 0; i < segments.size(); ++i) {
    const auto& s = segments[i];
    const double slen = s.length();
    if (!(slen > 0)) continue;
    const Vec3 sdir = (s.b - s.a) / slen;
    int best = -1;
    double best_dist = 0;
    for (size_t e = 0; e < wf.edges.size(); ++e) {
      const Vec3& A = wf.junctions[wf.edges[e][0]];
      const Vec3& B = wf.junctions[wf.edges[e][1]];
      const double len = (B - A).norm();
      if (len <= 0) continue;
      const Vec3 u = (B - A) / len;
      const double cos_angle = std::abs(u.dot(sdir));
      if (cos_angle < cos_tol) continue;
      const double da = u.cross(s.a - A).norm(), db = u.cross(s.b - A).norm();
      const double dist = std::max(da, db);
      if (dist > o.max_distance_m) continue;
      const double ta = u.dot(s.a - A), tb = u.dot(s.b - A);
      const double inside = std::max(0.0, std::min(std::max(ta, tb), len) - std::max(std::min(ta, tb), 0.0));
      if (inside < o.min_overlap * slen * cos_angle) continue;
      if (best < 0 || dist < best_dist) {
        best = static_cast<int>(e);
        best_dist = dist;
      }
    }
    if (best >= 0) labels[i] = make_edge_label(s, wf, wf.edges[best][0], wf.edges[best][1]);
  }
  return labels;
}

}  // namespace lc2wf

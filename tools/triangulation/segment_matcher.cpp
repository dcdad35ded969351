// Directed epipolar matching of the segments of two views, with an exact angular prefilter: every
// epipolar line in view b passes through the epipole, so a source segment can only overlap a target
// segment if their pencils of lines through the epipole intersect.
// A target segment along its epipolar line (the pair's planes coincide) is matched by its endpoints instead.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "tools/triangulation/epipolar.h"
#include "tools/triangulation/view_geometry.h"

namespace lc2wf {
namespace {

constexpr double kPi = 3.14159265358979323846;

double wrap_pi(double a) {
  a = std::fmod(a, kPi);
  return a < 0 ? a + kPi : a;
}

// Angle in [0, pi) of a homogeneous line's direction.
double line_angle(const Vec3& l) { return wrap_pi(std::atan2(l.x(), -l.y())); }

struct TargetArc {
  bool always_test = false;  // epipole on (or near) the target's line: the pencil test does not apply
  double line_angle = 0.0;   // direction of the target line, i.e. the angle of the "point at infinity"
  double lo = 0.0, hi = 0.0; // arc of the target segment, measured from line_angle, inside (0, pi)
};

}  // namespace

ViewGeometry make_view_geometry(const TriangulationView& view, double sigma_p_px) {
  ViewGeometry g;
  g.camera = &view.camera;
  g.segments = &view.segments;
  g.centre = view.camera.center();
  const size_t n = view.segments.size();
  g.ray_a.resize(n);
  g.ray_b.resize(n);
  g.ray_mid.resize(n);
  g.plane_normal.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Segment2& s = view.segments[i];
    g.ray_a[i] = pixel_ray(view.camera, s.a);
    g.ray_b[i] = pixel_ray(view.camera, s.b);
    g.ray_mid[i] = pixel_ray(view.camera, 0.5 * (s.a + s.b));
    const Vec3 c = g.ray_a[i].cross(g.ray_b[i]);
    g.plane_normal[i] = c.norm() > 0 ? Vec3(c.normalized()) : Vec3::Zero();
  }
  const Vec2 pp(view.camera.K(0, 2), view.camera.K(1, 2));
  const Vec3 r0 = pixel_ray(view.camera, pp), r1 = pixel_ray(view.camera, pp + Vec2(sigma_p_px, 0));
  g.sigma_factor = r0.cross(r1).norm();
  return g;
}

std::vector<LineHypothesis> match_view_pair(const ViewGeometry& a, const ViewGeometry& b, int b_index,
                                            const TriangulatorOptions& options, long long* candidate_tests) {
  const Camera& ca = *a.camera;
  const Camera& cb = *b.camera;
  const auto& src = *a.segments;
  const auto& tgt = *b.segments;
  const Eigen::Matrix3d F = fundamental_matrix(ca, cb);
  const Vec3 eh = cb.K * cb.to_camera(a.centre);  // epipole in b (homogeneous)
  const bool use_prefilter = std::abs(eh.z()) > 1e-6 * eh.head<2>().norm();
  const Vec2 e = use_prefilter ? Vec2(eh.head<2>() / eh.z()) : Vec2::Zero();

  std::vector<TargetArc> arcs(tgt.size());
  if (use_prefilter) {
    for (size_t t = 0; t < tgt.size(); ++t) {
      const Segment2& q = tgt[t];
      const Vec2 d = q.b - q.a;
      TargetArc& arc = arcs[t];
      // Distance of the epipole to the target's infinite line.
      if (std::abs(d.x() * (e.y() - q.a.y()) - d.y() * (e.x() - q.a.x())) < 1.0 * d.norm()) {
        arc.always_test = true;
        continue;
      }
      arc.line_angle = wrap_pi(std::atan2(d.y(), d.x()));
      const double a1 = wrap_pi(std::atan2(q.a.y() - e.y(), q.a.x() - e.x()) - arc.line_angle);
      const double a2 = wrap_pi(std::atan2(q.b.y() - e.y(), q.b.x() - e.x()) - arc.line_angle);
      arc.lo = std::min(a1, a2);
      arc.hi = std::max(a1, a2);
    }
  }

  // Targets along their epipolar line: matched by endpoints (endpoint_depths), not by ray-plane depths.
  const double along_sin = std::sin(options.endpoint_angle_deg * kPi / 180.0);
  std::vector<char> along(tgt.size(), 0);
  if (options.endpoint_angle_deg > 0) {
    for (size_t t = 0; t < tgt.size(); ++t) {
      const Vec2 d = tgt[t].b - tgt[t].a;
      const Vec2 mid = 0.5 * (tgt[t].a + tgt[t].b);
      const Vec3 l = eh.cross(Vec3(mid.x(), mid.y(), 1.0));
      const double ln = l.head<2>().norm(), dn = d.norm();
      along[t] = ln > 0 && dn > 0 && std::abs(l.head<2>().dot(d)) < along_sin * ln * dn;
    }
  }
  const double band_px = 2.0 * options.sigma_p_px;

  const double min_sin = std::sin(options.min_ray_plane_angle_deg * kPi / 180.0);
  const double max_cos_view = std::cos(options.min_view_angle_deg * kPi / 180.0);
  std::vector<LineHypothesis> out;
  std::vector<LineHypothesis> cands;
  long long tests = 0;
  for (size_t s = 0; s < src.size(); ++s) {
    cands.clear();
    const Vec3 l1 = F * Vec3(src[s].a.x(), src[s].a.y(), 1.0);
    const Vec3 l2 = F * Vec3(src[s].b.x(), src[s].b.y(), 1.0);
    const double s1 = line_angle(l1), s2 = line_angle(l2);
    // The source endpoints' epipolar lines scaled to pixel distances (zero when undefined), for targets along them.
    const Vec3 e1 = l1.head<2>().norm() > 0 ? Vec3(l1 / l1.head<2>().norm()) : Vec3::Zero();
    const Vec3 e2 = l2.head<2>().norm() > 0 ? Vec3(l2 / l2.head<2>().norm()) : Vec3::Zero();
    auto off_lines = [&](const Vec2& q) { return std::max(std::abs(e1.dot(Vec3(q.x(), q.y(), 1.0))), std::abs(e2.dot(Vec3(q.x(), q.y(), 1.0)))); };
    const double source_length = src[s].length();
    auto add = [&](size_t t, double overlap, const Eigen::Vector2d& depths, bool by_endpoints) {
      LineHypothesis h;
      h.by_endpoints = by_endpoints;
      h.source_segment = static_cast<int>(s);
      h.target_view = b_index;
      h.target_segment = static_cast<int>(t);
      h.overlap = overlap;
      h.depth1 = depths[0];
      h.depth2 = depths[1];
      cands.push_back(h);
    };
    for (size_t t = 0; t < tgt.size(); ++t) {
      if (along[t]) {
        const Segment2& q = tgt[t];
        if (e1.isZero() || e2.isZero() || off_lines(q.a) > band_px || off_lines(q.b) > band_px) continue;
        ++tests;
        const double lt = q.length();
        const double ov = std::min(source_length, lt) / std::max(source_length, lt);
        if (!(ov > options.epipolar_overlap)) continue;
        const auto ds = endpoint_depths(a.centre, a.ray_a[s], a.ray_b[s], b.centre, b.ray_a[t], b.ray_b[t], min_sin);
        if (ds) add(t, ov, *ds, true);
        continue;
      }
      if (use_prefilter && !arcs[t].always_test) {
        const double b1 = wrap_pi(s1 - arcs[t].line_angle), b2 = wrap_pi(s2 - arcs[t].line_angle);
        constexpr double kTol = 1e-7;
        if (std::max(b1, b2) < arcs[t].lo - kTol || std::min(b1, b2) > arcs[t].hi + kTol) continue;
      }
      ++tests;
      const double ov = epipolar_overlap(F, src[s], tgt[t]);
      if (ov <= options.epipolar_overlap) continue;
      if (b.plane_normal[t].isZero() || a.plane_normal[s].isZero()) continue;
      const auto ds = ray_plane_depths(a.centre, a.ray_a[s], a.ray_b[s], b.centre, b.plane_normal[t], min_sin);
      if (!ds || (*ds)[0] <= 0 || (*ds)[1] <= 0) continue;
      const auto dt = ray_plane_depths(b.centre, b.ray_a[t], b.ray_b[t], a.centre, a.plane_normal[s], min_sin);
      if (!dt || (*dt)[0] <= 0 || (*dt)[1] <= 0) continue;
      add(t, ov, *ds, false);
    }
    if (options.knn > 0 && static_cast<int>(cands.size()) > options.knn) {
      std::partial_sort(cands.begin(), cands.begin() + options.knn, cands.end(), [](const LineHypothesis& x, const LineHypothesis& y) {
        return x.overlap != y.overlap ? x.overlap > y.overlap : x.target_segment < y.target_segment;
      });
      cands.resize(options.knn);
    }
    for (LineHypothesis& h : cands) {
      h.p1 = a.centre + h.depth1 * a.ray_a[s];
      h.p2 = a.centre + h.depth2 * a.ray_b[s];
      const Vec3 d = h.p2 - h.p1;
      const double len = d.norm();
      if (len <= 0) continue;
      h.direction = d / len;
      // Orientation filter: reject lines nearly along the viewing ray (depth is ill-conditioned there).
      if (std::abs(h.direction.dot(a.ray_mid[s])) >= max_cos_view) continue;
      const double k = b.sigma_factor;
      h.target_var1 = (k * (h.p1 - b.centre).norm()) * (k * (h.p1 - b.centre).norm());
      h.target_var2 = (k * (h.p2 - b.centre).norm()) * (k * (h.p2 - b.centre).norm());
      out.push_back(h);
    }
  }
  if (candidate_tests) *candidate_tests += tests;
  return out;
}

}  // namespace lc2wf

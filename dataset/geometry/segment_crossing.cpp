#include "dataset/geometry/segment_crossing.h"

#include <algorithm>
#include <cmath>

namespace lc2wf {

SegmentClosestPoints segment_closest_points(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  const Vec3 u = a1 - a0, v = b1 - b0, w = a0 - b0;
  const double uu = u.dot(u), vv = v.dot(v), uv = u.dot(v), uw = u.dot(w), vw = v.dot(w);
  constexpr double kTiny = 1e-18;
  SegmentClosestPoints c;
  if (uu <= kTiny && vv <= kTiny) {
    c.distance = w.norm();
    return c;
  }
  if (uu <= kTiny) {
    c.t = std::clamp(vw / vv, 0.0, 1.0);
  } else if (vv <= kTiny) {
    c.s = std::clamp(-uw / uu, 0.0, 1.0);
  } else {
    const double det = uu * vv - uv * uv;
    // Parallel lines: any s works; s = 0 then the t it implies.
    c.s = det > kTiny * uu * vv ? std::clamp((uv * vw - vv * uw) / det, 0.0, 1.0) : 0.0;
    c.t = (uv * c.s + vw) / vv;
    if (c.t < 0.0 || c.t > 1.0) {  // t clamped: s is then the closest point of the first segment to that end
      c.t = std::clamp(c.t, 0.0, 1.0);
      c.s = std::clamp((uv * c.t - uw) / uu, 0.0, 1.0);
    }
  }
  c.distance = ((a0 + c.s * u) - (b0 + c.t * v)).norm();
  return c;
}

bool segments_cross(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double max_distance,
                    double end_margin, double min_angle_deg) {
  const Vec3 u = a1 - a0, v = b1 - b0;
  const double lu = u.norm(), lv = v.norm();
  if (lu <= 2.0 * end_margin || lv <= 2.0 * end_margin) return false;
  const double cos_angle = std::abs(u.dot(v)) / (lu * lv);
  if (cos_angle >= std::cos(min_angle_deg * M_PI / 180.0)) return false;
  const SegmentClosestPoints c = segment_closest_points(a0, a1, b0, b1);
  if (c.distance > max_distance) return false;
  const double from_a = std::min(c.s, 1.0 - c.s) * lu, from_b = std::min(c.t, 1.0 - c.t) * lv;
  return from_a >= end_margin && from_b >= end_margin;
}

}  // namespace lc2wf

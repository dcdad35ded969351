#include "dataset/photo/camera_coverage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "dataset/geometry/footprint.h"

namespace lc2wf {
namespace {

double degrees(double radians) { return radians * 180.0 / M_PI; }

// Into (-180, 180].
double wrap_degrees(double a) {
  a = std::fmod(a, 360.0);
  if (a <= -180.0) a += 360.0;
  if (a > 180.0) a -= 360.0;
  return a;
}

std::string format_degrees(double a) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f", a);
  return std::string(buf) + " deg";
}

bool sees_a_point_of(const Camera& cam, const Vec2& a, const Vec2& b, double z) {
  for (double t : {0.5, 0.25, 0.75, 0.05, 0.95}) {
    const Vec3 p((a + t * (b - a)).x(), (a + t * (b - a)).y(), z);
    if (!(cam.to_camera(p).z() > 0)) continue;
    const Vec2 q = cam.project(p);
    if (q.x() >= -0.5 && q.y() >= -0.5 && q.x() <= cam.width - 0.5 && q.y() <= cam.height - 0.5) return true;
  }
  return false;
}

}  // namespace

void CoverageOptions::Check() const {
  if (min_cameras < 1) throw std::invalid_argument("CoverageOptions.min_cameras must be >= 1");
  if (!(max_view_angle_deg > 0 && max_view_angle_deg < 90))
    throw std::invalid_argument("CoverageOptions.max_view_angle_deg must be in (0, 90)");
}

CameraCoverage camera_coverage(const std::vector<Camera>& cameras, const std::vector<Vec3>& outline_points,
                               const CoverageOptions& options) {
  options.Check();
  CameraCoverage c;
  const std::vector<Vec2> rect = footprint_rectangle(outline_points);
  double z_lo = 0, z_hi = 0;
  if (!outline_points.empty()) {
    z_lo = z_hi = outline_points.front().z();
    for (const Vec3& p : outline_points) z_lo = std::min(z_lo, p.z()), z_hi = std::max(z_hi, p.z());
  }
  const double z_mid = 0.5 * (z_lo + z_hi);
  double extent = 0;
  for (const Vec2& p : rect) c.centre += p / static_cast<double>(rect.size());
  for (const Vec2& p : rect) extent = std::max(extent, (p - c.centre).norm());

  std::vector<double> azimuths;
  for (const Camera& cam : cameras) {
    const Vec2 d = cam.center().head<2>() - c.centre;
    if (d.norm() <= 1e-9 * std::max(1.0, extent)) continue;
    azimuths.push_back(degrees(std::atan2(d.y(), d.x())));
  }
  c.cameras = static_cast<int>(azimuths.size());
  if (!azimuths.empty()) {
    std::sort(azimuths.begin(), azimuths.end());
    // The arc is the circle minus its largest gap between neighbouring directions.
    size_t after_gap = 0;
    double gap = azimuths.front() + 360.0 - azimuths.back();
    for (size_t i = 1; i < azimuths.size(); ++i)
      if (azimuths[i] - azimuths[i - 1] > gap) gap = azimuths[i] - azimuths[i - 1], after_gap = i;
    c.azimuth_from_deg = azimuths[after_gap];
    c.azimuth_to_deg = azimuths[(after_gap + azimuths.size() - 1) % azimuths.size()];
    c.azimuth_span_deg = 360.0 - gap;
  }

  if (rect.size() != 4) return c;
  const double min_cos = std::cos(options.max_view_angle_deg * M_PI / 180.0);
  double perimeter = 0, seen = 0;
  for (size_t k = 0; k < 4; ++k) {
    SideCoverage s;
    s.a = rect[k];
    s.b = rect[(k + 1) % 4];
    s.length_m = (s.b - s.a).norm();
    if (!(s.length_m > 1e-9 * std::max(1.0, extent))) continue;  // a footprint of collinear points has no such side
    const Vec2 u = (s.b - s.a) / s.length_m, outward(u.y(), -u.x());  // counter-clockwise: outside is on the right
    s.outward_azimuth_deg = degrees(std::atan2(outward.y(), outward.x()));
    const Vec2 mid = 0.5 * (s.a + s.b);
    for (const Camera& cam : cameras) {
      const Vec2 to_cam = cam.center().head<2>() - mid;
      if (!(to_cam.norm() > 0) || to_cam.normalized().dot(outward) < min_cos) continue;
      if (sees_a_point_of(cam, s.a, s.b, z_mid)) ++s.cameras;
    }
    s.seen = s.cameras >= options.min_cameras;
    perimeter += s.length_m;
    if (s.seen) seen += s.length_m;
    c.sides.push_back(s);
  }
  c.seen_outline_share = perimeter > 0 ? seen / perimeter : 0.0;
  return c;
}

CameraCoverage camera_coverage(const std::vector<Camera>& cameras, const Wireframe& wireframe,
                               const std::vector<Segment3>& segments, const CoverageOptions& options) {
  const std::vector<Vec2> rect = footprint_rectangle(wireframe.junctions);
  if (rect.size() == 4 && (rect[1] - rect[0]).norm() * (rect[2] - rect[1]).norm() > 0) {
    CameraCoverage c = camera_coverage(cameras, wireframe.junctions, options);
    c.outline = "wireframe";
    return c;
  }
  std::vector<Vec3> ends;
  for (const Segment3& s : segments) ends.push_back(s.a), ends.push_back(s.b);
  CameraCoverage c = camera_coverage(cameras, ends, options);
  c.outline = "cloud";
  return c;
}

nlohmann::json coverage_json(const CameraCoverage& c) {
  nlohmann::json sides = nlohmann::json::array(), seen = nlohmann::json::array(), unseen = nlohmann::json::array();
  for (const SideCoverage& s : c.sides) (s.seen ? seen : unseen).push_back(s.outward_azimuth_deg);
  for (const SideCoverage& s : c.sides)
    sides.push_back({{"from", {s.a.x(), s.a.y()}}, {"to", {s.b.x(), s.b.y()}}, {"length_m", s.length_m},
                     {"facing_azimuth_deg", s.outward_azimuth_deg}, {"cameras", s.cameras}, {"seen", s.seen}});
  return {{"cameras", c.cameras},
          {"centre", {c.centre.x(), c.centre.y()}},
          {"azimuth_from_deg", c.azimuth_from_deg},
          {"azimuth_to_deg", c.azimuth_to_deg},
          {"azimuth_span_deg", c.azimuth_span_deg},
          {"outline", c.outline},
          {"seen_outline_share", c.seen_outline_share},
          {"seen_sides_facing_deg", seen},
          {"unseen_sides_facing_deg", unseen},
          {"sides", sides},
          {"summary", c.summary()}};
}

std::string CameraCoverage::summary() const {
  std::string line = std::to_string(cameras) + " camera(s) over " + format_degrees(azimuth_span_deg) + " of azimuth around the building (" +
                     format_degrees(azimuth_from_deg) + " to " + format_degrees(azimuth_to_deg) + ")";
  if (sides.empty()) return line + "; no footprint to check the sides of";
  std::string seen_list, unseen_list;
  int seen = 0;
  for (const SideCoverage& s : sides) {
    std::string& list = s.seen ? seen_list : unseen_list;
    list += (list.empty() ? "" : ", ") + format_degrees(wrap_degrees(s.outward_azimuth_deg));
    seen += s.seen;
  }
  char share[32];
  std::snprintf(share, sizeof share, "%.0f", 100.0 * seen_outline_share);
  return line + "; " + std::to_string(seen) + " of " + std::to_string(sides.size()) + " footprint sides seen (" + share +
         " % of the outline)" + (seen_list.empty() ? "" : "; seen: facing " + seen_list) +
         (unseen_list.empty() ? "" : "; unseen: facing " + unseen_list);
}

}  // namespace lc2wf

#include "dataset/synthetic/surface_clutter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lc2wf {
namespace {

// Two edge directions leaving one junction, each with how far the corner's triangle reaches along it.
struct Corner {
  Vec3 apex, u, v;  // u, v: edge vectors clipped to corner_reach_m
};

std::vector<Corner> wireframe_corners(const Wireframe& wf, double reach) {
  std::vector<std::vector<Vec3>> leaving(wf.junctions.size());
  for (const auto& e : wf.edges) {
    const Vec3 d = wf.junctions[e[1]] - wf.junctions[e[0]];
    const double length = d.norm();
    if (length <= 0.0) continue;
    const Vec3 clipped = d * (std::min(length, reach) / length);
    leaving[e[0]].push_back(clipped);
    leaving[e[1]].push_back(-clipped);
  }
  std::vector<Corner> corners;
  for (size_t j = 0; j < leaving.size(); ++j)
    for (size_t a = 0; a < leaving[j].size(); ++a)
      for (size_t b = a + 1; b < leaving[j].size(); ++b) {
        const Vec3& u = leaving[j][a];
        const Vec3& v = leaving[j][b];
        if (u.cross(v).norm() < 0.2 * u.norm() * v.norm()) continue;  // (anti)parallel edges span no face
        corners.push_back({wf.junctions[j], u, v});
      }
  return corners;
}

Segment3 centred_segment(const Vec3& centre, const Vec3& unit_direction, double length) {
  return {centre - 0.5 * length * unit_direction, centre + 0.5 * length * unit_direction};
}

Segment3 face_line(const Corner& c, double length, DataRng& rng) {
  double s = rng.uniform(), t = rng.uniform();
  if (s + t > 1.0) s = 1.0 - s, t = 1.0 - t;  // uniform over the triangle
  const Vec3 e1 = c.u.normalized();
  const Vec3 e2 = (c.v - e1.dot(c.v) * e1).normalized();
  const double angle = rng.uniform(0.0, M_PI);
  return centred_segment(c.apex + s * c.u + t * c.v, std::cos(angle) * e1 + std::sin(angle) * e2, length);
}

}  // namespace

void SurfaceClutterOptions::Check() const {
  if (face_lines < 0 || ground_lines < 0) throw std::invalid_argument("SurfaceClutterOptions: line counts must be >= 0");
  if (!(ground_margin_m > 0.0 && ground_margin_m <= 100.0))
    throw std::invalid_argument("SurfaceClutterOptions.ground_margin_m must be in (0, 100] (metres)");
  if (!(corner_reach_m > 0.0 && corner_reach_m <= 100.0))
    throw std::invalid_argument("SurfaceClutterOptions.corner_reach_m must be in (0, 100] (metres)");
  if (!(min_length_m > 0.0 && min_length_m <= max_length_m && max_length_m <= 100.0))
    throw std::invalid_argument("SurfaceClutterOptions: need 0 < min_length_m <= max_length_m <= 100 (metres)");
}

std::vector<Segment3> make_surface_clutter(const Wireframe& wf, const SurfaceClutterOptions& o, DataRng& rng) {
  o.Check();
  std::vector<Segment3> out;
  if (wf.junctions.empty()) return out;
  const std::vector<Corner> corners = wireframe_corners(wf, o.corner_reach_m);
  if (!corners.empty())
    for (int i = 0; i < o.face_lines; ++i)
      out.push_back(face_line(corners[rng.below(corners.size())], rng.uniform(o.min_length_m, o.max_length_m), rng));

  Vec3 lo = wf.junctions.front(), hi = lo;
  for (const Vec3& p : wf.junctions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  for (int i = 0; i < o.ground_lines; ++i) {
    Vec3 centre(0.0, 0.0, lo.z());
    do {  // rejection from the box; the ring around the footprint has area (margin > 0), so this ends
      centre.x() = rng.uniform(lo.x() - o.ground_margin_m, hi.x() + o.ground_margin_m);
      centre.y() = rng.uniform(lo.y() - o.ground_margin_m, hi.y() + o.ground_margin_m);
    } while (centre.x() > lo.x() && centre.x() < hi.x() && centre.y() > lo.y() && centre.y() < hi.y());
    const double angle = rng.uniform(0.0, M_PI);
    out.push_back(centred_segment(centre, Vec3(std::cos(angle), std::sin(angle), 0.0),
                                  rng.uniform(o.min_length_m, o.max_length_m)));
  }
  return out;
}

LineCloud with_surface_clutter(const LineCloud& cloud, const SurfaceClutterOptions& options, uint64_t seed) {
  DataRng rng(seed);
  LineCloud out = cloud;
  const bool labelled = cloud.labels.size() == cloud.segments.size() && !cloud.segments.empty();
  const bool supported = !cloud.support.empty();
  for (const Segment3& s : make_surface_clutter(cloud.wireframe, options, rng)) {
    out.segments.push_back(s);
    if (labelled) out.labels.emplace_back();
    if (supported) out.support.emplace_back();
  }
  return out;
}

}  // namespace lc2wf

#include "tools/render/camera_ring.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <stdexcept>
#include <utility>

#include "dataset/geometry/footprint.h"

namespace lc2wf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Uniform in [-1, 1] from the raw engine output (platform independent).
double symmetric_uniform(std::mt19937_64& gen) { return 2.0 * static_cast<double>(gen() >> 11) * 0x1.0p-53 - 1.0; }

bool all_inside(const Camera& cam, const std::vector<Vec3>& points, double margin_px_x, double margin_px_y) {
  for (const Vec3& p : points) {
    const Vec3 c = cam.to_camera(p);
    if (c.z() <= 1e-6) return false;
    const Vec2 px = cam.project(p);
    if (px.x() < margin_px_x - 0.5 || px.x() > cam.width - 0.5 - margin_px_x) return false;
    if (px.y() < margin_px_y - 0.5 || px.y() > cam.height - 0.5 - margin_px_y) return false;
  }
  return true;
}

// Azimuth (degrees) a sector faces: the outward normal of one of the two long sides of the footprint's
// minimum-area rectangle (bit 0 of `pick`), or the corner between it and a neighbouring side (bit 1). nullopt
// when the footprint has no area.
std::optional<double> sector_centre_deg(const std::vector<Vec3>& points, bool on_corner, uint64_t pick) {
  const std::vector<Vec2> r = footprint_rectangle(points);  // counter-clockwise
  if (r.size() != 4) return std::nullopt;
  auto side = [&](int k) { return Vec2(r[(k + 1) % 4] - r[k]); };
  if (side(0).norm() < 1e-9 || side(1).norm() < 1e-9) return std::nullopt;
  auto outward = [&](int k) {
    const Vec2 d = side(k).normalized();
    return Vec2(d.y(), -d.x());
  };
  const int k = (side(0).norm() >= side(1).norm() ? 0 : 1) + 2 * static_cast<int>(pick & 1);
  Vec2 n = outward(k);
  if (on_corner) n += outward((k + ((pick >> 1) & 1 ? 1 : 3)) % 4);
  return std::atan2(n.y(), n.x()) * 180.0 / kPi;
}

// Smallest distance d at which place(d) frames every point: the framing test is monotone in the distance.
double closest_framing(const std::function<Camera(double)>& place, const std::vector<Vec3>& points, double size, double margin_x,
                       double margin_y) {
  double near_d = 1e-3 * size, far_d = 2.0 * size;
  while (!all_inside(place(far_d), points, margin_x, margin_y)) {
    far_d *= 2.0;
    if (far_d > 1e6 * size) throw std::invalid_argument("make_camera_ring: cannot frame the points");
  }
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (near_d + far_d);
    if (all_inside(place(mid), points, margin_x, margin_y))
      far_d = mid;
    else
      near_d = mid;
  }
  return far_d;
}

}  // namespace

void CameraRingOptions::Check() const {
  if (views < 1) throw std::invalid_argument("CameraRingOptions.views must be >= 1");
  if (width < 16 || height < 16) throw std::invalid_argument("CameraRingOptions.width/height must be >= 16");
  if (focal_px < 0) throw std::invalid_argument("CameraRingOptions.focal_px must be >= 0");
  if (min_elevation_deg < 0 || max_elevation_deg >= 90 || min_elevation_deg > max_elevation_deg)
    throw std::invalid_argument("CameraRingOptions.min/max_elevation_deg must satisfy 0 <= min <= max < 90");
  if (rings < 1) throw std::invalid_argument("CameraRingOptions.rings must be >= 1");
  if (azimuth_jitter_deg < 0 || elevation_jitter_deg < 0 || target_jitter < 0)
    throw std::invalid_argument("CameraRingOptions jitters must be >= 0");
  if (margin < 0 || margin >= 0.45) throw std::invalid_argument("CameraRingOptions.margin must be in [0, 0.45)");
  if (!(azimuth_span_deg > 0 && azimuth_span_deg <= 360))
    throw std::invalid_argument("CameraRingOptions.azimuth_span_deg must be in (0, 360]");
  const bool rings_only = min_camera_height_m == 0 && max_camera_height_m == 0;
  if (!rings_only && !(min_camera_height_m > 0 && min_camera_height_m <= max_camera_height_m && std::isfinite(max_camera_height_m)))
    throw std::invalid_argument("CameraRingOptions.min/max_camera_height_m must both be 0 (elevation rings) or satisfy 0 < min <= max");
  if (straight_walk && (rings_only || !(azimuth_span_deg <= 150)))
    throw std::invalid_argument("CameraRingOptions.straight_walk needs camera heights and an azimuth_span_deg of at most 150");
}

namespace {

// The axis-aligned box of a non-empty point set (lowest, highest corner): what a ring frames and what the
// pixel rule measures.
std::pair<Vec3, Vec3> bounding_box(const std::vector<Vec3>& points) {
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

}  // namespace

double view_scale_for(const std::vector<Vec3>& points, const CameraRingOptions& options, double max_metres_per_pixel,
                      int max_side) {
  if (!(max_metres_per_pixel > 0) || points.empty()) return 1.0;
  const auto [lo, hi] = bounding_box(points);
  const double wanted = (hi - lo).norm() / (max_metres_per_pixel * options.width);
  const double most = static_cast<double>(max_side) / std::max(options.width, options.height);
  return std::clamp(wanted, 1.0, std::max(1.0, most));
}

CameraRingOptions scaled_ring(const CameraRingOptions& options, double scale) {
  CameraRingOptions o = options;
  o.width = static_cast<int>(std::lround(options.width * scale));
  o.height = static_cast<int>(std::lround(options.height * scale));
  o.focal_px = options.focal_px * scale;
  return o;
}

Camera look_at(const Vec3& center, const Vec3& target, const Eigen::Matrix3d& K, int width, int height) {
  const Vec3 z = (target - center).normalized();
  Vec3 x = z.cross(Vec3::UnitZ());
  if (x.norm() < 1e-9) x = Vec3::UnitX();  // looking straight down: any image x works
  x.normalize();
  const Vec3 y = z.cross(x);
  Camera cam;
  cam.K = K;
  cam.R.row(0) = x.transpose();
  cam.R.row(1) = y.transpose();
  cam.R.row(2) = z.transpose();
  cam.t = -cam.R * center;
  cam.width = width;
  cam.height = height;
  return cam;
}

std::vector<Camera> make_camera_ring(const std::vector<Vec3>& points, const CameraRingOptions& options) {
  options.Check();
  if (points.empty()) throw std::invalid_argument("make_camera_ring: no points to frame");
  const auto [lo, hi] = bounding_box(points);
  const Vec3 centre = 0.5 * (lo + hi);
  const double size = std::max((hi - lo).norm(), 1e-3);
  const double f = options.focal_px > 0 ? options.focal_px : options.width * 35.0 / 36.0;
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  K(0, 0) = K(1, 1) = f;
  K(0, 2) = (options.width - 1) / 2.0;
  K(1, 2) = (options.height - 1) / 2.0;

  std::mt19937_64 gen(options.seed * 0x9E3779B97F4A7C15ull + 0x1234567ull);
  const double phase = 360.0 * (static_cast<double>(gen() >> 11) * 0x1.0p-53);
  const bool sector = options.azimuth_span_deg < 360.0;
  const bool by_height = options.max_camera_height_m > 0;
  // The whole ring draws nothing more here, so its cameras stay those of a ring without these options.
  const double sector_centre = sector ? sector_centre_deg(points, options.sector_on_corner, gen()).value_or(phase) : phase;
  const double margin_x = options.margin * options.width, margin_y = options.margin * options.height;
  std::vector<std::function<Camera(double)>> places;
  std::vector<double> distances;
  for (int i = 0; i < options.views; ++i) {
    const double el_draw = symmetric_uniform(gen);
    const double az_draw = symmetric_uniform(gen);
    double az_deg;
    if (sector) {
      const double first = sector_centre - 0.5 * options.azimuth_span_deg;
      az_deg = std::clamp(first + options.azimuth_span_deg * (i + 0.5) / options.views + options.azimuth_jitter_deg * az_draw, first,
                          first + options.azimuth_span_deg);
    } else {
      az_deg = phase + 360.0 * i / options.views + options.azimuth_jitter_deg * az_draw;
    }
    const double az = az_deg * kPi / 180.0;
    Vec3 target = centre;
    for (int k = 0; k < 3; ++k) target[k] += options.target_jitter * size * symmetric_uniform(gen);
    std::function<Camera(double)> place;
    if (by_height) {
      // Street level: a fixed height above the lowest point, moved back horizontally until the building fits.
      const double z = lo.z() + options.min_camera_height_m + (options.max_camera_height_m - options.min_camera_height_m) * 0.5 * (el_draw + 1.0);
      // On the arc: d along the azimuth from the aim point. On a walk: on the line d in front of the side,
      // where the ray from the centre at this azimuth meets it.
      Vec3 origin = target, dir(std::cos(az), std::sin(az), 0.0);
      if (options.straight_walk) {
        const double facing = sector_centre * kPi / 180.0;
        origin = centre;
        dir = Vec3(std::cos(facing), std::sin(facing), 0.0) + std::tan(az - facing) * Vec3(-std::sin(facing), std::cos(facing), 0.0);
      }
      place = [&, z, origin, dir, target](double d) {
        Vec3 c = origin + d * dir;
        c.z() = z;
        return look_at(c, target, K, options.width, options.height);
      };
    } else {
      const int ring = i % options.rings;
      const double base_el = options.rings == 1 ? 0.5 * (options.min_elevation_deg + options.max_elevation_deg)
                                                : options.min_elevation_deg + (options.max_elevation_deg - options.min_elevation_deg) * ring / (options.rings - 1);
      const double el = std::clamp(base_el + options.elevation_jitter_deg * el_draw, options.min_elevation_deg, options.max_elevation_deg) * kPi / 180.0;
      const Vec3 dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
      place = [&, dir, target](double d) { return look_at(target + d * dir, target, K, options.width, options.height); };
    }
    distances.push_back(closest_framing(place, points, size, margin_x, margin_y));
    places.push_back(place);
  }
  // A walk keeps its one line: every view steps back to the distance the farthest one needs.
  if (options.straight_walk) std::fill(distances.begin(), distances.end(), *std::max_element(distances.begin(), distances.end()));
  std::vector<Camera> cams;
  for (int i = 0; i < options.views; ++i) cams.push_back(places[i](distances[i]));
  return cams;
}

}  // namespace lc2wf

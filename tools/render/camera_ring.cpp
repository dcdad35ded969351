#include "tools/render/camera_ring.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

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
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 centre = 0.5 * (lo + hi);
  const double size = std::max((hi - lo).norm(), 1e-3);
  const double f = options.focal_px > 0 ? options.focal_px : options.width * 35.0 / 36.0;
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  K(0, 0) = K(1, 1) = f;
  K(0, 2) = (options.width - 1) / 2.0;
  K(1, 2) = (options.height - 1) / 2.0;

  std::mt19937_64 gen(options.seed * 0x9E3779B97F4A7C15ull + 0x1234567ull);
  const double phase = 360.0 * (static_cast<double>(gen() >> 11) * 0x1.0p-53);
  std::vector<Camera> cams;
  for (int i = 0; i < options.views; ++i) {
    const int ring = i % options.rings;
    const double base_el = options.rings == 1 ? 0.5 * (options.min_elevation_deg + options.max_elevation_deg)
                                              : options.min_elevation_deg + (options.max_elevation_deg - options.min_elevation_deg) * ring / (options.rings - 1);
    const double el = std::clamp(base_el + options.elevation_jitter_deg * symmetric_uniform(gen), options.min_elevation_deg,
                                 options.max_elevation_deg) * kPi / 180.0;
    const double az = (phase + 360.0 * i / options.views + options.azimuth_jitter_deg * symmetric_uniform(gen)) * kPi / 180.0;
    Vec3 target = centre;
    for (int k = 0; k < 3; ++k) target[k] += options.target_jitter * size * symmetric_uniform(gen);
    const Vec3 dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    // Smallest distance that frames every point: the framing test is monotone in the distance.
    double near_d = 1e-3 * size, far_d = 2.0 * size;
    while (!all_inside(look_at(target + far_d * dir, target, K, options.width, options.height), points,
                       options.margin * options.width, options.margin * options.height)) {
      far_d *= 2.0;
      if (far_d > 1e6 * size) throw std::invalid_argument("make_camera_ring: cannot frame the points");
    }
    for (int it = 0; it < 50; ++it) {
      const double mid = 0.5 * (near_d + far_d);
      if (all_inside(look_at(target + mid * dir, target, K, options.width, options.height), points,
                     options.margin * options.width, options.margin * options.height))
        far_d = mid;
      else
        near_d = mid;
    }
    cams.push_back(look_at(target + far_d * dir, target, K, options.width, options.height));
  }
  return cams;
}

}  // namespace lc2wf

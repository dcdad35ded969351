#include "tools/render/raster_renderer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>

#include "tools/render/sfm_textures.h"

namespace lc2wf {
namespace {

constexpr double kNear = 1e-3;
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// Sutherland-Hodgman clip of a camera-space polygon against z >= kNear.
std::vector<Vec3> clip_near(const std::vector<Vec3>& poly) {
  std::vector<Vec3> out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec3& a = poly[i];
    const Vec3& b = poly[(i + 1) % poly.size()];
    const bool ina = a.z() >= kNear, inb = b.z() >= kNear;
    if (ina) out.push_back(a);
    if (ina != inb) out.push_back(a + (b - a) * ((kNear - a.z()) / (b.z() - a.z())));
  }
  return out;
}

// Calls fn(x, y) for every pixel centre inside the 2D triangle (inclusive edges), clipped to w x h.
template <typename Fn>
void scan_triangle(const Vec2& p0, const Vec2& p1, const Vec2& p2, int w, int h, Fn&& fn) {
  const double area = (p1 - p0).x() * (p2 - p0).y() - (p1 - p0).y() * (p2 - p0).x();
  if (std::abs(area) < 1e-12) return;
  const double sgn = area > 0 ? 1.0 : -1.0;
  // Clamped in double before the int cast: casting a far-off or NaN coordinate to int is undefined.
  const auto pixel = [](double v, int n) { return static_cast<int>(std::clamp(v, -1.0, static_cast<double>(n))); };
  const double lo_x = std::ceil(std::min({p0.x(), p1.x(), p2.x()})), hi_x = std::floor(std::max({p0.x(), p1.x(), p2.x()}));
  const double lo_y = std::ceil(std::min({p0.y(), p1.y(), p2.y()})), hi_y = std::floor(std::max({p0.y(), p1.y(), p2.y()}));
  if (!(lo_x <= hi_x && lo_y <= hi_y)) return;  // also NaN
  const int x0 = std::max(0, pixel(lo_x, w)), x1 = std::min(w - 1, pixel(hi_x, w));
  const int y0 = std::max(0, pixel(lo_y, h)), y1 = std::min(h - 1, pixel(hi_y, h));
  if (x0 > x1 || y0 > y1) return;
  auto edge = [sgn](const Vec2& a, const Vec2& b) {
    // e(x,y) = A x + B y + C, non-negative inside.
    return std::array<double, 3>{sgn * -(b.y() - a.y()), sgn * (b.x() - a.x()),
                                 sgn * ((b.y() - a.y()) * a.x() - (b.x() - a.x()) * a.y())};
  };
  const auto e0 = edge(p1, p2), e1 = edge(p2, p0), e2 = edge(p0, p1);
  constexpr double kEps = -1e-9;
  for (int y = y0; y <= y1; ++y) {
    double w0 = e0[0] * x0 + e0[1] * y + e0[2];
    double w1 = e1[0] * x0 + e1[1] * y + e1[2];
    double w2 = e2[0] * x0 + e2[1] * y + e2[2];
    for (int x = x0; x <= x1; ++x) {
      if (w0 >= kEps && w1 >= kEps && w2 >= kEps) fn(x, y, w0, w1, w2);
      w0 += e0[0];
      w1 += e1[0];
      w2 += e2[0];
    }
  }
}

// Linear [0, 1] -> 8-bit sRGB through a table: the per-pixel pow() dominated the render time.
class SrgbTable {
 public:
  static constexpr int kSize = 4096;
  SrgbTable() {
    for (int i = 0; i < kSize; ++i) {
      const double linear = static_cast<double>(i) / (kSize - 1);
      const double srgb = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
      table_[i] = static_cast<float>(srgb * 255.0);
    }
  }
  float operator()(float linear) const {
    const int i = static_cast<int>(std::clamp(linear, 0.0f, 1.0f) * (kSize - 1) + 0.5f);
    return table_[i];
  }

 private:
  std::array<float, kSize> table_{};
};

const SrgbTable& srgb_table() {
  static const SrgbTable table;
  return table;
}

}  // namespace

void RasterOptions::Check() const {
  if (supersample < 1 || supersample > 4) throw std::invalid_argument("RasterOptions.supersample must be in [1, 4]");
  if (sun_elevation_deg <= 0 || sun_elevation_deg > 90)
    throw std::invalid_argument("RasterOptions.sun_elevation_deg must be in (0, 90]");
  if (ambient < 0 || ambient > 1) throw std::invalid_argument("RasterOptions.ambient must be in [0, 1]");
  if (view_light < 0 || view_light > 1) throw std::invalid_argument("RasterOptions.view_light must be in [0, 1]");
  if (noise_sigma < 0) throw std::invalid_argument("RasterOptions.noise_sigma must be >= 0");
  if (textures != "paper" && textures != "sfm" && textures != "photo")
    throw std::invalid_argument("RasterOptions.textures must be paper, sfm or photo, not " + textures);
  if (blur_sigma_px < 0 || blur_sigma_px > 10) throw std::invalid_argument("RasterOptions.blur_sigma_px must be in [0, 10]");
  if (shadow_map_size < 16 || shadow_map_size > 8192)
    throw std::invalid_argument("RasterOptions.shadow_map_size must be in [16, 8192]");
}

Camera supersampled_camera(const Camera& camera, int factor) {
  Camera c = camera;
  const double s = factor;
  c.K(0, 0) *= s;
  c.K(1, 1) *= s;
  c.K(0, 1) *= s;
  c.K(0, 2) = s * (camera.K(0, 2) + 0.5) - 0.5;
  c.K(1, 2) = s * (camera.K(1, 2) + 0.5) - 0.5;
  c.width = camera.width * factor;
  c.height = camera.height * factor;
  return c;
}

RasterRenderer::RasterRenderer(const PolyMesh& mesh, const RasterOptions& options, const PhotoScene& scene)
    : mesh_(build_faced_mesh(options.textures == "photo" ? scene_mesh(mesh, scene) : mesh)),
      options_(options),
      building_faces_(static_cast<int>(mesh.faces.size())) {
  options_.Check();
  style_.seed = options_.seed;
  style_.wall = (options_.seed >> 3) % 3 == 0 ? WallStyle::Brick : WallStyle::Siding;
  ground_z_ = std::numeric_limits<double>::infinity();
  for (const Vec3& v : mesh.vertices) ground_z_ = std::min(ground_z_, v.z());
  double az = options_.sun_azimuth_deg * kDegToRad, el = options_.sun_elevation_deg * kDegToRad;
  if (options_.textures == "photo") {
    scene.options.Check();
    if (scene.facades.size() != mesh.faces.size() && !scene.facades.empty())
      throw std::invalid_argument("RasterRenderer: the photo scene was made for another mesh");
    photo_options_ = scene.options;
    photo_ = std::make_shared<const PhotoTextures>(scene, options_.seed);
    if (scene.options.vary_sun) az = scene.sun_azimuth_deg * kDegToRad, el = scene.sun_elevation_deg * kDegToRad;
  }
  sun_ = Vec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  if (options_.shadows) build_shadow_map();
}

void RasterRenderer::build_shadow_map() {
  sun_a_ = sun_.unitOrthogonal();
  sun_b_ = sun_.cross(sun_a_);
  double min_a = 1e300, max_a = -1e300, min_b = 1e300, max_b = -1e300;
  for (const Vec3& v : mesh_.vertices) {
    min_a = std::min(min_a, v.dot(sun_a_));
    max_a = std::max(max_a, v.dot(sun_a_));
    min_b = std::min(min_b, v.dot(sun_b_));
    max_b = std::max(max_b, v.dot(sun_b_));
  }
  int n = options_.shadow_map_size;
  if (photo_) {
    // Clutter widens the map: keep the building's texel size (up to 4096 texels a side).
    double lo_a = 1e300, hi_a = -1e300, lo_b = 1e300, hi_b = -1e300;
    for (const MeshTriangle& tri : mesh_.triangles)
      if (tri.face < building_faces_)
        for (int k : tri.v) {
          lo_a = std::min(lo_a, mesh_.vertices[k].dot(sun_a_)), hi_a = std::max(hi_a, mesh_.vertices[k].dot(sun_a_));
          lo_b = std::min(lo_b, mesh_.vertices[k].dot(sun_b_)), hi_b = std::max(hi_b, mesh_.vertices[k].dot(sun_b_));
        }
    const double building_span = std::max(hi_a - lo_a, hi_b - lo_b), span = std::max(max_a - min_a, max_b - min_b);
    if (building_span > 0) n = static_cast<int>(std::min(4096.0, std::ceil(n * std::max(1.0, span / building_span))));
  }
  shadow_texel_ = std::max(max_a - min_a, max_b - min_b) / (n - 4) + 1e-9;
  shadow_min_a_ = min_a - 2 * shadow_texel_;
  shadow_min_b_ = min_b - 2 * shadow_texel_;
  shadow_height_ = cv::Mat(n, n, CV_32F, cv::Scalar(-std::numeric_limits<float>::infinity()));
  for (const MeshTriangle& tri : mesh_.triangles) {
    Vec2 p[3];
    double hgt[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3& X = mesh_.vertices[tri.v[k]];
      p[k] = Vec2((X.dot(sun_a_) - shadow_min_a_) / shadow_texel_ - 0.5, (X.dot(sun_b_) - shadow_min_b_) / shadow_texel_ - 0.5);
      hgt[k] = X.dot(sun_);
    }
    scan_triangle(p[0], p[1], p[2], n, n, [&](int x, int y, double w0, double w1, double w2) {
      const double s = w0 + w1 + w2;
      const float hv = static_cast<float>((w0 * hgt[0] + w1 * hgt[1] + w2 * hgt[2]) / s);
      float& cell = shadow_height_.at<float>(y, x);
      cell = std::max(cell, hv);
    });
  }
}

bool RasterRenderer::in_shadow(const Vec3& X) const {
  if (shadow_height_.empty()) return false;
  const double fx = std::round((X.dot(sun_a_) - shadow_min_a_) / shadow_texel_ - 0.5);
  const double fy = std::round((X.dot(sun_b_) - shadow_min_b_) / shadow_texel_ - 0.5);
  // Range-checked in double (false for NaN) before the int cast.
  if (!(fx >= 0 && fy >= 0 && fx < shadow_height_.cols && fy < shadow_height_.rows)) return false;
  const int x = static_cast<int>(fx), y = static_cast<int>(fy);
  // Bias covers the texel quantisation of tilted faces.
  return shadow_height_.at<float>(y, x) > X.dot(sun_) + 0.04 + 2.0 * shadow_texel_;
}

void RasterRenderer::depth_map(const Camera& camera, cv::Mat& depth, cv::Mat& face_ids) const {
  const int w = camera.width, h = camera.height;
  depth = cv::Mat(h, w, CV_32F, cv::Scalar(std::numeric_limits<float>::infinity()));
  face_ids = cv::Mat(h, w, CV_32S, cv::Scalar(-1));
  const double fx = camera.K(0, 0), fy = camera.K(1, 1), cx = camera.K(0, 2), cy = camera.K(1, 2);
  std::vector<Vec3> cam_pts(mesh_.vertices.size());
  for (size_t i = 0; i < cam_pts.size(); ++i) cam_pts[i] = camera.to_camera(mesh_.vertices[i]);
  // Per face: 1/z = ia * x + ib * y + ic (plane in camera space, exact perspective depth).
  std::vector<std::array<double, 3>> inv_z(mesh_.frames.size());
  std::vector<bool> usable(mesh_.frames.size());
  for (size_t f = 0; f < mesh_.frames.size(); ++f) {
    const Vec3 nc = camera.R * mesh_.frames[f].normal;
    const double dc = mesh_.frames[f].offset + nc.dot(camera.t);
    usable[f] = std::abs(dc) > 1e-9;  // a plane through the camera centre is seen edge-on
    if (!usable[f]) continue;
    inv_z[f] = {nc.x() / (fx * dc), nc.y() / (fy * dc), (nc.z() - nc.x() * cx / fx - nc.y() * cy / fy) / dc};
  }
  auto project = [&](const Vec3& c) { return Vec2(fx * c.x() / c.z() + cx, fy * c.y() / c.z() + cy); };
  for (const MeshTriangle& tri : mesh_.triangles) {
    if (!usable[tri.face]) continue;
    const auto& iz = inv_z[tri.face];
    auto write = [&](int x, int y, double, double, double) {
      const double inv = iz[0] * x + iz[1] * y + iz[2];
      if (inv <= 0) return;
      const float z = static_cast<float>(1.0 / inv);
      float& d = depth.at<float>(y, x);
      if (z < d) {
        d = z;
        face_ids.at<int>(y, x) = tri.face;
      }
    };
    const Vec3 &a = cam_pts[tri.v[0]], &b = cam_pts[tri.v[1]], &c = cam_pts[tri.v[2]];
    if (a.z() >= kNear && b.z() >= kNear && c.z() >= kNear) {
      scan_triangle(project(a), project(b), project(c), w, h, write);
      continue;
    }
    const std::vector<Vec3> poly = clip_near({a, b, c});
    for (size_t k = 1; k + 1 < poly.size(); ++k) scan_triangle(project(poly[0]), project(poly[k]), project(poly[k + 1]), w, h, write);
  }
}

RasterImage RasterRenderer::render(const Camera& camera, uint64_t view_seed) const {
  const Camera cam = options_.supersample > 1 ? supersampled_camera(camera, options_.supersample) : camera;
  cv::Mat depth, ids;
  depth_map(cam, depth, ids);
  const Eigen::Matrix3d Rt = cam.R.transpose();
  const Vec3 C = cam.center();
  const double fx = cam.K(0, 0), fy = cam.K(1, 1), cx = cam.K(0, 2), cy = cam.K(1, 2);
  const double ground_z = ground_z_;
  cv::Mat linear(cam.height, cam.width, CV_32FC3);
  const bool sfm = options_.textures == "sfm";
  const double view_light = options_.effective_view_light();
  const ViewPhotometry photometry = photo_ ? view_photometry(photo_options_, options_.seed, view_seed) : ViewPhotometry{};
  const Rgb sky = photo_ ? Rgb{static_cast<float>(sky_colour().r * photometry.exposure), static_cast<float>(sky_colour().g * photometry.exposure),
                               static_cast<float>(sky_colour().b * photometry.exposure)}
                         : sky_colour();
  for (int y = 0; y < cam.height; ++y) {
    const float* drow = depth.ptr<float>(y);
    const int* irow = ids.ptr<int>(y);
    cv::Vec3f* out = linear.ptr<cv::Vec3f>(y);
    for (int x = 0; x < cam.width; ++x) {
      const Vec3 m((x - cx) / fx, (y - cy) / fy, 1.0);
      Rgb colour;
      Vec3 X, n;
      if (irow[x] >= 0) {
        const FaceFrame& frame = mesh_.frames[irow[x]];
        X = Rt * (m * drow[x] - cam.t);
        n = frame.normal.dot(C - X) >= 0 ? frame.normal : Vec3(-frame.normal);
        if (photo_)
          colour = irow[x] < building_faces_ ? photo_->building(irow[x], frame, X) : photo_->clutter(irow[x] - building_faces_, frame, X);
        else
          colour = sfm ? sfm_surface_colour(frame, X, options_.seed) : surface_colour(frame, X, style_);
      } else {
        const Vec3 r = Rt * m;
        if (r.z() >= -1e-9 || C.z() <= ground_z) {
          out[x] = cv::Vec3f(sky.b, sky.g, sky.r);
          continue;
        }
        X = C + r * ((ground_z - C.z()) / r.z());
        n = Vec3::UnitZ();
        if (photo_)
          colour = photo_->ground(X.x(), X.y());
        else
          colour = sfm ? sfm_ground_colour(X.x(), X.y(), options_.seed) : ground_colour(X.x(), X.y(), style_);
      }
      double direct = std::max(0.0, n.dot(sun_));
      if (direct > 0 && options_.shadows && in_shadow(X)) direct = 0;
      // n faces the camera (or is the ground's up): the ambient share is dimmer the more obliquely it is seen.
      const double facing = std::clamp(n.dot((C - X).normalized()), 0.0, 1.0);
      double light = options_.ambient * (1.0 - view_light * (1.0 - facing)) + (1.0 - options_.ambient) * direct;
      if (photo_) light *= photometry.exposure;
      out[x] = cv::Vec3f(colour.b * light, colour.g * light, colour.r * light);
    }
  }
  if (options_.supersample > 1) cv::resize(linear, linear, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_AREA);
  if (options_.blur_sigma_px > 0) cv::GaussianBlur(linear, linear, cv::Size(), options_.blur_sigma_px * photometry.blur_gain);
  RasterImage result;
  result.image = cv::Mat(camera.height, camera.width, CV_8UC3);
  // Gaussian noise from a seeded table of Box-Muller draws (raw engine bits: identical on every platform,
  // unlike std::normal_distribution), indexed by a per-view random walk.
  std::mt19937_64 gen(options_.seed * 0x9E3779B97F4A7C15ull ^ (view_seed + 0x632BE59BD9B4E019ull));
  constexpr int kNoise = 1 << 14;
  std::vector<float> noise(kNoise, 0.0f);
  const double noise_sigma = options_.noise_sigma * photometry.noise_gain;
  if (noise_sigma > 0) {
    for (int i = 0; i < kNoise; ++i) {
      const double u1 = (static_cast<double>(gen() >> 11) + 0.5) * 0x1.0p-53, u2 = static_cast<double>(gen() >> 11) * 0x1.0p-53;
      noise[i] = static_cast<float>(noise_sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2));
    }
  }
  const SrgbTable& srgb = srgb_table();
  uint64_t state = gen();
  for (int y = 0; y < camera.height; ++y) {
    const cv::Vec3f* in = linear.ptr<cv::Vec3f>(y);
    cv::Vec3b* px = result.image.ptr<cv::Vec3b>(y);
    for (int x = 0; x < camera.width; ++x) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      const float n = noise[(state >> 40) & (kNoise - 1)];
      for (int c = 0; c < 3; ++c) px[x][c] = cv::saturate_cast<uint8_t>(srgb(in[x][c]) + n);
    }
  }
  return result;
}

}  // namespace lc2wf

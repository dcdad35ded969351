#include "tools/render/photo_textures.h"

#include <algorithm>
#include <cmath>

#include "tools/render/value_noise.h"

namespace lc2wf {
namespace {

Rgb scale(Rgb c, double s) { return {static_cast<float>(c.r * s), static_cast<float>(c.g * s), static_cast<float>(c.b * s)}; }
double frac(double x) { return x - std::floor(x); }

constexpr Rgb kPlasters[] = {{0.78f, 0.74f, 0.64f}, {0.82f, 0.81f, 0.78f}, {0.62f, 0.62f, 0.60f}, {0.75f, 0.58f, 0.36f}, {0.55f, 0.30f, 0.22f}};
constexpr Rgb kRoofs[] = {{0.50f, 0.18f, 0.10f}, {0.16f, 0.16f, 0.18f}, {0.32f, 0.22f, 0.16f}};
constexpr Rgb kCars[] = {{0.55f, 0.05f, 0.04f}, {0.06f, 0.12f, 0.40f}, {0.55f, 0.56f, 0.58f}, {0.03f, 0.03f, 0.03f}, {0.85f, 0.85f, 0.83f}};
constexpr Rgb kGlass = {0.07f, 0.09f, 0.12f};

template <size_t N>
Rgb pick(const Rgb (&palette)[N], uint64_t h) {
  return palette[h % N];
}

// Glass with a brighter band of sky reflection, a mullion and a transom in the frame colour.
Rgb window_pixel(const FacadeRect& r, double u, double z, double h, Rgb frame) {
  const double f = 0.04 * h;
  if (u < r.u0 + f || u > r.u1 - f || z < r.z0 + f || z > r.z1 - f) return frame;
  const double mid = 0.5 * (r.u0 + r.u1), transom = r.z0 + 0.7 * (r.z1 - r.z0);
  if (std::abs(u - mid) < 0.012 * h || std::abs(z - transom) < 0.012 * h) return frame;
  const double sky = 0.8 + 0.6 * std::clamp((z - r.z0) / (r.z1 - r.z0), 0.0, 1.0);
  return scale(kGlass, sky);
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = std::clamp((p - a).dot(d) / std::max(1e-12, d.squaredNorm()), 0.0, 1.0);
  return (p - a - t * d).norm();
}

}  // namespace

PhotoTextures::PhotoTextures(const PhotoScene& scene, uint64_t seed) : scene_(scene), seed_(seed) {
  const uint64_t h = mix_seed(seed, 0x7E77u);
  plaster_ = pick(kPlasters, h);
  roof_ = pick(kRoofs, h >> 8);
  window_frame_ = (h >> 16) % 3 == 0 ? Rgb{0.12f, 0.12f, 0.12f} : Rgb{0.86f, 0.86f, 0.84f};
}

Rgb PhotoTextures::wall(const FacadeLayout& L, const FaceFrame& frame, const Vec3& X) const {
  const double u = (X - frame.origin).dot(frame.axis_u), z = X.z(), h = L.storey_height;
  const PhotoOptions& o = scene_.options;
  if (o.gutters && L.peak_z - L.top_z < 0.05 * h && z > L.top_z - 0.07 * h) return {0.10f, 0.10f, 0.10f};
  for (const FacadeRect& d : L.doors)
    if (u > d.u0 - 0.04 * h && u < d.u1 + 0.04 * h && z >= d.z0 && z < d.z1 + 0.04 * h) {
      if (u < d.u0 || u > d.u1 || z > d.z1) return window_frame_;
      const bool panel = std::abs(z - (d.z0 + 0.5 * (d.z1 - d.z0))) < 0.01 * h;
      return panel ? Rgb{0.05f, 0.03f, 0.02f} : Rgb{0.22f, 0.12f, 0.06f};
    }
  for (const FacadeRect& r : L.windows) {
    if (r.contains(u, z)) return window_pixel(r, u, z, h, window_frame_);
    if (u > r.u0 - 0.06 * h && u < r.u1 + 0.06 * h && z < r.z0 && z > r.z0 - 0.06 * h) return {0.70f, 0.70f, 0.68f};  // sill
  }
  const double dirt = 0.9 + 0.1 * value_noise(u * 0.6, z * 0.6, seed_ + 21) + 0.05 * value_noise(u * 7, z * 7, seed_ + 22);
  // Rising damp: a darker plinth band at the foot of the wall.
  const double plinth = z < L.ground_z + 0.15 * h ? 0.7 : 1.0;
  return scale(plaster_, dirt * plinth);
}

Rgb PhotoTextures::roof(const FaceFrame& frame, const Vec3& X) const {
  const Vec3 d = X - frame.origin;
  const double u = d.dot(frame.axis_u), v = d.dot(frame.axis_v), h = scene_.storey_height;
  const double weather = 0.85 + 0.2 * value_noise(u * 0.4, v * 0.4, seed_ + 31);
  if (frame.kind == SurfaceKind::FlatRoof || !scene_.options.roof_tiles) {
    const double grit = 0.9 + 0.15 * value_noise(u * 9, v * 9, seed_ + 32);
    return scale(frame.kind == SurfaceKind::FlatRoof ? Rgb{0.35f, 0.34f, 0.33f} : roof_, weather * grit);
  }
  // Courses of about 0.33 m (fine lines along the eave), staggered joints, a shadow under each course.
  const double course = 0.11 * h, width = 0.1 * h;
  const double row = std::floor(v / course), t = frac(v / course);
  const double col = std::floor(u / width + 0.5 * std::fmod(std::abs(row), 2.0));
  double shade = 0.85 + 0.3 * cell_random(static_cast<int64_t>(col), static_cast<int64_t>(row), seed_ + 33);
  if (t > 0.82) shade *= 0.45;
  if (frac(u / width + 0.5 * std::fmod(std::abs(row), 2.0)) < 0.06) shade *= 0.8;
  return scale(roof_, shade * weather);
}

Rgb PhotoTextures::building(int face, const FaceFrame& frame, const Vec3& X) const {
  switch (frame.kind) {
    case SurfaceKind::Wall:
      if (face >= 0 && face < static_cast<int>(scene_.facades.size()) && scene_.facades[face].wall) return wall(scene_.facades[face], frame, X);
      return scale(plaster_, 0.9);
    case SurfaceKind::SlopedRoof:
    case SurfaceKind::FlatRoof:
      return roof(frame, X);
    case SurfaceKind::Base:
      break;
  }
  return {0.25f, 0.25f, 0.25f};
}

Rgb PhotoTextures::clutter(int face, const FaceFrame& frame, const Vec3& X) const {
  const uint64_t object = scene_.objects[face];
  const uint64_t h = mix_seed(seed_, object);
  const Vec3 d = X - frame.origin;
  const double u = d.dot(frame.axis_u), v = d.dot(frame.axis_v), hs = scene_.storey_height;
  switch (scene_.kinds[face]) {
    case ClutterKind::Chimney:
      return scale(h % 2 ? Rgb{0.45f, 0.20f, 0.13f} : plaster_, 0.9 + 0.1 * value_noise(u * 5, v * 5, h));
    case ClutterKind::Balcony:
      return scale({0.72f, 0.72f, 0.70f}, 0.92 + 0.08 * value_noise(u * 3, v * 3, h));
    case ClutterKind::CarBody:
      return pick(kCars, h);
    case ClutterKind::CarCabin:
      return {0.06f, 0.07f, 0.08f};
    case ClutterKind::Trunk:
      return {0.20f, 0.13f, 0.08f};
    case ClutterKind::Foliage: {
      // Leaf clumps: two octaves of noise in 3D-ish coordinates, strong contrast like real crowns.
      const double n = 0.6 * value_noise(X.x() * 2.5 + X.z() * 1.7, X.y() * 2.5 - X.z() * 2.1, h) +
                       0.4 * value_noise(X.x() * 9 - X.z() * 5, X.y() * 9 + X.z() * 4, h + 1);
      return scale({0.10f, 0.22f, 0.06f}, 0.45 + 0.9 * n);
    }
    case ClutterKind::NeighbourWall: {
      // A plain grid of windows by storey, in the face's own coordinates.
      const Rgb base = pick(kPlasters, h >> 4);
      const double zs = frac((X.z() - scene_.facades.front().ground_z) / hs), us = frac(u / hs);
      if (zs > 0.3 && zs < 0.75 && us > 0.29 && us < 0.71) return zs < 0.33 || zs > 0.72 || us < 0.32 || us > 0.68 ? window_frame_ : kGlass;
      return scale(base, 0.9 + 0.1 * value_noise(u * 0.5, X.z() * 0.5, h));
    }
    case ClutterKind::NeighbourRoof:
      return scale({0.30f, 0.30f, 0.31f}, 0.9 + 0.1 * value_noise(u * 2, v * 2, h));
  }
  return {0.5f, 0.5f, 0.5f};
}

Rgb PhotoTextures::ground(double x, double y) const {
  const Vec2 p(x, y);
  const GroundLayout& g = scene_.ground;
  const double h = scene_.storey_height;
  if (scene_.options.ground) {
    for (const auto& path : g.paths)
      if (distance_to_segment(p, path[0], path[1]) < g.path_half_width) {
        const double along = (p - path[0]).dot((path[1] - path[0]).normalized());
        const bool joint = frac(along / (0.2 * h)) < 0.06;
        return scale({0.55f, 0.53f, 0.50f}, joint ? 0.6 : 0.95 + 0.1 * value_noise(x * 4, y * 4, seed_ + 41));
      }
    if (g.road) {
      const Vec2 across_dir(-g.road_dir.y(), g.road_dir.x());
      const double across = std::abs((p - g.road_point).dot(across_dir)), along = (p - g.road_point).dot(g.road_dir);
      if (across < g.road_half_width) {
        if (across < 0.03 * h && frac(along / (1.0 * h)) < 0.5) return {0.80f, 0.80f, 0.78f};  // dashed centre line
        return scale({0.10f, 0.10f, 0.11f}, 0.9 + 0.2 * value_noise(x * 3, y * 3, seed_ + 42));
      }
      if (across < g.road_half_width + 0.06 * h) return {0.60f, 0.60f, 0.58f};  // kerb
      if (across < g.road_half_width + 0.6 * h) return scale({0.45f, 0.44f, 0.42f}, frac(along / (0.3 * h)) < 0.05 ? 0.7 : 1.0);  // pavement
    }
  }
  const double n = 0.5 * value_noise(x * 0.5, y * 0.5, seed_ + 11) + 0.3 * value_noise(x * 2.2, y * 2.2, seed_ + 13) +
                   0.2 * value_noise(x * 8, y * 8, seed_ + 14);
  return scale({0.11f, 0.20f, 0.06f}, 0.6 + 0.8 * n);
}

}  // namespace lc2wf

#include "tools/render/photo_textures.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "tools/render/value_noise.h"

namespace lc2wf {
namespace {

Rgb scale(Rgb c, double s) { return {static_cast<float>(c.r * s), static_cast<float>(c.g * s), static_cast<float>(c.b * s)}; }
double frac(double x) { return x - std::floor(x); }

constexpr Rgb kPlasters[] = {{0.78f, 0.74f, 0.64f}, {0.82f, 0.81f, 0.78f}, {0.62f, 0.62f, 0.60f}, {0.75f, 0.58f, 0.36f}, {0.55f, 0.30f, 0.22f}};
constexpr Rgb kRoofs[] = {{0.50f, 0.18f, 0.10f}, {0.16f, 0.16f, 0.18f}, {0.32f, 0.22f, 0.16f}};
constexpr Rgb kCars[] = {{0.55f, 0.05f, 0.04f}, {0.06f, 0.12f, 0.40f}, {0.55f, 0.56f, 0.58f}, {0.03f, 0.03f, 0.03f}, {0.85f, 0.85f, 0.83f}};
constexpr Rgb kGlass = {0.07f, 0.09f, 0.12f};
constexpr Rgb kSkyReflection = {0.42f, 0.47f, 0.55f};

template <size_t N>
Rgb pick(const Rgb (&palette)[N], uint64_t h) {
  return palette[h % N];
}

// Zero-mean material detail in [-1, 1]: octave noise from `finest` metres up (the sfm textures' noise,
// stretched the same way: standard deviation about 0.55, a few per cent clipped). Real surfaces have it at
// every scale (plaster grain and stains, lichen on tiles, asphalt grit, leaves); flat colours give SIFT
// nothing to find, and identical windows nothing to tell apart.
double detail(double u, double v, double finest, int octaves, uint64_t seed) {
  const double sd = 0.2 / std::sqrt(static_cast<double>(octaves));
  return std::clamp(0.55 / sd * (octave_noise(u, v, finest, octaves, seed) - 0.5), -1.0, 1.0);
}

// `c` with its brightness varied by `amount` x detail.
Rgb grained(Rgb c, double amount, double u, double v, double finest, int octaves, uint64_t seed) {
  return scale(c, std::max(0.0, 1.0 + amount * detail(u, v, finest, octaves, seed)));
}

// Plaster: stains over metres, grain from 4 cm up and damp patches of 10-50 cm with soft edges.
Rgb plaster(Rgb c, double u, double z, uint64_t seed) {
  const double stains = 0.88 + 0.12 * value_noise(u * 0.6, z * 0.6, seed + 21);
  const double patches = std::clamp((octave_noise(u, z, 0.12, 3, seed + 28) - 0.56) * 12, 0.0, 1.0);
  return grained(scale(c, stains * (1 - 0.22 * patches)), 0.3, u, z, 0.04, 6, seed + 22);
}

constexpr Rgb kCurtains[] = {{0.85f, 0.84f, 0.80f}, {0.75f, 0.68f, 0.55f}, {0.55f, 0.20f, 0.15f}, {0.45f, 0.50f, 0.55f}, {0.90f, 0.90f, 0.88f}};

// Glass with a brighter band of sky reflection, a mullion and a transom in the frame colour. What lies
// behind the glass differs per window (`id`): patches of mirrored sky, reflections of clouds and trees,
// curtains drawn to the sides, a net curtain below or a blind from the top, each in its own colour.
Rgb window_pixel(const FacadeRect& r, double u, double z, double h, Rgb frame, uint64_t id) {
  const double f = 0.04 * h;
  if (u < r.u0 + f || u > r.u1 - f || z < r.z0 + f || z > r.z1 - f) return frame;
  const double mid = 0.5 * (r.u0 + r.u1), transom = r.z0 + 0.7 * (r.z1 - r.z0);
  if (std::abs(u - mid) < 0.012 * h || std::abs(z - transom) < 0.012 * h) return frame;
  const double s = (u - r.u0) / (r.u1 - r.u0), t = (z - r.z0) / (r.z1 - r.z0);  // 0..1 across the window
  const uint64_t w = mix_seed(id);
  const double curtain = cell_random(0, 1, w), cover = 0.15 + 0.3 * cell_random(0, 2, w);
  const bool drawn = (curtain < 0.3 && (s < cover || s > 1 - cover)) || (curtain >= 0.3 && curtain < 0.45 && t < 0.25 + cover) ||
                     (curtain >= 0.45 && curtain < 0.6 && t > 1 - cover);
  if (drawn) return grained(kCurtains[w % std::size(kCurtains)], 0.15, u, z, 0.03, 3, w);
  const double sky = (0.8 + 0.6 * t) * (0.7 + 0.6 * cell_random(0, 4, w));
  // Patches of mirrored sky and clouds with soft edges, more or fewer per window.
  const double mirror = 0.85 * std::clamp((octave_noise(u, z, 0.08, 3, w + 2) - 0.5) * 6 + 0.5 * (cell_random(0, 5, w) - 0.3), 0.0, 1.0);
  const Rgb glass = grained(scale(kGlass, sky), 0.45, u, z, 0.04, 4, w + 1);
  return {static_cast<float>(glass.r * (1 - mirror) + kSkyReflection.r * mirror), static_cast<float>(glass.g * (1 - mirror) + kSkyReflection.g * mirror),
          static_cast<float>(glass.b * (1 - mirror) + kSkyReflection.b * mirror)};
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

Rgb PhotoTextures::wall(const FacadeLayout& L, int face, const FaceFrame& frame, const Vec3& X) const {
  const double u = (X - frame.origin).dot(frame.axis_u), z = X.z(), h = L.storey_height;
  // The face's own patch of the detail noise, kilometres from its neighbours' (as the sfm textures).
  const double su = u + 1000.0 * frame.texture_offset.x(), sz = z + 1000.0 * frame.texture_offset.y();
  const PhotoOptions& o = scene_.options;
  if (o.gutters && L.peak_z - L.top_z < 0.05 * h && z > L.top_z - 0.07 * h) return grained({0.10f, 0.10f, 0.10f}, 0.2, su, sz, 0.03, 4, seed_ + 23);
  for (const FacadeRect& d : L.doors)
    if (u > d.u0 - 0.04 * h && u < d.u1 + 0.04 * h && z >= d.z0 && z < d.z1 + 0.04 * h) {
      if (u < d.u0 || u > d.u1 || z > d.z1) return window_frame_;
      const bool panel = std::abs(z - (d.z0 + 0.5 * (d.z1 - d.z0))) < 0.01 * h;
      // Wood: grain stretched along the height.
      return panel ? Rgb{0.05f, 0.03f, 0.02f} : grained({0.22f, 0.12f, 0.06f}, 0.3, su * 8, sz, 0.08, 4, seed_ + 24);
    }
  for (size_t w = 0; w < L.windows.size(); ++w) {
    const FacadeRect& r = L.windows[w];
    if (r.contains(u, z)) return window_pixel(r, u, z, h, window_frame_, mix_seed(seed_ + 25, (static_cast<uint64_t>(face) << 20) + w));
    if (u > r.u0 - 0.06 * h && u < r.u1 + 0.06 * h && z < r.z0 && z > r.z0 - 0.06 * h)
      return grained({0.70f, 0.70f, 0.68f}, 0.1, su, sz, 0.03, 3, seed_ + 26);  // sill
  }
  // Rising damp: a darker plinth band.
  return scale(plaster(plaster_, su, sz, seed_), z < L.ground_z + 0.15 * h ? 0.7 : 1.0);
}

Rgb PhotoTextures::roof(const FaceFrame& frame, const Vec3& X) const {
  const Vec3 d = X - frame.origin;
  // The face's own patch of tiles and noise: symmetric roof faces must not look alike.
  const double u = d.dot(frame.axis_u) + 1000.0 * frame.texture_offset.x(), v = d.dot(frame.axis_v) + 1000.0 * frame.texture_offset.y();
  const double h = scene_.storey_height;
  // Weathering over metres and lichen, soot and grit from 4 cm up.
  const double weather = (0.85 + 0.2 * value_noise(u * 0.4, v * 0.4, seed_ + 31)) * (1 + 0.22 * detail(u, v, 0.04, 6, seed_ + 34));
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
      if (face >= 0 && face < static_cast<int>(scene_.facades.size()) && scene_.facades[face].wall) return wall(scene_.facades[face], face, frame, X);
      return plaster(scale(plaster_, 0.9), (X - frame.origin).dot(frame.axis_u) + 1000.0 * frame.texture_offset.x(),
                     X.z() + 1000.0 * frame.texture_offset.y(), seed_);  // gable ends
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
  const double su = u + 1000.0 * frame.texture_offset.x(), sv = v + 1000.0 * frame.texture_offset.y();  // the face's own noise
  switch (scene_.kinds[face]) {
    case ClutterKind::Chimney:
      return grained(scale(h % 2 ? Rgb{0.45f, 0.20f, 0.13f} : plaster_, 0.9 + 0.1 * value_noise(u * 5, v * 5, h)), 0.25, su, sv, 0.03, 5, h + 2);
    case ClutterKind::Balcony:
      return grained(scale({0.72f, 0.72f, 0.70f}, 0.92 + 0.08 * value_noise(u * 3, v * 3, h)), 0.15, su, sv, 0.03, 5, h + 2);
    case ClutterKind::CarBody:
      return grained(pick(kCars, h), 0.08, su, sv, 0.05, 4, h + 2);
    case ClutterKind::CarCabin:
      return grained({0.06f, 0.07f, 0.08f}, 0.5, su, sv, 0.04, 4, h + 2);  // reflections
    case ClutterKind::Trunk:
      return grained({0.20f, 0.13f, 0.08f}, 0.35, su * 4, sv, 0.08, 4, h + 2);  // bark, stretched along the trunk
    case ClutterKind::Foliage: {
      // Leaf clumps: two octaves of noise in 3D-ish coordinates, strong contrast like real crowns, and
      // single leaves and gaps from 3 cm up.
      const double x = X.x() * 2.5 + X.z() * 1.7, y = X.y() * 2.5 - X.z() * 2.1;
      const double n = 0.6 * value_noise(x, y, h) + 0.4 * value_noise(X.x() * 9 - X.z() * 5, X.y() * 9 + X.z() * 4, h + 1);
      return grained(scale({0.10f, 0.22f, 0.06f}, 0.45 + 0.9 * n), 0.45, x, y, 0.08, 4, h + 2);
    }
    case ClutterKind::NeighbourWall: {
      // A plain grid of windows by storey, in the face's own coordinates; every pane its own reflection.
      const Rgb base = pick(kPlasters, h >> 4);
      const double zs = (X.z() - scene_.facades.front().ground_z) / hs, us = u / hs;
      const double fz = frac(zs), fu = frac(us);
      if (fz > 0.3 && fz < 0.75 && fu > 0.29 && fu < 0.71) {
        if (fz < 0.33 || fz > 0.72 || fu < 0.32 || fu > 0.68) return window_frame_;
        const double pane = 0.6 + 0.8 * cell_random(static_cast<int64_t>(std::floor(us)), static_cast<int64_t>(std::floor(zs)), h + 3);
        return grained(scale(kGlass, pane), 0.45, su, sv, 0.04, 4, h + 4);
      }
      return plaster(base, su, X.z() + 1000.0 * frame.texture_offset.y(), h);
    }
    case ClutterKind::NeighbourRoof:
      return grained(scale({0.30f, 0.30f, 0.31f}, 0.9 + 0.1 * value_noise(u * 2, v * 2, h)), 0.2, su, sv, 0.04, 6, h + 2);
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
        return grained(scale({0.55f, 0.53f, 0.50f}, joint ? 0.6 : 0.95 + 0.1 * value_noise(x * 4, y * 4, seed_ + 41)), 0.15, x, y, 0.03, 5, seed_ + 44);
      }
    if (g.road) {
      const Vec2 across_dir(-g.road_dir.y(), g.road_dir.x());
      const double across = std::abs((p - g.road_point).dot(across_dir)), along = (p - g.road_point).dot(g.road_dir);
      if (across < g.road_half_width) {
        if (across < 0.03 * h && frac(along / (1.0 * h)) < 0.5) return grained({0.80f, 0.80f, 0.78f}, 0.1, x, y, 0.03, 4, seed_ + 45);  // dashed centre line
        // Asphalt: patches and stains over metres, grit from 3 cm up.
        return grained(scale({0.10f, 0.10f, 0.11f}, 0.9 + 0.2 * value_noise(x * 3, y * 3, seed_ + 42)), 0.3, x, y, 0.03, 7, seed_ + 46);
      }
      if (across < g.road_half_width + 0.06 * h) return grained({0.60f, 0.60f, 0.58f}, 0.15, x, y, 0.03, 5, seed_ + 47);  // kerb
      if (across < g.road_half_width + 0.6 * h)  // pavement
        return grained(scale({0.45f, 0.44f, 0.42f}, frac(along / (0.3 * h)) < 0.05 ? 0.7 : 1.0), 0.15, x, y, 0.03, 5, seed_ + 49);
    }
  }
  // Grass: patches over metres, dry spots of 0.2-1 m with soft edges, tufts from 3 cm up.
  const double n = 0.5 * value_noise(x * 0.5, y * 0.5, seed_ + 11) + 0.3 * value_noise(x * 2.2, y * 2.2, seed_ + 13) +
                   0.2 * value_noise(x * 8, y * 8, seed_ + 14);
  const float dry = static_cast<float>(std::clamp((octave_noise(x, y, 0.25, 3, seed_ + 16) - 0.56) * 12, 0.0, 1.0));
  const Rgb grass{0.11f + 0.12f * dry, 0.20f + 0.02f * dry, 0.06f + 0.03f * dry};
  return grained(scale(grass, 0.6 + 0.8 * n), 0.35, x, y, 0.03, 6, seed_ + 15);
}

}  // namespace lc2wf

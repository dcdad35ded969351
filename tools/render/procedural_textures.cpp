#include "tools/render/procedural_textures.h"

#include <cmath>

#include "tools/render/value_noise.h"

namespace lc2wf {
namespace {

Rgb scale(Rgb c, double s) {
  return {static_cast<float>(c.r * s), static_cast<float>(c.g * s), static_cast<float>(c.b * s)};
}

double frac(double x) { return x - std::floor(x); }

// Terracotta tiles: dark grooves between tile columns run down the slope, weaker course lines across.
Rgb roof_tiles(double u, double v, uint64_t seed) {
  constexpr double kColumn = 0.32, kCourse = 0.42;
  const double course = std::floor(v / kCourse);
  const double shift = std::fmod(course, 2.0) * 0.5 * kColumn;  // staggered courses
  const double cu = (u + shift) / kColumn;
  const double across = frac(cu), down = frac(v / kCourse);
  double shade = 0.88 + 0.12 * std::sin(across * 3.14159265);  // barrel profile of each tile
  if (across < 0.16) shade *= 0.45;                            // groove between columns
  if (down > 0.9) shade *= 0.7;                                // overlap shadow of the next course
  shade *= 0.9 + 0.2 * cell_random(static_cast<int64_t>(std::floor(cu)), static_cast<int64_t>(course), seed);
  return scale({0.62f, 0.22f, 0.12f}, shade);
}

Rgb flat_roof(double u, double v, uint64_t seed) {
  const double n = 0.85 + 0.15 * value_noise(u * 1.3, v * 1.3, seed + 7);
  return scale({0.30f, 0.29f, 0.28f}, n);
}

// Horizontal lap siding: boards of fixed height with a shadow line under each lap.
Rgb siding(double u, double z, uint64_t seed) {
  constexpr double kBoard = 0.28;
  const double t = frac(z / kBoard);
  double shade = 0.9 + 0.1 * t;
  if (t < 0.12) shade *= 0.72;
  shade *= 0.96 + 0.08 * cell_random(static_cast<int64_t>(std::floor(u / 3.0)), static_cast<int64_t>(std::floor(z / kBoard)), seed);
  return scale({0.80f, 0.79f, 0.74f}, shade);
}

Rgb brick(double u, double z, uint64_t seed) {
  constexpr double kRow = 0.16, kLen = 0.42, kMortar = 0.02;
  const double row = std::floor(z / kRow);
  const double uu = u + std::fmod(row, 2.0) * 0.5 * kLen;
  const bool mortar = frac(z / kRow) * kRow < kMortar || frac(uu / kLen) * kLen < kMortar;
  if (mortar) return {0.82f, 0.80f, 0.76f};
  const double j = 0.9 + 0.2 * cell_random(static_cast<int64_t>(std::floor(uu / kLen)), static_cast<int64_t>(row), seed);
  return scale({0.62f, 0.52f, 0.40f}, j);
}

}  // namespace

Rgb surface_colour(const FaceFrame& frame, const Vec3& X, const TextureStyle& style) {
  const Vec3 d = X - frame.origin;
  const double u = d.dot(frame.axis_u) + frame.texture_offset.x(), v = d.dot(frame.axis_v) + frame.texture_offset.y();
  switch (frame.kind) {
    case SurfaceKind::SlopedRoof:
      return roof_tiles(u, v, style.seed);
    case SurfaceKind::FlatRoof:
      return flat_roof(X.x(), X.y(), style.seed);
    case SurfaceKind::Wall:
      // Boards and brick rows follow world height so they line up around corners.
      return style.wall == WallStyle::Siding ? siding(u, X.z(), style.seed) : brick(u, X.z(), style.seed);
    case SurfaceKind::Base:
      break;
  }
  return {0.25f, 0.25f, 0.25f};
}

Rgb ground_colour(double x, double y, const TextureStyle& style) {
  const double n = 0.6 * value_noise(x * 0.6, y * 0.6, style.seed + 11) + 0.4 * value_noise(x * 2.5, y * 2.5, style.seed + 13);
  return scale({0.11f, 0.20f, 0.06f}, 0.8 + 0.4 * n);
}

Rgb sky_colour() { return {0.55f, 0.65f, 0.80f}; }

}  // namespace lc2wf

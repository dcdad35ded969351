#include "tools/render/sfm_textures.h"

#include <algorithm>
#include <cmath>

namespace lc2wf {
namespace {

uint64_t splitmix(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double lattice(int64_t i, int64_t j, uint64_t seed) {
  const uint64_t h = splitmix(seed ^ splitmix(static_cast<uint64_t>(i) * 0xD1B54A32D192ED03ull + static_cast<uint64_t>(j)));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

double smooth_noise(double x, double y, uint64_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i = static_cast<int64_t>(fx), j = static_cast<int64_t>(fy);
  double tx = x - fx, ty = y - fy;
  tx = tx * tx * (3 - 2 * tx);
  ty = ty * ty * (3 - 2 * ty);
  const double top = lattice(i, j, seed) * (1 - tx) + lattice(i + 1, j, seed) * tx;
  const double bottom = lattice(i, j + 1, seed) * (1 - tx) + lattice(i + 1, j + 1, seed) * tx;
  return top * (1 - ty) + bottom * ty;
}

// Equal-weight octaves (periods 0.09 m .. 5.76 m), stretched: the mean of 7 octaves has a standard
// deviation near 0.08, so x3.5 about 0.5 spans [0, 1] with about 8% of the points clipped.
double luminance(double u, double v, uint64_t seed) {
  constexpr int kOctaves = 7;
  double sum = 0, period = 0.09;
  for (int k = 0; k < kOctaves; ++k, period *= 2) sum += smooth_noise(u / period, v / period, seed + 0x51ED27ull * k);
  const double stretched = std::clamp(0.5 + 3.5 * (sum / kOctaves - 0.5), 0.0, 1.0);
  return 0.08 + 0.92 * stretched;
}

Rgb tinted(float r, float g, float b, double l) {
  return {static_cast<float>(r * l), static_cast<float>(g * l), static_cast<float>(b * l)};
}

}  // namespace

Rgb sfm_surface_colour(const FaceFrame& frame, const Vec3& X, uint64_t seed) {
  const Vec3 d = X - frame.origin;
  // The per-face offsets differ by metres; x1000 puts faces kilometres apart in the noise.
  const double u = d.dot(frame.axis_u) + 1000.0 * frame.texture_offset.x();
  const double v = d.dot(frame.axis_v) + 1000.0 * frame.texture_offset.y();
  const double l = luminance(u, v, seed);
  switch (frame.kind) {
    case SurfaceKind::SlopedRoof: return tinted(0.75f, 0.35f, 0.25f, l);
    case SurfaceKind::FlatRoof: return tinted(0.55f, 0.55f, 0.58f, l);
    case SurfaceKind::Wall: return tinted(0.90f, 0.85f, 0.75f, l);
    default: return tinted(0.45f, 0.45f, 0.45f, l);
  }
}

Rgb sfm_ground_colour(double x, double y, uint64_t seed) { return tinted(0.40f, 0.55f, 0.30f, luminance(x, y, seed ^ 0x6A09E667ull)); }

}  // namespace lc2wf

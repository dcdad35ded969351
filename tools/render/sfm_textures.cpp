#include "tools/render/sfm_textures.h"

#include <algorithm>
#include <cmath>

#include "tools/render/value_noise.h"

namespace lc2wf {
namespace {

// Equal-weight octaves (periods 0.09 m .. 5.76 m), stretched: the mean of 7 octaves has a standard
// deviation near 0.08, so x3.5 about 0.5 spans [0, 1] with about 8% of the points clipped.
double luminance(double u, double v, uint64_t seed) {
  const double stretched = std::clamp(0.5 + 3.5 * (octave_noise(u, v, 0.09, 7, seed) - 0.5), 0.0, 1.0);
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

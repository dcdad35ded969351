// The rasteriser's SfM textures: deterministic, high contrast, no repeats, and symmetric faces differ.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tools/render/sfm_textures.h"

namespace lc2wf {
namespace {

double grey(const Rgb& c) { return 0.3 * c.r + 0.59 * c.g + 0.11 * c.b; }

FaceFrame wall(Vec2 offset) {
  FaceFrame f;
  f.kind = SurfaceKind::Wall;
  f.normal = Vec3::UnitY();
  f.axis_u = Vec3::UnitX();
  f.axis_v = -Vec3::UnitZ();
  f.texture_offset = offset;
  return f;
}

// Luminance on a 10 cm grid over a 6 m x 3 m patch of the face, starting `shift` metres along u.
std::vector<double> patch(const FaceFrame& f, double shift, uint64_t seed) {
  std::vector<double> out;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 30; ++j) out.push_back(grey(sfm_surface_colour(f, Vec3(shift + 0.1 * i, 0, -0.1 * j), seed)));
  return out;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= a.size(), mb /= b.size();
  double ab = 0, aa = 0, bb = 0;
  for (size_t i = 0; i < a.size(); ++i) ab += (a[i] - ma) * (b[i] - mb), aa += (a[i] - ma) * (a[i] - ma), bb += (b[i] - mb) * (b[i] - mb);
  return ab / std::sqrt(aa * bb);
}

TEST(SfmTextures, HighContrastAndDeterministic) {
  const auto p = patch(wall(Vec2(1.3, 0.7)), 0, 5);
  EXPECT_EQ(p, patch(wall(Vec2(1.3, 0.7)), 0, 5));
  double lo = 1, hi = 0, mean = 0, var = 0;
  for (double x : p) lo = std::min(lo, x), hi = std::max(hi, x), mean += x;
  mean /= p.size();
  for (double x : p) var += (x - mean) * (x - mean);
  EXPECT_GT(hi - lo, 0.5);
  EXPECT_GT(std::sqrt(var / p.size()), 0.08);  // paper-like siding varies far less
}

TEST(SfmTextures, NoRepeatsAndSymmetricFacesDiffer) {
  const auto base = patch(wall(Vec2(1.3, 0.7)), 0, 5);
  EXPECT_GT(correlation(base, patch(wall(Vec2(1.3, 0.7)), 0.05, 5)), 0.8);  // a 5 cm shift: the same pattern
  for (double shift : {2.4, 4.8, 8.0, 16.0, 24.0}) EXPECT_LT(std::abs(correlation(base, patch(wall(Vec2(1.3, 0.7)), shift, 5))), 0.3) << shift;
  EXPECT_LT(std::abs(correlation(base, patch(wall(Vec2(4.2, 2.9)), 0, 5))), 0.3);  // another face's offset
  EXPECT_LT(std::abs(correlation(base, patch(wall(Vec2(1.3, 0.7)), 0, 6))), 0.3);  // another building's seed
}

}  // namespace
}  // namespace lc2wf

// Scale from a facade's storeys (dataset/photo/storey_scale.h): hand-made facades of windows in a frame of
// arbitrary units, against bare walls and clutter without a rhythm.
#include <gtest/gtest.h>

#include <random>

#include "dataset/photo/storey_scale.h"

namespace lc2wf {
namespace {

constexpr double kUnitsPerMetre = 0.37;  // an SfM frame's arbitrary scale

Segment3 in_units(const Vec3& a, const Vec3& b) { return {a * kUnitsPerMetre, b * kUnitsPerMetre}; }

// A box of `storeys` storeys of `storey_m` metres, flat roof: its eaves, base and four full-height corners.
std::vector<Segment3> bare_box(int storeys, double storey_m) {
  const double h = storeys * storey_m;
  std::vector<Segment3> s;
  for (double z : {0.0, h})
    for (double y : {0.0, 10.0}) s.push_back(in_units(Vec3(0, y, z), Vec3(20, y, z)));
  for (double x : {0.0, 20.0})
    for (double y : {0.0, 10.0}) s.push_back(in_units(Vec3(x, y, 0), Vec3(x, y, h)));
  return s;
}

// Plus windows on both long walls, from 0.9 m to 2.2 m above each floor: sill, lintel and two sides, each
// side detected in one or two pieces, the ends jittered by triangulation noise; and a roof's tile courses
// every 0.25 m (horizontal: no part of the rhythm).
std::vector<Segment3> facade(int storeys, double storey_m, unsigned seed) {
  std::vector<Segment3> s = bare_box(storeys, storey_m);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.03);
  for (int k = 0; k < storeys; ++k)
    for (double y : {0.0, 10.0})
      for (double x = 1.5; x + 1.2 < 20; x += 3.0) {
        const double sill = k * storey_m + 0.9, lintel = k * storey_m + 2.2;
        for (double z : {sill, lintel}) s.push_back(in_units(Vec3(x, y, z + noise(rng)), Vec3(x + 1.2, y, z + noise(rng))));
        for (double u : {x, x + 1.2}) {
          const double cut = (rng() % 2) ? 0.5 * (sill + lintel) : lintel;
          s.push_back(in_units(Vec3(u, y, sill + noise(rng)), Vec3(u, y, cut + noise(rng))));
          if (cut < lintel) s.push_back(in_units(Vec3(u, y, cut + 0.05), Vec3(u, y, lintel + noise(rng))));
        }
      }
  const double h = storeys * storey_m;
  for (double z = 0.1; z < 1.5; z += 0.25) s.push_back(in_units(Vec3(2, 5, h + z), Vec3(18, 5, h + z)));
  return s;
}

double height_of(int storeys, double storey_m) { return storeys * storey_m * kUnitsPerMetre; }

TEST(StoreyScale, WindowRowsGiveTheStoreyInTheCloudsUnits) {
  for (int storeys : {3, 5, 12}) {
    const StoreyScale s = estimate_storey_scale(facade(storeys, 3.2, 7), height_of(storeys, 3.2));
    ASSERT_TRUE(s.found) << storeys << " storeys: " << s.why_not;
    EXPECT_NEAR(s.period, 3.2 * kUnitsPerMetre, 0.03 * 3.2 * kUnitsPerMetre) << storeys << " storeys";
    EXPECT_NEAR(s.storeys, storeys, 0.2 * storeys / 3);
    // The default storey of 3 m: 6 % off for these 3.2 m storeys, never a multiple of them.
    EXPECT_NEAR(s.metres_per_unit, 3.0 / (3.2 * kUnitsPerMetre), 0.03 * 3.0 / (3.2 * kUnitsPerMetre));
  }
}

TEST(StoreyScale, TheUsersStoreyHeightSetsTheScale) {
  StoreyScaleOptions o;
  o.storey_height_m = 4.0;
  const StoreyScale s = estimate_storey_scale(facade(4, 4.0, 3), height_of(4, 4.0), o);
  ASSERT_TRUE(s.found) << s.why_not;
  EXPECT_NEAR(s.metres_per_unit, 1.0 / kUnitsPerMetre, 0.03 / kUnitsPerMetre);
}

TEST(StoreyScale, BareWallsAndClutterWithoutRhythmGiveNoEstimate) {
  const StoreyScale bare = estimate_storey_scale(bare_box(4, 3.0), height_of(4, 3.0));
  EXPECT_FALSE(bare.found);
  EXPECT_EQ(bare.why_not, "too few short vertical lines");

  // Short vertical lines at uniformly random heights (trees, poles, clutter): many of them, no period.
  std::vector<Segment3> clutter = bare_box(4, 3.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> z(0.0, 11.0), x(0.0, 20.0), len(0.3, 2.0);
  for (int i = 0; i < 400; ++i) {
    const double x0 = x(rng), z0 = z(rng);
    clutter.push_back(in_units(Vec3(x0, 0, z0), Vec3(x0, 0, z0 + len(rng))));
  }
  const StoreyScale random = estimate_storey_scale(clutter, height_of(4, 3.0));
  EXPECT_FALSE(random.found) << "period " << random.period << ", strength " << random.strength;

  StoreyScaleOptions off;
  off.storey_height_m = 0;
  EXPECT_EQ(estimate_storey_scale(facade(4, 3.0, 1), height_of(4, 3.0), off).why_not, "turned off");
}

TEST(StoreyScale, BadOptionsAreRefusedByName) {
  StoreyScaleOptions o;
  o.min_repeats = 1;
  EXPECT_THROW(estimate_storey_scale({}, 1.0, o), std::invalid_argument);
  try {
    StoreyScaleOptions bad;
    bad.storey_height_m = -1;
    bad.Check();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("storey_height_m"), std::string::npos);
  }
}

}  // namespace
}  // namespace lc2wf

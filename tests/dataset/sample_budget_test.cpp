// The sample budget grows with the cloud: one pass per metres_per_pass of the longer horizontal side, the
// 2nd-98th percentile box so a few stray lines do not count, between 1 and the cap.
#include <gtest/gtest.h>

#include <algorithm>

#include "dataset/sampling/sampling.h"

namespace lc2wf {
namespace {

std::vector<Segment3> line_of_segments(double length_m, int count) {
  std::vector<Segment3> s;
  for (int i = 0; i < count; ++i) {
    const double x = length_m * i / (count - 1);
    s.push_back({Vec3(x, 0, 3), Vec3(x, 1, 3)});
  }
  return s;
}

TEST(SampleBudget, OnePassPerMetresOfTheLongerSide) {
  EXPECT_EQ(passes_for_extent(line_of_segments(10, 200), 40), 1);
  EXPECT_EQ(passes_for_extent(line_of_segments(39, 200), 40), 1);
  EXPECT_EQ(passes_for_extent(line_of_segments(42, 200), 40), 2);  // its 2nd-98th percentile span: 40.3 m
  EXPECT_EQ(passes_for_extent(line_of_segments(150, 200), 40), 4);
  EXPECT_EQ(passes_for_extent(line_of_segments(10000, 200), 40), 8);     // capped
  EXPECT_EQ(passes_for_extent(line_of_segments(10000, 200), 40, 3), 3);  // a smaller cap
  EXPECT_EQ(passes_for_extent(line_of_segments(150, 200), 0), 1);        // off
  EXPECT_EQ(passes_for_extent({}, 40), 1);
}

TEST(SampleBudget, AFewStrayLinesDoNotCount) {
  std::vector<Segment3> s = line_of_segments(20, 200);
  s.push_back({Vec3(500, 0, 0), Vec3(501, 0, 0)});  // 1 of 201: beyond the 98th percentile
  EXPECT_EQ(passes_for_extent(s, 40), 1);
  // The y extent counts as much as x.
  std::vector<Segment3> t;
  for (const Segment3& g : line_of_segments(100, 200)) t.push_back({Vec3(g.a.y(), g.a.x(), 0), Vec3(g.b.y(), g.b.x(), 0)});
  EXPECT_EQ(passes_for_extent(t, 40), 3);
}

// A cluttered cloud: 40 "corners" where 12 endpoints meet, spread over half a metre as many views' fragments
// are (C = 7/12), among 400 tighter "clutter" spots of 6 endpoints (C = 1), 1 m apart: every spot is a seed,
// they outnumber the 256 sample points, and the release's order (by C) would put all the clutter first.
std::vector<Vec3> corners_among_clutter() {
  std::vector<Vec3> p;
  auto spot = [&](double x, double y, int endpoints, double step) {
    for (int k = 0; k < endpoints; ++k) p.push_back(Vec3(x + step * (k - 0.5 * (endpoints - 1)), y, 1.0));
  };
  for (int k = 0; k < 400; ++k) spot(k % 20, k / 20, 6, 0.01);
  for (int k = 0; k < 40; ++k) spot(k % 8 + 0.5, k / 8 + 30.5, 12, 0.045);
  return p;
}

TEST(SampleBudget, TheSeedsWithTheMostEndpointsComeFirst) {
  const std::vector<Vec3> p = corners_among_clutter();
  SamplingOptions o;
  o.seeds = DensitySeedRule::loose();
  const std::vector<int> seeds = density_seeds(p, o);
  ASSERT_EQ(seeds.size(), 440u);
  for (int k = 0; k < 40; ++k) EXPECT_GE(seeds[k], 2400) << k;  // the 40 corners (indices 2400 on) lead
  auto corners_in = [](const std::vector<int>& sample, size_t first, size_t last) {
    int n = 0;
    for (size_t k = first; k < last; ++k) n += sample[k] >= 2400;
    return n;
  };
  const std::vector<int> one = sample_endpoints(p, o);
  ASSERT_EQ(one.size(), 256u);
  EXPECT_EQ(corners_in(one, 0, one.size()), 40);  // every corner gets a sample point in one pass
  // With two passes, the 184 seeds the first pass could not hold lead the second: every seed is sampled.
  o.passes = 2;
  const std::vector<int> two = sample_endpoints(p, o);
  ASSERT_EQ(two.size(), 512u);
  EXPECT_TRUE(std::equal(one.begin(), one.end(), two.begin()));
  std::vector<char> sampled(p.size(), 0);
  for (int s : two) sampled[static_cast<size_t>(s)] = 1;
  for (int s : seeds) EXPECT_TRUE(sampled[static_cast<size_t>(s)]) << s;
}

}  // namespace
}  // namespace lc2wf

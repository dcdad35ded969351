// The sample budget grows with the cloud: one pass per metres_per_pass of the longer horizontal side, the
// 2nd-98th percentile box so a few stray lines do not count, between 1 and the cap.
#include <gtest/gtest.h>

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
  EXPECT_EQ(passes_for_extent(line_of_segments(41.5, 200), 40), 2);
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

}  // namespace
}  // namespace lc2wf

// The closest points of two segments and the crossing test (dataset/geometry/segment_crossing.h).
#include "dataset/geometry/segment_crossing.h"

#include <gtest/gtest.h>

namespace lc2wf {
namespace {

TEST(SegmentCrossing, ClosestPointsOfSkewParallelAndDegenerateSegments) {
  // Skew: the x axis from -1 to 1 at z = 0 and the y axis from -1 to 1 at z = 0.5 meet above the origin.
  auto c = segment_closest_points({-1, 0, 0}, {1, 0, 0}, {0, -1, 0.5}, {0, 1, 0.5});
  EXPECT_NEAR(c.s, 0.5, 1e-12);
  EXPECT_NEAR(c.t, 0.5, 1e-12);
  EXPECT_NEAR(c.distance, 0.5, 1e-12);
  // The closest point beyond an end clamps to it: b starts 1 m past a's end.
  c = segment_closest_points({0, 0, 0}, {1, 0, 0}, {2, -1, 0}, {2, 1, 0});
  EXPECT_NEAR(c.s, 1.0, 1e-12);
  EXPECT_NEAR(c.t, 0.5, 1e-12);
  EXPECT_NEAR(c.distance, 1.0, 1e-12);
  // Parallel, 0.2 m apart and overlapping.
  c = segment_closest_points({0, 0, 0}, {4, 0, 0}, {1, 0.2, 0}, {3, 0.2, 0});
  EXPECT_NEAR(c.distance, 0.2, 1e-12);
  // Parallel and apart along their line: the gap between the nearest ends.
  c = segment_closest_points({0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {5, 0, 0});
  EXPECT_NEAR(c.distance, 2.0, 1e-12);
  // A point against a segment, and two points.
  c = segment_closest_points({0.5, 1, 0}, {0.5, 1, 0}, {0, 0, 0}, {1, 0, 0});
  EXPECT_NEAR(c.t, 0.5, 1e-12);
  EXPECT_NEAR(c.distance, 1.0, 1e-12);
  EXPECT_NEAR(segment_closest_points({0, 0, 0}, {0, 0, 0}, {0, 3, 4}, {0, 3, 4}).distance, 5.0, 1e-12);
}

TEST(SegmentCrossing, DiagonalsOfAWallCrossItsSidesDoNot) {
  // A 10 x 5 m wall in the x-z plane: its two diagonals cross at the centre; a side and a diagonal share a
  // corner; the mid-height line ends on the sides (a T, not a crossing).
  const Vec3 a{0, 0, 0}, b{10, 0, 0}, c{10, 0, 5}, d{0, 0, 5};
  EXPECT_TRUE(segments_cross(a, c, b, d, 0.1, 0.3, 10.0));
  EXPECT_FALSE(segments_cross(a, b, a, c, 0.1, 0.3, 10.0));
  EXPECT_FALSE(segments_cross({0, 0, 2.5}, {10, 0, 2.5}, b, c, 0.1, 0.3, 10.0));
  // The same diagonals 0.2 m apart cross at 0.25 m, not at 0.1 m.
  const Vec3 off{0, 0.2, 0};
  EXPECT_FALSE(segments_cross(a, c, b + off, d + off, 0.1, 0.3, 10.0));
  EXPECT_TRUE(segments_cross(a, c, b + off, d + off, 0.25, 0.3, 10.0));
  // Crossing 0.2 m from an end is within a 0.3 m margin, so not a crossing; it is with a 0.1 m margin.
  EXPECT_FALSE(segments_cross({0, 0, 0}, {4, 0, 0}, {0.2, -1, 0}, {0.2, 1, 0}, 0.1, 0.3, 10.0));
  EXPECT_TRUE(segments_cross({0, 0, 0}, {4, 0, 0}, {0.2, -1, 0}, {0.2, 1, 0}, 0.1, 0.1, 10.0));
  // Nearly parallel (5 degrees apart) is an overlap, not a crossing.
  EXPECT_FALSE(segments_cross({-5, 0, 0}, {5, 0, 0}, {-5, -0.437, 0}, {5, 0.437, 0}, 0.1, 0.3, 10.0));
  // Too short to have an interior beyond the margins.
  EXPECT_FALSE(segments_cross({-0.25, 0, 0}, {0.25, 0, 0}, {0, -1, 0}, {0, 1, 0}, 0.1, 0.3, 10.0));
}

}  // namespace
}  // namespace lc2wf

#include "dataset/geometry/segment_split.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "dataset/formats/errors.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"

namespace lc2wf {
namespace {

bool same_point(const Vec3& p, const Vec3& q) { return (p - q).norm() < 1e-12; }

TEST(SegmentSplit, LongSegmentsBecomeTwoStaggeredChainsShortOnesStay) {
  LineCloud c;
  c.name = "b";
  c.segments = {{Vec3(0, 0, 0), Vec3(3, 0, 0)}, {Vec3(0, 1, 0), Vec3(0, 1, 1)}};
  const LineCloud s = split_long_segments(c, 1.5);
  // 3 m at 1.5 m: chain [0, 1.5] [1.5, 3] and the staggered chain [0, 0.75] [0.75, 2.25] [2.25, 3].
  ASSERT_EQ(s.segments.size(), 6u);
  const double ends[5][2] = {{0, 1.5}, {1.5, 3}, {0, 0.75}, {0.75, 2.25}, {2.25, 3}};
  for (int k = 0; k < 5; ++k) {
    EXPECT_TRUE(same_point(s.segments[k].a, Vec3(ends[k][0], 0, 0))) << k;
    EXPECT_TRUE(same_point(s.segments[k].b, Vec3(ends[k][1], 0, 0))) << k;
  }
  EXPECT_TRUE(same_point(s.segments[5].a, c.segments[1].a));  // 1 m <= 1.5 m: as it was
  EXPECT_TRUE(same_point(s.segments[5].b, c.segments[1].b));
}

TEST(SegmentSplit, EveryPieceIsOnItsSegmentNoLongerThanTheLimitAndBothChainsCoverIt) {
  const LineCloud c = make_synthetic_line_cloud(make_random_building(3, "b"), 3);
  const double limit = 0.8;
  const LineCloud s = split_long_segments(c, limit);
  size_t at = 0;
  for (const Segment3& seg : c.segments) {
    const double length = seg.length();
    const int64_t n = static_cast<int64_t>(std::ceil(length / limit - 1e-9));
    if (n <= 1) {
      ASSERT_TRUE(same_point(s.segments[at].a, seg.a) && same_point(s.segments[at].b, seg.b));
      ++at;
      continue;
    }
    const Vec3 d = (seg.b - seg.a) / length;
    double covered = 0.0;
    for (int64_t k = 0; k < 2 * n + 1; ++k) {
      const Segment3& p = s.segments[at + static_cast<size_t>(k)];
      EXPECT_LE(p.length(), limit + 1e-9);
      EXPECT_GT(p.length(), 0.0);
      for (const Vec3& e : {p.a, p.b}) EXPECT_LT(((e - seg.a) - d.dot(e - seg.a) * d).norm(), 1e-9);
      covered += p.length();
    }
    EXPECT_NEAR(covered, 2 * length, 1e-9);  // two chains, no gap, no overlap within a chain
    EXPECT_TRUE(same_point(s.segments[at].a, seg.a));                              // first chain starts at a
    EXPECT_TRUE(same_point(s.segments[at + static_cast<size_t>(n)].a, seg.a));     // and so does the second
    EXPECT_TRUE(same_point(s.segments[at + static_cast<size_t>(2 * n)].b, seg.b));  // both end at b
    at += static_cast<size_t>(2 * n + 1);
  }
  EXPECT_EQ(at, s.segments.size());
  EXPECT_GT(s.segments.size(), c.segments.size());
}

TEST(SegmentSplit, KeepsTheBuildingDropsSupportsAndLabels) {
  const LineCloud c = make_synthetic_line_cloud(make_random_building(5, "b"), 5);
  ASSERT_FALSE(c.labels.empty());
  const LineCloud s = split_long_segments(c, 1.0);
  EXPECT_EQ(s.name, c.name);
  EXPECT_EQ(s.wireframe.junctions.size(), c.wireframe.junctions.size());
  EXPECT_EQ(s.wireframe.edges, c.wireframe.edges);
  EXPECT_EQ(s.cameras.size(), c.cameras.size());
  EXPECT_TRUE(s.labels.empty());
  EXPECT_TRUE(s.support.empty());
  EXPECT_NO_THROW(validate_line_cloud(s, "split"));
  EXPECT_EQ(split_long_segments(c, 0.0).segments.size(), c.segments.size());  // 0: off
}

TEST(SegmentSplit, RefusesNonFiniteLimitsAndCloudsThatWouldNotFitInMemory) {
  LineCloud c;
  c.name = "huge";
  c.segments = {{Vec3(0, 0, 0), Vec3(1e6, 0, 0)}};  // 1,000 km: raw units taken for metres
  EXPECT_THROW(split_long_segments(c, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  try {
    split_long_segments(c, 0.05);
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("huge"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("limit"), std::string::npos) << e.what();
  }
}

// Merged line maps (one line per stretch of edge) against per-view fragments (several overlapping lines).
TEST(SegmentSplit, OverlappedLongFractionTellsMergedMapsFromFragmentClouds) {
  LineCloud c;
  c.segments = {{Vec3(0, 0, 0), Vec3(4, 0, 0)}, {Vec3(4, 0, 0), Vec3(8, 0, 0)},    // consecutive, not overlapping
                {Vec3(0, 2, 0), Vec3(4, 2, 0)}, {Vec3(1, 2.05, 0), Vec3(5, 2.05, 0)},  // overlapping, 5 cm apart
                {Vec3(0, 4, 0), Vec3(4, 4, 0)}, {Vec3(0, 4, 0), Vec3(4, 4.5, 1)},     // crossing at 10 degrees
                {Vec3(0, 6, 0), Vec3(4, 6, 0)}, {Vec3(0, 6.3, 0), Vec3(4, 6.3, 0)},   // parallel, 30 cm apart
                {Vec3(0, 8, 0), Vec3(0, 8, 1)}};                                      // short: not counted
  // Long: 8 of 9; overlapped: the two of the overlapping pair only.
  EXPECT_NEAR(overlapped_long_fraction(c, 1.5), 2.0 / 8.0, 1e-12);
  EXPECT_EQ(overlapped_long_fraction(c, 10.0), 1.0);  // no segment that long
}

}  // namespace
}  // namespace lc2wf

// Line support of junction pairs and the pair screen built on it (dataset/selection/pair_support.h).
#include "dataset/selection/pair_support.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace lc2wf {
namespace {

constexpr double kRadius = 0.35, kAngle = 20.0;

double support_of(const std::vector<Segment3>& segments, const Vec3& u, const Vec3& v) {
  return SegmentSupport(segments).support(u, v, kRadius, kAngle);
}

JunctionPair pair(const Vec3& u, const Vec3& v, int i, int j) { return {u, v, i, j, -1, false}; }

TEST(PairSupport, CoveredShareOfThePairsLength) {
  const Vec3 u{0, 0, 0}, v{4, 0, 0};
  EXPECT_DOUBLE_EQ(support_of({}, u, v), 0.0);
  EXPECT_NEAR(support_of({{{1, 0.1, 0}, {3, 0.1, 0}}}, u, v), 0.5, 1e-12);
  // Reversed direction and the other orientation of the pair count the same.
  EXPECT_NEAR(support_of({{{3, 0, 0.2}, {1, 0, 0.2}}}, v, u), 0.5, 1e-12);
  // Overlaps count once; parts beyond the junctions do not count.
  EXPECT_NEAR(support_of({{{-2, 0, 0}, {1, 0, 0}}, {{0.5, 0, 0}, {1.5, 0, 0}}, {{3.5, 0, 0}, {9, 0, 0}}}, u, v), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(support_of({{{-1, 0, 0}, {5, 0, 0}}}, u, v), 1.0);
}

TEST(PairSupport, SegmentsTooFarOrAtAnAngleDoNotCount) {
  const Vec3 u{0, 0, 0}, v{4, 0, 0};
  EXPECT_DOUBLE_EQ(support_of({{{1, 0.4, 0}, {3, 0.4, 0}}}, u, v), 0.0);       // parallel, 0.4 m away
  EXPECT_DOUBLE_EQ(support_of({{{1, 0, 0}, {3, 0, 0.5}}}, u, v), 0.0);         // one endpoint 0.5 m away
  EXPECT_DOUBLE_EQ(support_of({{{1, -0.3, 0}, {2, 0.3, 0}}}, u, v), 0.0);      // 31 degrees
  EXPECT_NEAR(support_of({{{1, -0.15, 0}, {2, 0.15, 0}}}, u, v), 0.25, 1e-12);  // 16.7 degrees
  // Degenerate and non-finite segments are skipped, never counted.
  const double nan = std::nan("");
  EXPECT_DOUBLE_EQ(support_of({{{1, 0, 0}, {1, 0, 0}}, {{nan, 0, 0}, {2, 0, 0}}}, u, v), 0.0);
  // A pair of one point is fully supported: there is nothing to check.
  EXPECT_DOUBLE_EQ(support_of({}, u, u), 1.0);
}

TEST(PairSupport, ScreenKeepsSupportedAndShortPairsInOrder) {
  const std::vector<Segment3> segments{{{0, 0, 0}, {4, 0, 0}}};
  const std::vector<JunctionPair> pairs{pair({0, 0, 0}, {4, 0, 0}, 0, 1),   // on the segment
                                        pair({0, 0, 0}, {0, 4, 0}, 0, 2),   // no segment along it
                                        pair({0, 0, 0}, {0, 0.5, 0}, 0, 3), // short: kept
                                        pair({4, 0, 0}, {0, 4, 0}, 1, 2)};
  PairSupportOptions o;
  EXPECT_EQ(supported_pairs(pairs, segments, o).size(), pairs.size());  // off: every pair
  o.min_support = 0.5;
  const std::vector<JunctionPair> kept = supported_pairs(pairs, segments, o);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].j, 1);
  EXPECT_EQ(kept[1].j, 3);
  o.keep_shorter_than_m = 0.0;
  EXPECT_EQ(supported_pairs(pairs, segments, o).size(), 1u);
  EXPECT_TRUE(supported_pairs(pairs, {}, o).empty());
}

TEST(PairSupport, CheckNamesTheBadField) {
  auto message = [](PairSupportOptions o) {
    try {
      o.Check();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  PairSupportOptions o;
  EXPECT_EQ(message(o), "");
  o.min_support = 1.5;
  EXPECT_NE(message(o).find("min_support"), std::string::npos);
  o = {};
  o.radius_m = 0;
  EXPECT_NE(message(o).find("radius_m"), std::string::npos);
  o = {};
  o.max_angle_deg = 95;
  EXPECT_NE(message(o).find("max_angle_deg"), std::string::npos);
  o = {};
  o.keep_shorter_than_m = -1;
  EXPECT_NE(message(o).find("keep_shorter_than_m"), std::string::npos);
  o = {};
  o.min_support = std::nan("");
  EXPECT_NE(message(o).find("min_support"), std::string::npos);
}

}  // namespace
}  // namespace lc2wf

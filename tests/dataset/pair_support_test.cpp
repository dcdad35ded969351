// Line support of junction pairs and the pair screen built on it (dataset/selection/pair_support.h).
#include "dataset/selection/pair_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace lc2wf {
namespace {

constexpr double kRadius = 0.35, kAngle = 20.0;

double support_of(const std::vector<Segment3>& segments, const Vec3& u, const Vec3& v) {
  return SegmentSupport(segments).support(u, v, kRadius, kAngle);
}

JunctionPair pair(const Vec3& u, const Vec3& v, int i, int j) { return {u, v, i, j, -1, false}; }

// The share as the rule states it, every segment looked at: what the x-ordered scan must reproduce exactly.
double support_by_every_segment(const std::vector<Segment3>& segments, const Vec3& u, const Vec3& v) {
  const double length = (v - u).norm();
  const Vec3 d = (v - u) / length;
  std::vector<std::pair<double, double>> spans;
  for (const Segment3& s : segments) {
    const double l = s.length();
    const Vec3 dir = (s.b - s.a) / l;
    const Vec3 a = s.a - u, b = a + dir * l;  // the same arithmetic, so the same bits
    if (std::abs(dir.dot(d)) < std::cos(kAngle * M_PI / 180.0)) continue;
    const double ta = a.dot(d), tb = b.dot(d);
    if ((a - ta * d).squaredNorm() > kRadius * kRadius || (b - tb * d).squaredNorm() > kRadius * kRadius) continue;
    const double lo = std::max(std::min(ta, tb), 0.0), hi = std::min(std::max(ta, tb), length);
    if (hi > lo) spans.emplace_back(lo, hi);
  }
  std::sort(spans.begin(), spans.end());
  double covered = 0, lo = 0, hi = -1;
  for (const auto& [s0, s1] : spans) {
    if (s0 > hi) {
      if (hi > lo) covered += hi - lo;
      lo = s0, hi = s1;
    } else {
      hi = std::max(hi, s1);
    }
  }
  if (hi > lo) covered += hi - lo;
  return std::min(1.0, covered / length);
}

TEST(PairSupport, OrderedScanFindsWhatEverySegmentGives) {
  // Clutter of short and long segments (some spanning the whole cloud in x) along a grid of lines.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-30, 30), jitter(-0.3, 0.3), len(0.2, 25);
  std::vector<Segment3> segments;
  for (int k = 0; k < 3000; ++k) {
    const Vec3 a(coord(rng), std::round(coord(rng) / 5) * 5 + jitter(rng), std::round(coord(rng) / 10) * 3);
    const Vec3 dir = (k % 3 == 0) ? Vec3(1, 0.02 * jitter(rng), 0) : (k % 3 == 1) ? Vec3(0.01, 1, 0) : Vec3(0.02, 0, 1);
    segments.push_back({a, a + len(rng) * dir.normalized()});
  }
  const SegmentSupport support(segments);
  for (int q = 0; q < 300; ++q) {
    const Vec3 u(coord(rng), std::round(coord(rng) / 5) * 5, std::round(coord(rng) / 10) * 3);
    const Vec3 v = u + Vec3(q % 2 ? len(rng) : 0.1, q % 2 ? 0.05 : len(rng), 0);
    ASSERT_EQ(support.support(u, v, kRadius, kAngle), support_by_every_segment(segments, u, v)) << "query " << q;
  }
}

TEST(PairSupport, AnchoredQueriesGiveTheSameSharesBitForBit) {
  // The pair cap's ranking asks a junction's nearby segments about many directions from it: the anchored
  // form (every segment screened, no x window) must give SegmentSupport's share exactly, at borderline
  // angles too. Segments on a grid, some 20 degrees off (the angle limit) and some beyond it.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-3, 3), jitter(-0.4, 0.4), len(0.05, 4), turn(-0.4, 0.4);
  std::vector<Segment3> segments;
  for (int k = 0; k < 400; ++k) {
    const Vec3 a(coord(rng), std::round(coord(rng)) + jitter(rng), std::round(coord(rng)) * 0.5);
    const double t = (k % 5 == 0) ? (k % 2 ? 1 : -1) * kAngle * M_PI / 180.0 : turn(rng);
    const Vec3 dir = (k % 2 == 0) ? Vec3(std::cos(t), std::sin(t), 0) : Vec3(0, std::cos(t), std::sin(t));
    segments.push_back({a, a + len(rng) * dir});
  }
  const SegmentSupport support(segments);
  int supported = 0;
  for (int j = 0; j < 20; ++j) {
    const Vec3 u(std::round(coord(rng)), std::round(coord(rng)), 0);
    const AnchoredSegmentSupport anchored(segments, u);
    for (int q = 0; q < 50; ++q) {
      const double t = turn(rng), l = len(rng);
      const Vec3 v = u + l * ((q % 2 == 0) ? Vec3(std::cos(t), std::sin(t), 0) : Vec3(0, std::cos(t), std::sin(t)));
      const double expected = support.support(u, v, kRadius, kAngle);
      ASSERT_EQ(anchored.support(v, kRadius, kAngle), expected) << "junction " << j << ", query " << q;
      supported += expected > 0;
    }
  }
  EXPECT_GT(supported, 200) << "the queries should mostly meet segments";
}

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

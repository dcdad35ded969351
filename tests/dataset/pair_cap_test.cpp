// The pair cap before the edge model (dataset/selection/pair_cap.h): untouched below the cap, and above it the
// pairs with line support near their junctions, per-junction and total limits, deterministic.
#include "dataset/selection/pair_cap.h"

#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "core/rng.h"

namespace lc2wf {
namespace {

// Every pair (i < j) of the points, in lexicographic order as inference pairs them.
std::vector<JunctionPair> every_pair(const std::vector<Vec3>& points) {
  std::vector<JunctionPair> pairs;
  for (int i = 0; i < static_cast<int>(points.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(points.size()); ++j) pairs.push_back({points[i], points[j], i, j, -1, false});
  return pairs;
}

bool same_pairs(const std::vector<JunctionPair>& a, const std::vector<JunctionPair>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].i != b[k].i || a[k].j != b[k].j) return false;
  return true;
}

// A 10 x 6 m box's 8 corners and 12 edges (as segments), and `clutter` random points and short random
// segments around it.
struct Scene {
  std::vector<Vec3> points;
  std::vector<Segment3> segments;
};

Scene box_with_clutter(int clutter_points, int clutter_segments, uint64_t seed) {
  Scene s;
  for (int k = 0; k < 8; ++k) s.points.push_back(Vec3(k & 1 ? 10 : 0, k & 2 ? 6 : 0, k & 4 ? 5 : 0));
  for (int a = 0; a < 8; ++a)
    for (int b = a + 1; b < 8; ++b)
      if (__builtin_popcount(a ^ b) == 1) s.segments.push_back({s.points[a], s.points[b]});
  Rng rng(seed);
  auto uniform = [&](double lo, double hi) { return rng.next_uniform(lo, hi); };
  for (int k = 0; k < clutter_points; ++k) s.points.push_back(Vec3(uniform(-20, 30), uniform(-20, 26), uniform(0, 12)));
  for (int k = 0; k < clutter_segments; ++k) {
    const Vec3 a(uniform(-20, 30), uniform(-20, 26), uniform(0, 12));
    s.segments.push_back({a, a + Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1))});
  }
  return s;
}

TEST(PairCap, PairsAtOrBelowTheCapPassUnchanged) {
  const Scene s = box_with_clutter(43, 500, 3);  // 51 junctions: 1,275 pairs, just below the default cap
  const std::vector<JunctionPair> pairs = every_pair(s.points);
  ASSERT_EQ(pairs.size(), 1275u);
  ASSERT_LE(pairs.size(), static_cast<size_t>(PairCapOptions{}.max_pairs));
  EXPECT_TRUE(same_pairs(capped_pairs(pairs, s.segments, PairCapOptions{}), pairs));
  PairCapOptions off;
  off.max_pairs = 0;
  const Scene big = box_with_clutter(300, 100, 4);
  const std::vector<JunctionPair> many = every_pair(big.points);
  EXPECT_TRUE(same_pairs(capped_pairs(many, big.segments, off), many));
}

TEST(PairCap, AboveTheCapTheSupportedEdgesStayWithinBothLimits) {
  const Scene s = box_with_clutter(400, 3000, 5);  // 408 junctions: 83,028 pairs
  const std::vector<JunctionPair> pairs = every_pair(s.points);
  PairCapOptions cap;
  cap.max_pairs = 1500;
  cap.max_pairs_per_junction = 10;
  const std::vector<JunctionPair> kept = capped_pairs(pairs, s.segments, cap);
  EXPECT_LE(kept.size(), 1500u);
  EXPECT_GT(kept.size(), 1000u);
  std::map<int, int> per_junction;
  for (const JunctionPair& p : kept) ++per_junction[p.i], ++per_junction[p.j];
  for (const auto& [junction, count] : per_junction) EXPECT_LE(count, 10) << junction;
  // The box's 12 edges have segments along them at both ends: all kept, whatever the clutter.
  int box_edges = 0;
  for (const JunctionPair& p : kept)
    if (p.i < 8 && p.j < 8 && __builtin_popcount(p.i ^ p.j) == 1) ++box_edges;
  EXPECT_EQ(box_edges, 12);
  // Kept pairs keep their input order, and the same input gives the same pairs.
  for (size_t k = 1; k < kept.size(); ++k) EXPECT_TRUE(kept[k - 1].i < kept[k].i || (kept[k - 1].i == kept[k].i && kept[k - 1].j < kept[k].j));
  EXPECT_TRUE(same_pairs(capped_pairs(pairs, s.segments, cap), kept));
  // The ranking spread over threads gives the same ranks, so the same pairs.
  EXPECT_EQ(pair_end_support(pairs, s.segments, PairSupportOptions{}, cap.end_length_m, 3),
            pair_end_support(pairs, s.segments, PairSupportOptions{}, cap.end_length_m, 1));
  EXPECT_TRUE(same_pairs(capped_pairs(pairs, s.segments, cap, PairSupportOptions{}, 3), kept));
}

TEST(PairCap, CloseDetectionsOfOneJunctionRankFirst) {
  // Pairs shorter than keep_shorter_than_m carry the identical-pair evidence: kept before supported edges.
  std::vector<Vec3> points = {{0, 0, 0}, {0, 0, 0.6}, {5, 0, 0}, {0, 5, 0}};
  const std::vector<Segment3> segments = {{{0, 0, 0}, {5, 0, 0}}, {{0, 0, 0}, {0, 5, 0}}};
  PairCapOptions cap;
  cap.max_pairs = 1;
  const std::vector<JunctionPair> kept = capped_pairs(every_pair(points), segments, cap);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].i, 0);
  EXPECT_EQ(kept[0].j, 1);
  cap.max_pairs = 3;
  const std::vector<JunctionPair> three = capped_pairs(every_pair(points), segments, cap);
  ASSERT_EQ(three.size(), 3u);  // the close pair, then the two supported edges from junction 0
  EXPECT_EQ(three[1].i, 0);
  EXPECT_EQ(three[1].j, 2);
  EXPECT_EQ(three[2].j, 3);
}

TEST(PairCap, EndSupportIsTheCoveredShareNearBothJunctions) {
  const std::vector<Segment3> segments = {{{0, 0, 0}, {1, 0, 0}}};  // covers half of u's first 2 m only
  const std::vector<JunctionPair> pairs = {{{0, 0, 0}, {10, 0, 0}, 0, 1, -1, false}};
  const std::vector<double> rank = pair_end_support(pairs, segments, PairSupportOptions{}, 2.0);
  ASSERT_EQ(rank.size(), 1u);
  EXPECT_NEAR(rank[0], 0.25, 1e-12);
  // Junctions without an index (-1) are measured where they are, each on its own.
  const std::vector<JunctionPair> loose = {{{0, 0, 0}, {10, 0, 0}, -1, -1, -1, false}, {{10, 0, 0}, {0, 0, 0}, -1, -1, -1, false}};
  EXPECT_EQ(pair_end_support(loose, segments, PairSupportOptions{}, 2.0, 2), std::vector<double>({rank[0], rank[0]}));
}

TEST(PairCap, BadOptionsNameTheField) {
  PairCapOptions o;
  o.max_pairs = -1;
  try {
    o.Check();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("PairCapOptions.max_pairs"), std::string::npos);
  }
  o = {};
  o.end_length_m = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

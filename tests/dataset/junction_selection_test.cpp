// The one junction-selection rule: point NMS, the confidence or top-k cut, refinement, and the pairs.
#include "dataset/selection/junction_selection.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "dataset/sampling/pair_sampling.h"

namespace lc2wf {
namespace {

// Candidates regressed onto their own sample points (offset 0), so no offset limit screens them.
PredictedJunctions candidates(std::vector<Vec3> p, std::vector<double> c) {
  std::vector<double> offsets(p.size(), 0.0);
  return {std::move(p), std::move(c), std::move(offsets)};
}

// The release's radius, cut and candidates (the distances below are chosen around them), the sound NMS
// rule, no refinement.
JunctionSelectionOptions no_refine() {
  JunctionSelectionOptions o = JunctionSelectionOptions::release();
  o.nms = PointNmsRule::kGreedy;
  return o;
}

TEST(PointNms, GreedyAndSuppressorDifferOnChains) {
  const std::vector<Vec3> p{{0, 0, 0}, {0.2, 0, 0}, {0.4, 0, 0}};
  const std::vector<double> c{.9, .8, .7};
  EXPECT_EQ(point_nms(p, c, 0.25, PointNmsRule::kGreedy), (std::vector<int>{0, 2}));
  EXPECT_EQ(point_nms(p, c, 0.25, PointNmsRule::kSuppressor), (std::vector<int>{0}));
}

TEST(PointNms, OrderTiesAndStrictRadius) {
  // Output in descending confidence; equal confidences: lower index wins; distance == radius is not close.
  const std::vector<Vec3> p{{5, 0, 0}, {0, 0, 0}, {0.1, 0, 0}, {5.25, 0, 0}};
  const std::vector<double> c{.5, .7, .7, .6};
  for (auto rule : {PointNmsRule::kGreedy, PointNmsRule::kSuppressor})
    EXPECT_EQ(point_nms(p, c, 0.25, rule), (std::vector<int>{1, 3, 0}));
  EXPECT_TRUE(point_nms({}, {}, 0.25, PointNmsRule::kSuppressor).empty());
  EXPECT_THROW(point_nms(p, {1.0}, 0.25, PointNmsRule::kGreedy), std::invalid_argument);
}

TEST(PointNms, SuppressorTieBehindADroppedPoint) {
  // H drops J (same confidence as K); J never gets to drop K, so K survives under both rules.
  const std::vector<Vec3> p{{0, 0, 0}, {0.2, 0, 0}, {0.4, 0, 0}};
  const std::vector<double> c{.9, .8, .8};
  EXPECT_EQ(point_nms(p, c, 0.25, PointNmsRule::kSuppressor), (std::vector<int>{0, 2}));
  EXPECT_EQ(point_nms(p, c, 0.25, PointNmsRule::kGreedy), (std::vector<int>{0, 2}));
}

TEST(PointNms, GreedyEqualScoresInsideTheRadius) {
  // Equal scores: the lower index comes first in the order and suppresses the other.
  EXPECT_EQ(point_nms({Vec3(0, 0, 0), Vec3(0.1, 0, 0)}, {0.5, 0.5}, 0.25, PointNmsRule::kGreedy), (std::vector<int>{0}));
  EXPECT_EQ(point_nms({Vec3(0, 0, 0), Vec3(0.1, 0, 0)}, {0.5, 0.5}, 0.0, PointNmsRule::kGreedy), (std::vector<int>{0, 1}));
}

TEST(SelectJunctions, NmsThenStrictConfidenceThreshold) {
  const auto c = candidates({{0, 0, 0}, {0.1, 0, 0}, {3, 0, 0}, {6, 0, 0}}, {.86, .99, .85, .9});
  const JunctionSelection s = select_junctions(c, {}, no_refine());
  EXPECT_EQ(s.kept, (std::vector<int>{1, 3}));  // 0 suppressed by 1; 2 is not > 0.85
  EXPECT_EQ(s.confidences, (std::vector<double>{.99, .9}));
  EXPECT_TRUE(s.notes.empty());
}

TEST(SelectJunctions, TopKCutIgnoresConfidence) {
  const auto c = candidates({{0, 0, 0}, {0.1, 0, 0}, {3, 0, 0}, {6, 0, 0}, {9, 0, 0}}, {.3, .2, .1, .05, .01});
  JunctionSelectionOptions o = no_refine();
  o.top_k = 3;
  const JunctionSelection s = select_junctions(c, {}, o, SelectionCut::kTopK);
  EXPECT_EQ(s.kept, (std::vector<int>{0, 2, 3}));  // 1 suppressed by 0, then the 3 most confident
}

// max_offset_m: far-regressed candidates take no part, not even as suppressors in the NMS; without offsets
// the limit is an error, never a silent no-op.
TEST(SelectJunctions, MaxOffsetDropsFarVotesBeforeTheNms) {
  PredictedJunctions c = candidates({{0, 0, 0}, {0.1, 0, 0}, {3, 0, 0}, {6, 0, 0}}, {.99, .9, .95, .97});
  c.offset_m = {2.5, 0.3, 0.9, 1.2};
  JunctionSelectionOptions o = no_refine();
  EXPECT_EQ(select_junctions(c, {}, o).kept, (std::vector<int>{0, 3, 2}));  // 1 suppressed by the far vote 0
  o.max_offset_m = 1.0;
  EXPECT_EQ(select_junctions(c, {}, o).kept, (std::vector<int>{2, 1}));  // 0 and 3 ignored, so 1 survives
  o.max_offset_m = 0.2;
  const JunctionSelection none = select_junctions(c, {}, o);
  EXPECT_TRUE(none.kept.empty());
  EXPECT_FALSE(none.notes.empty());
  c.offset_m.clear();
  EXPECT_THROW(select_junctions(c, {}, o), std::invalid_argument);
  o.max_offset_m = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  // Users write <= 0 for "every candidate" (flags, configs); NaN stays an error.
  EXPECT_TRUE(std::isinf(JunctionSelectionOptions::offset_limit(0)));
  EXPECT_TRUE(std::isinf(JunctionSelectionOptions::offset_limit(-1)));
  EXPECT_DOUBLE_EQ(JunctionSelectionOptions::offset_limit(0.75), 0.75);
  o.max_offset_m = JunctionSelectionOptions::offset_limit(std::nan(""));
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

TEST(SelectJunctions, NmsRunsOnRegressedPositionsBeforeRefinement) {
  // Two candidates 0.3 m apart (both kept by the 0.25 m NMS) snap onto the same corner: refinement comes
  // after the NMS in every caller, so both stay (the edge model's "identical" class handles them).
  const Vec3 C(0, 0, 0);
  std::vector<Segment3> corner;
  for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}) corner.push_back({C, C + 2.0 * d});
  const auto c = candidates({C + Vec3(0.15, 0, 0), C + Vec3(-0.15, 0, 0)}, {.95, .9});
  JunctionSelectionOptions sound;  // with refinement
  sound.nms_radius_m = 0.25;
  const JunctionSelection s = select_junctions(c, corner, sound);
  ASSERT_EQ(s.kept, (std::vector<int>{0, 1}));
  EXPECT_LT((s.positions[0] - C).norm(), 0.02);
  EXPECT_LT((s.positions[1] - C).norm(), 0.02);
  const JunctionSelection release = select_junctions(c, corner, JunctionSelectionOptions::release());
  EXPECT_EQ(release.positions[0], c.positions[0]);  // the release keeps the regressed positions
}

TEST(SelectJunctions, EmptyAndSingleJunctionGiveNotesNotCrashes) {
  const JunctionSelection none = select_junctions({}, {}, JunctionSelectionOptions{});
  EXPECT_TRUE(none.kept.empty());
  EXPECT_FALSE(none.notes.empty());
  JunctionSelectionOptions without_lines;  // no segment shows a corner or stands over one: the checks would take both
  without_lines.corner.radius_m = 0;
  without_lines.footing.radius_m = 0;
  const JunctionSelection one = select_junctions(candidates({{0, 0, 0}, {1, 0, 0}}, {.95, .01}), {}, without_lines);
  EXPECT_EQ(one.kept.size(), 1u);
  EXPECT_FALSE(one.notes.empty());
  EXPECT_TRUE(selection_pairs(one, nullptr, 0.35).empty());
  EXPECT_THROW(select_junctions(candidates({{0, 0, 0}}, {}), {}, JunctionSelectionOptions{}), std::invalid_argument);
  EXPECT_THROW(select_junctions(candidates({{0, 0, NAN}}, {.9}), {}, JunctionSelectionOptions{}), std::invalid_argument);
}

TEST(SelectJunctions, OptionsAreChecked) {
  JunctionSelectionOptions o;
  o.nms_radius_m = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.min_confidence = 1.5;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.top_k = 1;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  EXPECT_EQ(JunctionSelectionOptions::release().nms, PointNmsRule::kSuppressor);
  EXPECT_EQ(JunctionSelectionOptions::release().refine.radius, 0.0);
  EXPECT_GT(JunctionSelectionOptions{}.refine.radius, 0.0);
}

TEST(SelectionPairs, LexicographicAndLabelledAgainstTheGt) {
  Wireframe gt;
  gt.junctions = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(4, 0, 0)};
  gt.edges = {{0, 1}, {1, 2}};
  const JunctionSelection s =
      select_junctions(candidates({{0, 0, 0}, {2.1, 0, 0}, {4, 0, 0}, {50, 0, 0}}, {.99, .98, .97, .96}), {}, no_refine());
  const auto pairs = selection_pairs(s, &gt, 0.35);
  ASSERT_EQ(pairs.size(), 6u);
  std::vector<std::array<int, 3>> got;
  for (const auto& p : pairs) got.push_back({p.i, p.j, p.label});
  EXPECT_EQ(got, (std::vector<std::array<int, 3>>{{0, 1, kPairConnected},
                                                  {0, 2, kPairDistance2},
                                                  {0, 3, kPairFalsePositive},
                                                  {1, 2, kPairConnected},
                                                  {1, 3, kPairFalsePositive},
                                                  {2, 3, kPairFalsePositive}}));
  EXPECT_EQ(selection_pairs(s, nullptr, 0.35)[0].label, -1);
}

}  // namespace
}  // namespace lc2wf

// Corner evidence: lines of two directions ending at a junction, and the selection that keeps only such
// junctions.
#include "dataset/selection/corner_evidence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dataset/selection/junction_selection.h"

namespace lc2wf {
namespace {

CornerEvidenceOptions at(double radius_m) {
  CornerEvidenceOptions o;
  o.radius_m = radius_m;
  return o;
}

TEST(CornerEvidence, TwoDirectionsEndingNearbyMakeACorner) {
  // An L of two walls' edges meeting at the origin, and a long edge along x at y = 5.
  const std::vector<Segment3> lines = {{{0, 0, 0}, {3, 0, 0}}, {{0.1, 0, 0}, {0.1, 0, 2}},  // the L (one end 0.1 m off)
                                       {{-4, 5, 0}, {-0.05, 5, 0}}, {{0.05, 5, 0}, {4, 5, 0}}};  // a gap in one edge
  const std::vector<char> shown = corner_evidence({{0, 0, 0}, {0, 5, 0}, {1.5, 0, 0}, {9, 9, 9}}, lines, at(0.3));
  EXPECT_EQ(shown, (std::vector<char>{1, 0, 0, 0}))
      << "the L's corner; not the middle of an edge where two pieces end, nor a point inside a line, nor empty space";
}

TEST(CornerEvidence, TheAngleDecidesInEitherOrientation) {
  auto corner = [](double turn_deg) {
    const double t = turn_deg * M_PI / 180.0;
    // The second segment points away from the junction or towards it: its orientation does not matter.
    const std::vector<Segment3> lines = {{{0, 0, 0}, {2, 0, 0}}, {{2 * std::cos(t), 2 * std::sin(t), 0}, {0, 0, 0}}};
    return corner_evidence({{0, 0, 0}}, lines, at(0.3))[0];
  };
  EXPECT_FALSE(corner(10));
  EXPECT_TRUE(corner(25));
  EXPECT_TRUE(corner(90));
  EXPECT_FALSE(corner(175)) << "a straight line through the junction, its two pieces pointing apart";
  EXPECT_TRUE(corner(150));
}

TEST(CornerEvidence, ACrowdOfEndsIsThinnedNotComparedPairByPair) {
  // 200,000 segments ending at the origin (2e10 pairs if all were compared): one direction only, then every
  // 50th of them turned by 90 degrees.
  std::vector<Segment3> bundle;
  for (int k = 0; k < 200000; ++k) bundle.push_back({{0, 0, 0}, {1, 1e-7 * k, 0}});
  EXPECT_FALSE(corner_evidence({{0, 0, 0}}, bundle, at(0.3))[0]);
  for (size_t k = 0; k < bundle.size(); k += 50) bundle[k].b = {0, 0, 1};
  EXPECT_TRUE(corner_evidence({{0, 0, 0}}, bundle, at(0.3))[0]);
}

TEST(CornerEvidence, OffKeepsEveryJunctionAndBadOptionsNameTheField) {
  EXPECT_EQ(corner_evidence({{0, 0, 0}, {1, 1, 1}}, {}, CornerEvidenceOptions{}), (std::vector<char>{1, 1}));
  EXPECT_TRUE(corner_evidence({}, {{{0, 0, 0}, {1, 0, 0}}}, at(0.3)).empty());
  // Degenerate and non-finite segments carry no direction and are never counted.
  const double nan = std::nan("");
  EXPECT_EQ(corner_evidence({{0, 0, 0}}, {{{0, 0, 0}, {0, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {0, nan, 1}}}, at(0.3)),
            std::vector<char>{0});
  CornerEvidenceOptions bad = at(-1);
  try {
    bad.Check();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("CornerEvidenceOptions.radius_m"), std::string::npos) << e.what();
  }
  bad = at(0.3);
  bad.min_angle_deg = 0;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

TEST(SelectJunctions, OnlyJunctionsWithCornerEvidenceArePaired) {
  // A box corner (three edges) and a vote in the middle of one of its edges.
  std::vector<Segment3> lines;
  for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}) lines.push_back({Vec3::Zero(), 4.0 * d});
  const PredictedJunctions c{{{0.05, 0, 0}, {2, 0, 0}}, {0.9, 0.95}, {0.0, 0.0}};
  JunctionSelectionOptions o;
  const JunctionSelection s = select_junctions(c, lines, o);
  EXPECT_EQ(s.kept, (std::vector<int>{0}));
  EXPECT_LT(s.positions[0].norm(), 0.02) << "refined onto the corner before the check";
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("corner check"), std::string::npos) << s.notes[0];
  o.corner.radius_m = 0;
  o.footing.radius_m = 0;  // the vote lies on the ground with nothing above it: the footing check would take it
  EXPECT_EQ(select_junctions(c, lines, o).kept, (std::vector<int>{1, 0}));  // by confidence
  EXPECT_EQ(JunctionSelectionOptions::release().corner.radius_m, 0.0) << "the release pairs every junction";
}

}  // namespace
}  // namespace lc2wf

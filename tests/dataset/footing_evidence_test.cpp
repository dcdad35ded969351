// Footing evidence: a junction on the ground is kept where the building stands over it, and the selection that
// drops the others.
#include "dataset/selection/footing_evidence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dataset/selection/junction_selection.h"

namespace lc2wf {
namespace {

FootingEvidenceOptions at(double radius_m) {
  FootingEvidenceOptions o;
  o.radius_m = radius_m;
  return o;
}

// A 6 x 4 box of height h on the ground (z = 0), its edges as segments, with a shadow's outline on the ground
// beside it: the shadow's far corners (8, 1, 0) and (8, 5, 0) have nothing above them.
std::vector<Segment3> box_with_shadow(double h) {
  std::vector<Segment3> s;
  const Vec3 c[4] = {{0, 0, 0}, {6, 0, 0}, {6, 4, 0}, {0, 4, 0}};
  for (int k = 0; k < 4; ++k) {
    const Vec3 up(0, 0, h);
    s.push_back({c[k], c[(k + 1) % 4]});
    s.push_back({c[k] + up, c[(k + 1) % 4] + up});
    s.push_back({c[k], c[k] + up});
  }
  s.push_back({{6, 0, 0}, {8, 1, 0}}), s.push_back({{8, 1, 0}, {8, 5, 0}}), s.push_back({{8, 5, 0}, {6, 4, 0}});
  return s;
}

TEST(FootingEvidence, AGroundCornerNeedsTheBuildingAboveIt) {
  const std::vector<Vec3> junctions = {{0, 0, 0}, {6, 4, 0.1}, {8, 1, 0}, {8, 5, 0.05}, {0, 0, 3}, {8, 1, 2}};
  EXPECT_EQ(footing_evidence(junctions, box_with_shadow(3), at(0.5)), (std::vector<char>{1, 1, 0, 0, 1, 1}))
      << "the box's foot corners stay, the shadow's go; junctions above the ground band are not tested";
}

TEST(FootingEvidence, NoHeightIsAssumed) {
  // A 1.5 m shed and a 60 m tower: their walls stand on their corners at either size; a 0.5 m kerb does not.
  for (double h : {1.5, 60.0}) EXPECT_EQ(footing_evidence({{0, 0, 0}, {8, 1, 0}}, box_with_shadow(h), at(0.5)), (std::vector<char>{1, 0})) << h;
  EXPECT_EQ(footing_evidence({{0, 0, 0}}, box_with_shadow(0.5), at(0.5)), std::vector<char>{0}) << "nothing rises 1 m";
}

TEST(FootingEvidence, TheGroundIsTheFramesNotTheLowestLines) {
  // Outliers 6 m below the ground (a tenth of the lines) leave the ground where the frame puts it.
  std::vector<Segment3> lines = box_with_shadow(3);
  for (int k = 0; k < 2; ++k) lines.push_back({{k + 2.0, 2, -6}, {k + 2.5, 2, -6}});
  EXPECT_EQ(footing_evidence({{0, 0, 0}, {8, 1, 0}, {2, 2, -6}}, lines, at(0.5)), (std::vector<char>{1, 0, 0}))
      << "a junction below the ground with nothing over it goes too";
  // A frame whose ground is elsewhere says so.
  for (Segment3& s : lines) s.a.z() += 100, s.b.z() += 100;
  FootingEvidenceOptions lifted = at(0.5);
  EXPECT_EQ(footing_evidence({{8, 1, 100}}, lines, lifted), std::vector<char>{1}) << "nothing on the ground at 0";
  lifted.ground_z_m = 100;
  EXPECT_EQ(footing_evidence({{0, 0, 100}, {8, 1, 100}}, lines, lifted), (std::vector<char>{1, 0}));
}

TEST(FootingEvidence, TheRadiusIsHorizontal) {
  // The wall's top corner overhangs by 0.4 m (eaves): it still stands over the foot at 0.5 m, not at 0.3 m.
  const std::vector<Segment3> lines = {{{0, 0, 0}, {5, 0, 0}}, {{0, 0, 0}, {0, 5, 0}}, {{-0.4, 0, 4}, {5, 0, 4}}, {{9, 9, 0}, {9, 9, 0.2}}};
  EXPECT_EQ(footing_evidence({{0, 0, 0}}, lines, at(0.5)), std::vector<char>{1});
  EXPECT_EQ(footing_evidence({{0, 0, 0}}, lines, at(0.3)), std::vector<char>{0});
}

TEST(FootingEvidence, OffKeepsEveryJunctionAndBadOptionsNameTheField) {
  EXPECT_EQ(footing_evidence({{8, 1, 0}}, box_with_shadow(3), FootingEvidenceOptions{}), std::vector<char>{1});
  EXPECT_EQ(footing_evidence({{8, 1, 0}}, {}, at(0.5)), std::vector<char>{0}) << "no segments: nothing stands over it";
  EXPECT_TRUE(footing_evidence({}, box_with_shadow(3), at(0.5)).empty());
  const double nan = std::nan("");
  EXPECT_EQ(footing_evidence({{8, 1, 0}}, {{{8, 1, nan}, {8, 1, 0.2}}, {{0, 0, 0}, {1, 0, 0}}}, at(0.5)), std::vector<char>{0})
      << "a non-finite end does not stand over the junction";
  EXPECT_EQ(footing_evidence({{8, 1, 0}}, {{{8, 1, nan}, {8, 1, 5}}, {{0, 0, 0}, {1, 0, 0}}}, at(0.5)), std::vector<char>{1})
      << "the segment's finite end does";
  for (auto [field, bad] : std::vector<std::pair<std::string, FootingEvidenceOptions>>{
           {"radius_m", at(-1)}, {"min_rise_m", [] { auto o = at(0.5); o.min_rise_m = 0; return o; }()},
           {"ground_band_m", [nan] { auto o = at(0.5); o.ground_band_m = nan; return o; }()},
           {"ground_z_m", [nan] { auto o = at(0.5); o.ground_z_m = nan; return o; }()}}) {
    try {
      bad.Check();
      ADD_FAILURE() << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("FootingEvidenceOptions." + field), std::string::npos) << e.what();
    }
  }
}

TEST(SelectJunctions, GroundJunctionsWithNothingAboveAreNotPaired) {
  const std::vector<Segment3> lines = box_with_shadow(3);
  const PredictedJunctions c{{{0, 0, 0}, {8, 1, 0}, {6, 0, 3}}, {0.9, 0.95, 0.8}, {0.0, 0.0, 0.0}};
  JunctionSelectionOptions o;
  EXPECT_EQ(select_junctions(c, lines, o).kept, (std::vector<int>{0, 2})) << "the shadow's corner passes the corner check only";
  o.footing.radius_m = 0;
  EXPECT_EQ(select_junctions(c, lines, o).kept, (std::vector<int>{1, 0, 2}));
  EXPECT_EQ(JunctionSelectionOptions::release().footing.radius_m, 0.0) << "the release pairs every junction";
  const PredictedJunctions lone{{{8, 1, 0}, {8, 5, 0}}, {0.9, 0.9}, {0.0, 0.0}};
  const JunctionSelection s = select_junctions(lone, lines, JunctionSelectionOptions{});
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("footing check"), std::string::npos) << s.notes[0];
}

}  // namespace
}  // namespace lc2wf

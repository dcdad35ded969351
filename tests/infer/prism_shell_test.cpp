// The prism rule of the face finder (infer/surfaces/prism_shell.h): walls extruded from the roof outline
// down to the ground level, the ground as the footprint, hidden faces dropped, parts and failures;
// surfaces_from_wireframe closing predicted-like wireframes with it; faces from the confident edges first.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "infer/surfaces/polygon_geometry.h"
#include "infer/surfaces/prism_shell.h"
#include "infer/surfaces/shell_checks.h"
#include "infer/surfaces/wireframe_surfaces.h"
#include "tests/infer/surface_fixtures.h"

namespace lc2wf {
namespace {

// A surface model of the given faces (junction ids of the fixture), all labelled roof.
SurfaceModel sheet(const testing::FixtureBuilding& b, const std::vector<std::vector<int>>& faces) {
  SurfaceModel m;
  m.vertices = b.wireframe.junctions;
  for (const auto& f : faces) m.faces.push_back({f, SurfaceLabel::kRoof});
  return m;
}

int faces_with(const SurfaceModel& m, SurfaceLabel label, size_t corners) {
  int n = 0;
  for (const SurfaceFace& f : m.faces) n += f.label == label && f.ring.size() == corners;
  return n;
}

void expect_vertical_walls(const SurfaceModel& m) {
  for (const SurfaceFace& f : m.faces)
    if (f.label == SurfaceLabel::kWall) EXPECT_NEAR(newell_normal(m.polygon(f)).normalized().z(), 0, 0.02);  // within ~1 degree
}

TEST(PrismShell, AHippedRoofBecomesAClosedPrism) {
  const auto b = testing::hipped_building();
  std::string why;
  const auto m = extrude_roof_to_ground(sheet(b, {{4, 5, 9, 8}, {6, 7, 8, 9}, {4, 8, 7}, {5, 6, 9}}), PrismOptions{}, &why);
  ASSERT_TRUE(m) << why;
  EXPECT_TRUE(check_shell(*m, 0.01).valid_solid());
  EXPECT_EQ(m->count(SurfaceLabel::kRoof), 4);
  EXPECT_EQ(faces_with(*m, SurfaceLabel::kWall, 4), 4);
  EXPECT_EQ(faces_with(*m, SurfaceLabel::kGround, 4), 1);
  EXPECT_EQ(m->vertices.size(), 10u);  // 6 roof corners + 4 on the ground
  expect_vertical_walls(*m);
}

TEST(PrismShell, GableEndsAreOneWallThroughTheRidgeEnd) {
  // The outline runs eave - ridge end - eave in one vertical plane: one pentagon, not two quads.
  const auto b = testing::gabled_building();
  const auto m = extrude_roof_to_ground(sheet(b, {{4, 5, 9, 8}, {7, 6, 9, 8}}), PrismOptions{});
  ASSERT_TRUE(m);
  EXPECT_TRUE(check_shell(*m, 0.01).valid_solid());
  EXPECT_EQ(faces_with(*m, SurfaceLabel::kWall, 5), 2);
  EXPECT_EQ(faces_with(*m, SurfaceLabel::kWall, 4), 2);
}

TEST(PrismShell, AStepBetweenRoofLevelsStandsOnTheWallBelowIt) {
  // Low roof, the wall between the levels and the tall roof: the outline has vertical sides at the step,
  // the long walls are the fixture's hexagons (ground, low eave, step, tall eave).
  const auto b = testing::two_level_building();
  const auto m = extrude_roof_to_ground(sheet(b, {{4, 5, 7, 6}, {6, 7, 10, 9}, {8, 9, 10, 11}}), PrismOptions{});
  ASSERT_TRUE(m);
  EXPECT_TRUE(check_shell(*m, 0.01).valid_solid());
  EXPECT_EQ(faces_with(*m, SurfaceLabel::kWall, 6), 2);
  EXPECT_EQ(faces_with(*m, SurfaceLabel::kWall, 4), 2);
  EXPECT_EQ(m->faces.size(), 3u + 4u + 1u);
}

TEST(PrismShell, AFaceUnderTheRoofIsDropped) {
  // The eave level's horizontal cycle lies under the hipped roof: no roof, not kept.
  const auto b = testing::hipped_building();
  const auto m = extrude_roof_to_ground(sheet(b, {{4, 5, 9, 8}, {6, 7, 8, 9}, {4, 8, 7}, {5, 6, 9}, {4, 5, 6, 7}}), PrismOptions{});
  ASSERT_TRUE(m);
  EXPECT_TRUE(check_shell(*m, 0.01).valid_solid());
  EXPECT_EQ(m->count(SurfaceLabel::kRoof), 4);
}

TEST(PrismShell, SeparatePartsArePrismsEachAndCanBeLeftOut) {
  testing::FixtureBuilding b;
  b.wireframe.junctions = {{0, 0, 3}, {2, 0, 3}, {2, 2, 3}, {0, 2, 3}, {10, 0, 4}, {13, 0, 4}, {13, 3, 4}, {10, 3, 4}};
  const SurfaceModel two = sheet(b, {{0, 1, 2, 3}, {4, 5, 6, 7}});
  int parts = 0;
  const auto m = extrude_roof_to_ground(two, PrismOptions{}, nullptr, &parts);
  ASSERT_TRUE(m);
  EXPECT_EQ(parts, 2);
  EXPECT_TRUE(check_shell(*m, 0.01).valid_solid());
  EXPECT_EQ(m->count(SurfaceLabel::kGround), 2);
  PrismOptions first_only;
  first_only.parts = {true, false};  // the larger part (the second square) comes first
  const auto one = extrude_roof_to_ground(two, first_only);
  ASSERT_TRUE(one);
  EXPECT_EQ(one->faces.size(), 6u);
  for (const Vec3& p : one->vertices) EXPECT_GE(p.x(), 10);
}

TEST(PrismShell, PrismsTouchingAlongAWallCornerAreNoValidSolidTogether) {
  // Two flat roofs meeting at one corner: each part's prism has its own ground vertex under the shared corner,
  // at one place, so the vertical side there bounds four faces (what a file with rounded coordinates shows).
  testing::FixtureBuilding b;
  b.wireframe.junctions = {{0, 0, 3}, {2, 0, 3}, {2, 2, 3}, {0, 2, 3}, {4, 2, 3}, {4, 4, 3}, {2, 4, 3}};
  const auto both = extrude_roof_to_ground(sheet(b, {{0, 1, 2, 3}, {2, 4, 5, 6}}), PrismOptions{});
  ASSERT_TRUE(both);
  const ShellCheck c = check_shell(*both, 0.01);
  EXPECT_EQ(c.overused_edges, 1);
  EXPECT_FALSE(c.valid_solid());
  // surfaces_from_wireframe keeps the parts that stay valid: one prism of 6 faces.
  Wireframe w = b.wireframe;
  w.junctions.push_back({0, 0, 0});
  w.edges = {{0, 1}, {1, 2}, {2, 3}, {0, 3}, {2, 4}, {4, 5}, {5, 6}, {2, 6}, {0, 7}};
  const SurfaceModel m = surfaces_from_wireframe(w);
  EXPECT_TRUE(m.closed_solid());
  EXPECT_TRUE(check_shell(m, 0.01).valid_solid());
  EXPECT_EQ(m.faces.size(), 6u);
}

TEST(PrismShell, SheetsThatAreNoFootprintSayWhy) {
  std::string why;
  // A side in three faces: two roof facets and a wall standing on their ridge.
  testing::FixtureBuilding fan;
  fan.wireframe.junctions = {{0, 0, 3}, {4, 0, 3}, {2, 3, 2}, {2, -3, 2}, {2, 0, 6}};
  EXPECT_FALSE(extrude_roof_to_ground(sheet(fan, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}), PrismOptions{}, &why));
  EXPECT_NE(why.find("three or more"), std::string::npos) << why;
  // Every face reaches the ground level: nothing to extrude.
  EXPECT_FALSE(extrude_roof_to_ground(sheet(testing::box_building(), {{0, 1, 5, 4}}), PrismOptions{}, &why));
  EXPECT_NE(why.find("no roof face"), std::string::npos) << why;
  EXPECT_FALSE(extrude_roof_to_ground(SurfaceModel{}, PrismOptions{}, &why));
}

TEST(PrismShell, JunctionsThatAreNotFiniteOrMissingGiveNoFacesWithAReason) {
  Wireframe w = testing::hipped_building().wireframe;
  w.junctions[6].z() = std::nan("");
  const SurfaceModel m = surfaces_from_wireframe(w);
  EXPECT_EQ(m.status, ShellStatus::kNoFaces);
  ASSERT_FALSE(m.reasons.empty());
  EXPECT_NE(m.reasons[0].find("not finite"), std::string::npos) << m.reasons[0];
  Wireframe dangling = testing::hipped_building().wireframe;
  dangling.edges.push_back({3, 42});
  EXPECT_EQ(surfaces_from_wireframe(dangling).status, ShellStatus::kNoFaces);
}

TEST(PrismShell, ARoofWithAHoleIsNoSheet) {
  // Four flat frames around a missing middle square: the outline is two loops.
  testing::FixtureBuilding b;
  b.wireframe.junctions = {{0, 0, 3}, {3, 0, 3}, {3, 3, 3}, {0, 3, 3}, {1, 1, 3}, {2, 1, 3}, {2, 2, 3}, {1, 2, 3}};
  std::string why;
  EXPECT_FALSE(extrude_roof_to_ground(sheet(b, {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}), PrismOptions{}, &why));
  EXPECT_NE(why.find("not one loop"), std::string::npos) << why;
}

// A hipped house as a model predicts it: junctions off by a few centimetres, the walls' vertical edges at two
// corners only, no ground edges, and a spurious horizontal cycle at the eaves.
Wireframe predicted_like_hipped_house(unsigned seed) {
  Wireframe w = testing::hipped_building().wireframe;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 0.03);
  for (Vec3& p : w.junctions) p += Vec3(noise(rng), noise(rng), noise(rng));
  w.edges = {{4, 5}, {5, 6}, {6, 7}, {4, 7}, {4, 8}, {7, 8}, {5, 9}, {6, 9}, {8, 9}, {0, 4}, {2, 6}, {4, 6}};
  return w;
}

TEST(PrismShell, NoisyPredictedLikeWireframesBecomeTheHouseNotALidOnTheRoof) {
  // Without the prism rule the roof closes with the eaves' cycle as a lid (5 "roof" faces, no ground);
  // with it, the vertical edges give the ground level and the house stands on it.
  int houses = 0, houses_without = 0;
  SurfaceOptions without;
  without.prism_walls = false;
  const auto is_house = [](const SurfaceModel& m) {
    return m.closed_solid() && m.count(SurfaceLabel::kRoof) == 4 && m.count(SurfaceLabel::kGround) == 1;
  };
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const Wireframe w = predicted_like_hipped_house(seed);
    const SurfaceModel m = surfaces_from_wireframe(w);
    houses += is_house(m);
    houses_without += is_house(surfaces_from_wireframe(w, without));
    EXPECT_TRUE(check_shell(m, 0.01).valid_solid()) << "seed " << seed;
    expect_vertical_walls(m);
  }
  EXPECT_EQ(houses, 10);
  EXPECT_EQ(houses_without, 0);
}

// The box with unconfident edges from its roof corners to a tip above the roof: a pyramid roof they would make.
Wireframe box_with_tip(std::vector<double>* scores) {
  Wireframe w = testing::box_building().wireframe;
  w.junctions.push_back({2, 1.5, 3.5});
  scores->assign(w.edges.size(), 0.99);
  for (int corner : {4, 5, 6, 7}) w.edges.push_back({corner, 8}), scores->push_back(0.4);
  return w;
}

TEST(ScoredSurfaces, FacesComeFromTheConfidentEdgesWhenTheyClose) {
  std::vector<double> scores;
  const Wireframe w = box_with_tip(&scores);
  const SurfaceModel m = surfaces_from_wireframe(w, scores);
  EXPECT_TRUE(m.closed_solid());
  EXPECT_EQ(m.faces.size(), 6u);
  for (const Vec3& p : m.vertices) EXPECT_LT(p.z(), 3) << "the tip of the unconfident edges is in a face";
  // Unscored, the pyramid is the roof.
  const SurfaceModel unscored = surfaces_from_wireframe(w);
  EXPECT_TRUE(std::any_of(unscored.vertices.begin(), unscored.vertices.end(), [](const Vec3& p) { return p.z() > 3; }));
  // min_edge_score 0 uses every edge, as unscored.
  SurfaceOptions every;
  every.min_edge_score = 0;
  EXPECT_EQ(surfaces_from_wireframe(w, scores, every).faces.size(), unscored.faces.size());
}

TEST(ScoredSurfaces, AllEdgesWhenTheConfidentOnesDoNotClose) {
  // The walls' vertical edges unconfident: roof and ground alone are no solid, all the edges are.
  Wireframe w = testing::box_building().wireframe;
  std::vector<double> scores(w.edges.size(), 0.99);
  for (size_t e = 8; e < 12; ++e) scores[e] = 0.5;  // {0,4}, {1,5}, {2,6}, {3,7}
  const SurfaceModel m = surfaces_from_wireframe(w, scores);
  EXPECT_TRUE(m.closed_solid());
  EXPECT_EQ(m.faces.size(), 6u);
  EXPECT_THROW(surfaces_from_wireframe(w, std::vector<double>(3, 1.0)), std::invalid_argument);
  SurfaceOptions bad;
  bad.min_edge_score = 1.5;
  EXPECT_THROW(surfaces_from_wireframe(w, scores, bad), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

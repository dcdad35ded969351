// The roof-kind rule on meshes whose kind a person knows: boxes (flat, two levels), a shed, gabled and
// hipped houses from the synthetic generator, a cross-gabled L and a roof of flat and pitched parts.
#include <gtest/gtest.h>

#include "dataset/geometry/roof_kind.h"
#include "dataset/synthetic/synthetic_building.h"

namespace lc2wf {
namespace {

// A closed box x in [x0, x1], y in [0, w], z in [0, h]: ground, four walls, a flat roof.
void add_box(PolyMesh& m, double x0, double x1, double w, double h) {
  const int b = static_cast<int>(m.vertices.size());
  for (double z : {0.0, h}) {
    m.vertices.push_back({x0, 0, z});
    m.vertices.push_back({x1, 0, z});
    m.vertices.push_back({x1, w, z});
    m.vertices.push_back({x0, w, z});
  }
  m.faces.push_back({b + 3, b + 2, b + 1, b + 0});
  m.labels.push_back(FaceLabel::Base);
  m.faces.push_back({b + 4, b + 5, b + 6, b + 7});
  m.labels.push_back(FaceLabel::Roof);
  for (int i = 0; i < 4; ++i) {
    m.faces.push_back({b + i, b + (i + 1) % 4, b + 4 + (i + 1) % 4, b + 4 + i});
    m.labels.push_back(FaceLabel::Wall);
  }
}

TEST(RoofKind, BoxIsFlat) {
  PolyMesh m;
  add_box(m, 0, 10, 8, 12);
  EXPECT_EQ(classify_roof(m), RoofKind::Flat);
}

TEST(RoofKind, TwoBoxesOfDifferentHeightAreFlatAtSeveralLevels) {
  PolyMesh m;
  add_box(m, 0, 10, 8, 12);
  add_box(m, 10, 18, 8, 6);
  EXPECT_EQ(classify_roof(m), RoofKind::FlatMulti);
}

TEST(RoofKind, OnePitchedPlaneIsAShed) {
  // A box whose roof rises from 3 m at y = 0 to 5 m at y = 8.
  PolyMesh m;
  m.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 8, 0}, {0, 8, 0}, {0, 0, 3}, {10, 0, 3}, {10, 8, 5}, {0, 8, 5}};
  m.faces = {{3, 2, 1, 0}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  m.labels = {FaceLabel::Base, FaceLabel::Roof, FaceLabel::Wall, FaceLabel::Wall, FaceLabel::Wall, FaceLabel::Wall};
  EXPECT_EQ(classify_roof(m), RoofKind::Shed);
}

TEST(RoofKind, GableAndHipEndsOfTheSyntheticHouses) {
  RectBuildingSpec gable;
  gable.west = gable.east = RoofEnd::Gable;
  EXPECT_EQ(classify_roof(make_rect_mesh(gable)), RoofKind::Gabled);
  EXPECT_EQ(classify_roof(make_rect_mesh(RectBuildingSpec{})), RoofKind::Hipped);
}

TEST(RoofKind, FlatAndPitchedPartsMix) {
  RectBuildingSpec gable;
  gable.west = gable.east = RoofEnd::Gable;
  PolyMesh m = make_rect_mesh(gable);
  add_box(m, 30, 45, 9, 4);  // a flat annex of about the house's roof area, apart from it
  EXPECT_EQ(classify_roof(m), RoofKind::Mixed);
}

TEST(RoofKind, NoRoofFaceIsUnknownAndNamesAreStable) {
  PolyMesh m;
  add_box(m, 0, 1, 1, 1);
  for (auto& l : m.labels) l = FaceLabel::Wall;
  EXPECT_EQ(classify_roof(m), RoofKind::Unknown);
  EXPECT_EQ(roof_kind_name(RoofKind::FlatMulti), "flat-multi");
  EXPECT_EQ(roof_kind_name(RoofKind::Gabled), "gabled");
  RoofKindOptions bad;
  bad.flat_share_mixed = 0.95;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

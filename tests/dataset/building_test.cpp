#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "dataset/geometry/building.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/mesh_io.h"
#include "dataset/synthetic/synthetic_building.h"
#include "test_util.h"

using ::testing::HasSubstr;
using ::testing::Not;

namespace lc2wf {
namespace {

// A 10 x 8 raw-unit box with a gable roof (ridge along x), written as a polyshape.
const char* kGableBox =
    "# Number of verts: 10\n"
    "# Number of faces: 9\n"
    "0,0,60\n200,0,60\n200,160,60\n0,160,60\n0,80,120\n200,80,120\n"
    "0,0,0\n200,0,0\n200,160,0\n0,160,0\n"
    "1,2,6,5,1\n2,3,6,1\n3,4,5,6,1\n4,1,5,1\n"
    "1,7,8,2,3\n2,8,9,3,3\n3,9,10,4,3\n4,10,7,1,3\n"
    "10,9,8,7,2\n";

PolyMesh parse(const std::string& text, const std::string& name = "mem.polyshape") {
  std::istringstream in(text);
  return parse_polyshape(in, name);
}

TEST(Polyshape, ParsesGableBox) {
  const PolyMesh m = parse(kGableBox);
  ASSERT_EQ(m.vertices.size(), 10u);
  ASSERT_EQ(m.faces.size(), 9u);
  EXPECT_EQ(m.faces[1], (std::vector<int>{1, 2, 5}));
  EXPECT_EQ(m.labels[0], FaceLabel::Roof);
  EXPECT_EQ(m.labels[4], FaceLabel::Wall);
  EXPECT_EQ(m.labels[8], FaceLabel::Base);
  EXPECT_DOUBLE_EQ(m.vertices[4].z(), 120.0);
}

TEST(Polyshape, GableBoxWireframeAndUnits) {
  const Building b = make_building("gable", parse(kGableBox));
  // 6 roof edges... 4 eaves + ridge + 4 gable rakes = 9 roof, 4 vertical, 4 base = 17.
  EXPECT_EQ(b.wireframe.junctions.size(), 10u);
  EXPECT_EQ(b.wireframe.edges.size(), 17u);
  // Footprint 200 x 160 raw = 10 x 8 m, centred; eaves 3 m, ridge 6 m.
  EXPECT_NEAR(b.mesh.vertices[0].x(), -5.0, 1e-12);
  EXPECT_NEAR(b.mesh.vertices[0].y(), -4.0, 1e-12);
  EXPECT_NEAR(b.mesh.vertices[0].z(), 3.0, 1e-12);
  EXPECT_NEAR(b.mesh.vertices[4].z(), 6.0, 1e-12);
  EXPECT_NEAR((b.units.origin_raw - Vec3(100, 80, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((b.units.to_raw(b.mesh.vertices[5]) - Vec3(200, 80, 120)).norm(), 0.0, 1e-9);
  std::set<std::pair<int, int>> edges;
  for (const auto& e : b.wireframe.edges) {
    EXPECT_LT(e[0], e[1]);
    edges.insert({e[0], e[1]});
  }
  EXPECT_EQ(edges.size(), 17u);
  EXPECT_TRUE(edges.count({4, 5}));  // ridge
  EXPECT_TRUE(edges.count({0, 6}));  // vertical corner
  EXPECT_TRUE(b.issues.warnings.empty());
}

TEST(Polyshape, DropCoplanarEdgesRemovesGableWallSeams) {
  BuildingOptions opt;
  opt.wireframe.drop_coplanar_edges = true;
  const Building b = make_building("gable", parse(kGableBox), opt);
  // The two gable triangles are coplanar with the walls below them: seams (1,2) and (3,0) are dropped.
  EXPECT_EQ(b.wireframe.edges.size(), 15u);
}

TEST(Polyshape, BadInputsNameFileAndLine) {
  auto expect_error = [](const std::string& text, const std::string& needle) {
    try {
      parse(text, "bad.polyshape");
      FAIL() << "no error for: " << needle;
    } catch (const DataError& e) {
      EXPECT_THAT(std::string(e.what()), HasSubstr(needle)) << e.what();
      EXPECT_THAT(std::string(e.what()), HasSubstr("bad.polyshape")) << e.what();
    }
  };
  expect_error("", "bad.polyshape:1: unexpected end of file");
  expect_error("# Number of verts: 3\n", "bad.polyshape:2: unexpected end of file");
  expect_error("# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0,0\n", "bad.polyshape:5: unexpected end of file");
  expect_error("# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0,nan\n0,1,0\n1,2,3,1\n", ":4: vertex coordinate 'nan'");
  expect_error("# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0,inf\n0,1,0\n1,2,3,1\n", ":4: vertex coordinate 'inf'");
  expect_error("# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0\n0,1,0\n1,2,3,1\n", ":4: vertex line needs 3");
  expect_error("# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0,0\n0,1,0\n1,2,4,1\n", ":6: vertex id 4 out of range");
  expect_error("# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0,0\n0,1,0\n1,2,0,1\n", ":6: vertex id 0 out of range");
  expect_error("# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0,0\n0,1,0\n1,2,3,7\n", ":6: face label '7'");
  expect_error("# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0,0\n0,1,0\n1,2,1\n", ":6: face line needs at least 3");
  expect_error("# Number of verts: x\n", ":1: bad count");
  expect_error("hello\n", ":1: expected header");
  expect_error("# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0,0\n0,1,0\n1,2,3,1\nextra\n", ":7: unexpected content");
}

TEST(Polyshape, MissingFileIsNamed) {
  try {
    read_polyshape("/nonexistent/x.polyshape");
    FAIL();
  } catch (const DataError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("/nonexistent/x.polyshape: cannot open"));
  }
}

TEST(Building, MergesDuplicateVerticesAndDropsDegenerateFaces) {
  // Two near-coincident corners (0.0002 m apart after /20) on a box; the wall between them collapses.
  std::string text =
      "# Number of verts: 10\n# Number of faces: 8\n"
      "0,0,60\n200,0,60\n200,160,60\n0,160,60\n0,160.004,60\n"
      "0,0,0\n200,0,0\n200,160,0\n0,160,0\n0,160.004,0\n"
      "1,2,3,4,5,1\n"
      "1,6,7,2,3\n2,7,8,3,3\n3,8,9,4,3\n4,9,10,5,3\n5,10,6,1,3\n"
      "10,9,8,7,6,2\n"
      "1,2,7,3\n";
  const Building b = make_building("dup", parse(text));
  EXPECT_EQ(b.issues.merged_vertices, 2);
  EXPECT_EQ(b.issues.dropped_faces, 1);
  EXPECT_EQ(b.mesh.vertices.size(), 8u);
  ASSERT_FALSE(b.issues.warnings.empty());
  EXPECT_THAT(b.issues.warnings[0], HasSubstr("dup: merged 2 duplicate vertices"));
  for (const auto& f : b.mesh.faces) {
    for (int id : f) EXPECT_LT(id, 8);
  }
}

TEST(Building, NonPlanarPolicy) {
  std::string text = kGableBox;
  text.replace(text.find("0,80,120"), 8, "0,80,140");  // lifts one ridge end out of both roof planes' fit
  EXPECT_TRUE(make_building("np", parse(text)).issues.non_planar);
  BuildingOptions skip;
  skip.non_planar = NonPlanarPolicy::Skip;
  EXPECT_THROW(make_building("np", parse(text), skip), BuildingSkipped);
  EXPECT_FALSE(make_building("ok", parse(kGableBox), skip).issues.non_planar);
}

TEST(Building, OptionsCheckNamesField) {
  BuildingOptions o;
  o.raw_per_metre = 0;
  try {
    o.Check();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("raw_per_metre"));
  }
}

TEST(Building, FewerThanTwoVerticesIsAnError) {
  PolyMesh m;
  m.vertices = {Vec3(0, 0, 0)};
  m.faces = {{0, 0, 0}};
  EXPECT_THROW(make_building("tiny", m), DataError);
}

TEST(Obj, ReadsFacesLinesSlashesNegativeIdsAndYUp) {
  const auto dir = test::scratch_dir("obj");
  const auto path = dir / "a.obj";
  {
    std::ofstream f(path);
    f << "# comment\nmtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 1 2 3\nv 0 1 0\nvt 0 0\n"
         "f 1/1 2/1/1 3//1\nf -4 -2 -1\nl 2 4 1\ng grp\n";
  }
  const ObjData o = read_obj(path);
  ASSERT_EQ(o.mesh.vertices.size(), 4u);
  EXPECT_EQ(o.mesh.faces[0], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(o.mesh.faces[1], (std::vector<int>{0, 2, 3}));
  ASSERT_EQ(o.lines.size(), 2u);
  EXPECT_EQ(o.lines[0], (std::array<int, 2>{1, 3}));
  ObjReadOptions yup;
  yup.y_up = true;
  EXPECT_NEAR((read_obj(path, yup).mesh.vertices[2] - Vec3(1, -3, 2)).norm(), 0, 1e-12);
  const Wireframe w = read_obj_wireframe(path);
  // l: (1,3),(0,3); faces add (0,1),(1,2),(0,2),(2,3) -> 6 unique.
  EXPECT_EQ(w.edges.size(), 6u);
}

TEST(Obj, BadInputs) {
  auto expect_error = [](const std::string& text, const std::string& needle) {
    std::istringstream in(text);
    try {
      parse_obj(in, "bad.obj");
      FAIL() << needle;
    } catch (const DataError& e) {
      EXPECT_THAT(std::string(e.what()), HasSubstr(needle)) << e.what();
    }
  };
  expect_error("v 0 0\n", "bad.obj:1: 'v' needs 3");
  expect_error("v 0 0 nan\n", "bad.obj:1: vertex coordinate");
  expect_error("v 0 0 0\nv 1 0 0\nf 1 2 3\n", "bad.obj:3: vertex reference 3 out of range");
  expect_error("v 0 0 0\nf 1 1\n", "bad.obj:2: 'f' needs at least 3");
  expect_error("v 0 0 0\nv 0 0 1\nl 1 x\n", "bad.obj:3: vertex reference 'x'");
  expect_error("v 0 0 0\nl 1 1\n", "bad.obj:2: 'l' repeats a vertex");
}

TEST(Obj, WireframeRoundTripInRawUnits) {
  const Building b = make_rect_building("r", RectBuildingSpec{});
  const auto dir = test::scratch_dir("obj_rt");
  write_obj_wireframe(dir / "w.obj", b.wireframe, &b.units);
  const Wireframe raw = read_obj_wireframe(dir / "w.obj");
  ASSERT_EQ(raw.junctions.size(), b.wireframe.junctions.size());
  ASSERT_EQ(raw.edges, b.wireframe.edges);
  for (size_t i = 0; i < raw.junctions.size(); ++i) {
    EXPECT_NEAR((b.units.to_metres(raw.junctions[i]) - b.wireframe.junctions[i]).norm(), 0, 1e-6);
  }
  write_obj_mesh(dir / "m.obj", b.mesh);
  const ObjData m = read_obj(dir / "m.obj");
  EXPECT_EQ(m.mesh.faces, b.mesh.faces);
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    EXPECT_THAT(e.path().string(), Not(HasSubstr(".tmp."))) << "temporary file left behind";
  }
}

TEST(Synthetic, RectAndLWireframes) {
  RectBuildingSpec hip;
  const Building r = make_rect_building("hip", hip);
  EXPECT_EQ(r.wireframe.junctions.size(), 10u);
  EXPECT_EQ(r.wireframe.edges.size(), 17u);
  EXPECT_EQ(r.mesh.faces.size(), 9u);
  EXPECT_LT(r.issues.max_planarity_dev_m, 1e-9);
  EXPECT_EQ(r.issues.non_manifold_edges, 0);
  // Ridge height: eave + tan(37 deg) * 4.5 m.
  EXPECT_NEAR(r.mesh.vertices[4].z(), 3.75 + std::tan(37.0 * M_PI / 180) * 4.5, 1e-9);

  LBuildingSpec l;
  l.end_x = RoofEnd::Gable;
  const Building lb = make_l_building("l", l);
  EXPECT_EQ(lb.wireframe.junctions.size(), 15u);
  EXPECT_EQ(lb.wireframe.edges.size(), 26u);
  EXPECT_EQ(lb.mesh.faces.size(), 13u);
  EXPECT_LT(lb.issues.max_planarity_dev_m, 1e-9);
  EXPECT_EQ(lb.issues.non_manifold_edges, 0);
  // Footprint centred: bounding box of x and y symmetric about 0.
  double xmin = 1e9, xmax = -1e9;
  for (const auto& v : lb.mesh.vertices) {
    xmin = std::min(xmin, v.x());
    xmax = std::max(xmax, v.x());
  }
  EXPECT_NEAR(xmin + xmax, 0.0, 1e-9);
  EXPECT_NEAR(xmax - xmin, 16.0, 1e-9);
}

TEST(Synthetic, RandomBuildingsAreDeterministicAndValid) {
  for (uint64_t seed = 0; seed < 40; ++seed) {
    const Building a = make_random_building(seed, "x");
    const Building b = make_random_building(seed, "x");
    ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
    for (size_t i = 0; i < a.mesh.vertices.size(); ++i) EXPECT_EQ(a.mesh.vertices[i], b.mesh.vertices[i]);
    EXPECT_LT(a.issues.max_planarity_dev_m, 1e-9) << seed;
    EXPECT_EQ(a.issues.non_manifold_edges, 0) << seed;
    EXPECT_TRUE(a.wireframe.edges.size() == 17u || a.wireframe.edges.size() == 26u) << seed;
  }
  EXPECT_NE(make_random_building(1, "x").mesh.vertices[0], make_random_building(2, "x").mesh.vertices[0]);
  EXPECT_THROW(make_rect_building("x", RectBuildingSpec{8, 9}), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

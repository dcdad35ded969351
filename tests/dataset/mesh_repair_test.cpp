// The shared repair steps at the generator's tolerances (1 um) and the LoD2 clean-up's (mm to cm): the same
// code, only the options differ; and the one closure check with and without rims of dropped inner rings.
#include "dataset/geometry/mesh_repair.h"

#include <gtest/gtest.h>

#include "dataset/geometry/closed_mesh.h"

namespace lc2wf {
namespace {

// Ids of a ring of points welded at `tol` (one welder for all rings).
std::vector<Ring> weld_all(const std::vector<std::vector<Vec3>>& rings, double tol, std::vector<Vec3>& vertices) {
  VertexWelder w(tol);
  std::vector<Ring> faces;
  for (const auto& r : rings)
    if (Ring f = w.add_ring(r); !f.empty()) faces.push_back(std::move(f));
  vertices = w.take_vertices();
  return faces;
}

TEST(MeshRepair, WeldsAtTheCallersTolerance) {
  const std::vector<std::vector<Vec3>> rings = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                                                {{1.003, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}};
  std::vector<Vec3> v;
  EXPECT_EQ(unique_edges(weld_all(rings, 0.005, v)).size(), 7u);  // surveyed: the 3 mm gap closes
  EXPECT_EQ(v.size(), 6u);
  EXPECT_EQ(unique_edges(weld_all(rings, 1e-6, v)).size(), 8u);   // exact: it stays
  // A ring of no area (thinner than the tolerance) is dropped, its points stay vertices.
  EXPECT_TRUE(weld_all({{{0, 0, 0}, {1, 0, 0}, {2, 0, 1e-7}}}, 1e-6, v).empty());
  EXPECT_EQ(v.size(), 3u);
}

TEST(MeshRepair, TJunctionsAndStraightVerticesAtTheCallersTolerance) {
  // A corner 5 mm beside another face's edge: a T at 1 cm, none at 1 um.
  const std::vector<Vec3> v = {{0, 0, 0}, {2, 0, 0}, {2, 0, 1}, {0, 0, 1}, {1, 0.005, 0}, {1, -1, 0}, {1.5, -1, 0}};
  std::vector<Ring> faces = {{0, 1, 2, 3}, {4, 5, 6}};
  std::vector<Ring> exact = faces;
  EXPECT_EQ(conform_t_junctions(v, exact, 1e-6), 0);
  EXPECT_EQ(conform_t_junctions(v, faces, 0.01), 1);
  EXPECT_EQ(faces[0], (Ring{0, 4, 1, 2, 3}));
  // A vertex 4 mm off a straight edge: removed at 1 cm, kept at 1 um; the face's index is reported.
  const std::vector<Vec3> w = {{0, 0, 0}, {1, 0.004, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  std::vector<Ring> square = {{0, 1, 2, 3, 4}};
  EXPECT_EQ(remove_collinear_vertices(w, square, 1e-6), 0);
  std::vector<int> kept;
  EXPECT_EQ(remove_collinear_vertices(w, square, 0.01, &kept), 1);
  EXPECT_EQ(square[0], (Ring{0, 2, 3, 4}));
  EXPECT_EQ(kept, std::vector<int>{0});
  std::vector<Vec3> u = w;
  drop_unused_vertices(u, square);
  EXPECT_EQ(u.size(), 4u);
  EXPECT_EQ(square[0], (Ring{0, 1, 2, 3}));
}

TEST(MeshRepair, OptionsAreChecked) {
  MeshRepairOptions o;
  EXPECT_NO_THROW(o.Check());
  o.collinear_m = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  ClosedMeshOptions c;
  c.on_face_tol = -1;
  EXPECT_THROW(c.Check(), std::invalid_argument);
}

TEST(ClosedMesh, OpenEdgesAndRimsOfDroppedInnerRings) {
  // A 10 x 10 x 3 box and, on its roof, a 2 x 2 x 1 box without a floor (it stood in the roof's opening).
  auto box = [](double x0, double y0, double x1, double y1, double z0, double z1, bool floor) {
    std::vector<PointFace> f = {{{{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}, FaceLabel::Roof},
                                {{{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}}},
                                {{{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}}},
                                {{{x1, y1, z0}, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}}},
                                {{{x0, y1, z0}, {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}}}};
    if (floor) f.push_back({{{x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0}}, FaceLabel::Base});
    return f;
  };
  const PolyMesh closed = mesh_from_faces(box(0, 0, 10, 10, 0, 3, true));
  EXPECT_TRUE(inspect_closed_mesh(closed).closed());
  std::vector<PointFace> faces = box(0, 0, 10, 10, 0, 3, true);
  for (PointFace& f : box(4, 4, 6, 6, 3, 4, false)) faces.push_back(std::move(f));
  const PolyMesh m = mesh_from_faces(faces);
  const ClosedMeshReport strict = inspect_closed_mesh(m);
  EXPECT_FALSE(strict.closed());
  EXPECT_EQ(strict.open_edges, 4);
  EXPECT_NEAR(strict.open_length, 8.0, 1e-12);
  ClosedMeshOptions rims;
  rims.on_face_tol = 0.03;
  const ClosedMeshReport lenient = inspect_closed_mesh(m, rims);
  EXPECT_EQ(lenient.open_edges, 0);
  EXPECT_EQ(lenient.edges_on_faces, 4);
  EXPECT_EQ(lenient.edges_not_shared_by_two, 4);
}

}  // namespace
}  // namespace lc2wf

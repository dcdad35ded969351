// Each step of the LoD2 clean-up on small hand-made meshes, then the whole chain.
#include "dataset/geometry/lod2_cleanup.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace lc2wf {
namespace {

CityPolygon poly(std::vector<Vec3> ring, CitySurface kind = CitySurface::kWall, int part = 0) {
  CityPolygon p;
  p.exterior = std::move(ring);
  p.kind = kind;
  p.part = part;
  return p;
}

// Outward quads of an axis-aligned box, with semantics.
std::vector<CityPolygon> box(double x0, double y0, double x1, double y1, double z0, double z1, int part = 0) {
  return {poly({{x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0}}, CitySurface::kGround, part),
          poly({{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}, CitySurface::kRoof, part),
          poly({{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}}, CitySurface::kWall, part),
          poly({{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}}, CitySurface::kWall, part),
          poly({{x1, y1, z0}, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}}, CitySurface::kWall, part),
          poly({{x0, y1, z0}, {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}}, CitySurface::kWall, part)};
}

int edge_count(const Lod2Mesh& m) {
  std::set<std::pair<int, int>> e;
  for (const auto& f : m.faces)
    for (size_t k = 0; k < f.size(); ++k) e.insert({std::min(f[k], f[(k + 1) % f.size()]), std::max(f[k], f[(k + 1) % f.size()])});
  return static_cast<int>(e.size());
}

Lod2Mesh mesh_of(std::vector<CityPolygon> polys, double tol = 0.005) { return weld_polygons(polys, tol); }

TEST(Lod2Cleanup, DropsInnerRings) {
  std::vector<CityPolygon> p = box(0, 0, 10, 6, 0, 3);
  p[1].interiors.push_back({{3, 2, 3}, {3, 4, 3}, {7, 4, 3}, {7, 2, 3}});
  EXPECT_EQ(drop_inner_rings(p), 1);
  for (const auto& q : p) EXPECT_TRUE(q.interiors.empty());
}

TEST(Lod2Cleanup, WeldsWithinToleranceAndDropsDegenerateFaces) {
  std::vector<CityPolygon> p = {poly({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}}),  // closing repeat
                                poly({{1.003, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1.004, 0}}),    // 3-4 mm from the first
                                poly({{5, 5, 5}, {6, 5, 5}, {7, 5, 5.001}}),                   // no area
                                poly({{0, 0, 0}, {0.002, 0, 0}, {0, 0.003, 0}})};               // collapses to one point
  Lod2CleanupReport r;
  const Lod2Mesh m = weld_polygons(p, 0.005, &r);
  ASSERT_EQ(m.faces.size(), 2u);
  EXPECT_EQ(m.faces[0].size(), 4u);
  EXPECT_EQ(edge_count(m), 7);  // two squares sharing one edge
  EXPECT_EQ(r.degenerate_faces_dropped, 2);
  // Nothing welds at 1 mm: two squares side by side (8 edges) and the small triangle (3).
  EXPECT_EQ(edge_count(weld_polygons(p, 0.001)), 11);
}

TEST(Lod2Cleanup, ClassifiesUnlabelledFacesByNormalAndHeight) {
  std::vector<CityPolygon> p = box(0, 0, 10, 6, 0, 3);
  for (auto& q : p) q.kind = CitySurface::kUnknown;
  Lod2Mesh m = mesh_of(p);
  Lod2CleanupOptions o;
  EXPECT_EQ(classify_unlabelled_faces(m, o), 6);
  const std::vector<CitySurface> want = {CitySurface::kGround, CitySurface::kRoof, CitySurface::kWall,
                                         CitySurface::kWall,   CitySurface::kWall, CitySurface::kWall};
  EXPECT_EQ(m.kinds, want);
  // Inward-facing faces (signed volume < 0) give the same labels.
  for (auto& q : p) std::reverse(q.exterior.begin(), q.exterior.end());
  Lod2Mesh flipped = mesh_of(p);
  classify_unlabelled_faces(flipped, o);
  EXPECT_EQ(flipped.kinds, want);
}

TEST(Lod2Cleanup, MergesTrianglesOfOnePlaneAndKeepsOtherPlanesApart) {
  // A gabled roof of 4 triangles (2 per plane) + a wall triangle under the same edge.
  std::vector<CityPolygon> p = {poly({{0, 0, 3}, {10, 0, 3}, {10, 3, 5}}, CitySurface::kRoof),
                                poly({{0, 0, 3}, {10, 3, 5}, {0, 3, 5}}, CitySurface::kRoof),
                                poly({{10, 6, 3}, {0, 6, 3}, {10, 3, 5}}, CitySurface::kRoof),
                                poly({{0, 6, 3}, {0, 3, 5}, {10, 3, 5}}, CitySurface::kRoof)};
  Lod2Mesh m = mesh_of(p);
  EXPECT_EQ(merge_coplanar_faces(m, {}), 2);
  ASSERT_EQ(m.faces.size(), 2u);
  EXPECT_EQ(m.faces[0].size(), 4u);
  EXPECT_EQ(m.faces[1].size(), 4u);
  EXPECT_EQ(edge_count(m), 7);  // the two diagonals are gone
}

TEST(Lod2Cleanup, DoesNotMergeAcrossKindsOrOppositeOrientations) {
  std::vector<CityPolygon> kinds = {poly({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, CitySurface::kRoof),
                                    poly({{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}, CitySurface::kWall)};
  Lod2Mesh m = mesh_of(kinds);
  EXPECT_EQ(merge_coplanar_faces(m, {}), 0);
  EXPECT_EQ(m.faces.size(), 2u);
  // The same square as two triangles walking the diagonal the same way: one of them is flipped.
  std::vector<CityPolygon> flipped = {poly({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}), poly({{0, 0, 0}, {0, 1, 0}, {1, 1, 0}})};
  Lod2Mesh f = mesh_of(flipped);
  EXPECT_EQ(merge_coplanar_faces(f, {}), 0);
}

TEST(Lod2Cleanup, MergesSlightlyNonPlanarPiecesButNotALowPitchRidge) {
  // 1 cm out of plane: merged. 5 degrees apart (a ridge): kept.
  std::vector<CityPolygon> near = {poly({{0, 0, 0}, {4, 0, 0}, {4, 4, 0.01}}, CitySurface::kRoof),
                                   poly({{0, 0, 0}, {4, 4, 0.01}, {0, 4, 0}}, CitySurface::kRoof)};
  Lod2Mesh m = mesh_of(near);
  EXPECT_EQ(merge_coplanar_faces(m, {}), 1);
  const double rise = 4 * std::tan(5 * M_PI / 180);
  std::vector<CityPolygon> ridge = {poly({{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}}, CitySurface::kRoof),
                                    poly({{0, 4, 0}, {4, 4, 0}, {4, 8, rise}, {0, 8, rise}}, CitySurface::kRoof)};
  Lod2Mesh r = mesh_of(ridge);
  EXPECT_EQ(merge_coplanar_faces(r, {}), 0);
}

TEST(Lod2Cleanup, MergedRingAroundAHoleKeepsTheOutline) {
  // Four quads framing a 2 x 2 opening in a 6 x 6 roof: one face, the opening dropped like an inner ring.
  std::vector<CityPolygon> p = {poly({{0, 0, 0}, {6, 0, 0}, {4, 2, 0}, {2, 2, 0}}, CitySurface::kRoof),
                                poly({{6, 0, 0}, {6, 6, 0}, {4, 4, 0}, {4, 2, 0}}, CitySurface::kRoof),
                                poly({{6, 6, 0}, {0, 6, 0}, {2, 4, 0}, {4, 4, 0}}, CitySurface::kRoof),
                                poly({{0, 6, 0}, {0, 0, 0}, {2, 2, 0}, {2, 4, 0}}, CitySurface::kRoof)};
  Lod2Mesh m = mesh_of(p);
  EXPECT_EQ(merge_coplanar_faces(m, {}), 3);
  ASSERT_EQ(m.faces.size(), 1u);
  EXPECT_EQ(m.faces[0].size(), 4u);
}

TEST(Lod2Cleanup, RemovesCoincidentFacePairsAndDuplicates) {
  std::vector<CityPolygon> p = {poly({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}),   // a shared wall, part 1
                                poly({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}),   // the same, part 2, opposite
                                poly({{5, 0, 0}, {6, 0, 0}, {6, 0, 1}}),              // a duplicate pair
                                poly({{6, 0, 0}, {6, 0, 1}, {5, 0, 0}})};             // same direction, rotated
  Lod2Mesh m = mesh_of(p);
  EXPECT_EQ(remove_coincident_faces(m), 3);
  ASSERT_EQ(m.faces.size(), 1u);
  EXPECT_EQ(m.faces[0].size(), 3u);
}

TEST(Lod2Cleanup, InsertsVerticesLyingOnAnotherFacesEdge) {
  // B's corner (1, 0, 0) lies on A's bottom edge; (0.004, 0, 0) is a near-duplicate of A's corner, not a T.
  std::vector<CityPolygon> p = {poly({{0, 0, 0}, {2, 0, 0}, {2, 0, 1}, {0, 0, 1}}),
                                poly({{1, 0, 0}, {1, -1, 0}, {1.5, -1, 0}}), poly({{0.009, 0, 0}, {0.009, -1, 0}, {-1, -1, 0}})};
  Lod2Mesh m = weld_polygons(p, 0.001);
  EXPECT_EQ(conform_t_junctions(m.vertices, m.faces, 0.01), 1);
  EXPECT_EQ(m.faces[0].size(), 5u);
  EXPECT_EQ(m.vertices[m.faces[0][1]], Vec3(1, 0, 0));
}

TEST(Lod2Cleanup, RemovesDegreeTwoVerticesOnAStraightLineOnly) {
  // A square with a vertex in the middle of its bottom edge (removed) and one 5 cm off its top edge (kept).
  std::vector<CityPolygon> p = {poly({{0, 0, 0}, {1, 0.004, 0}, {2, 0, 0}, {2, 2, 0}, {1, 2.05, 0}, {0, 2, 0}})};
  Lod2Mesh m = mesh_of(p);
  EXPECT_EQ(remove_collinear_vertices(m.vertices, m.faces, 0.01), 1);
  EXPECT_EQ(m.faces[0].size(), 5u);
  // A vertex with three neighbours stays even on a straight line.
  std::vector<CityPolygon> t = {poly({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}), poly({{1, 0, 0}, {0, 0, 0}, {1, -1, 0}})};
  Lod2Mesh tm = mesh_of(t);
  EXPECT_EQ(remove_collinear_vertices(tm.vertices, tm.faces, 0.01), 0);
}

TEST(Lod2Cleanup, ClosureNamesTheReason) {
  std::string reason;
  EXPECT_EQ(closure_problem(mesh_of(box(0, 0, 1, 1, 0, 1)), &reason), "");
  EXPECT_EQ(reason, "");
  auto open = box(0, 0, 1, 1, 0, 1);
  open.erase(open.begin() + 3);
  EXPECT_NE(closure_problem(mesh_of(open), &reason), "");
  EXPECT_EQ(reason, "not_closed");
  auto no_roof = box(0, 0, 1, 1, 0, 1);
  no_roof[1].kind = CitySurface::kWall;
  closure_problem(mesh_of(no_roof), &reason);
  EXPECT_EQ(reason, "no_roof");
  closure_problem(mesh_of({poly({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}})}), &reason);
  EXPECT_EQ(reason, "too_few_faces");
  // A box on a roof whose opening was an inner ring: the small box's bottom edges lie on the roof.
  auto court = box(0, 0, 10, 10, 0, 3);
  auto top = box(4, 4, 6, 6, 3, 4);
  top.erase(top.begin());  // no ground of its own: it stood in the roof's opening
  court.insert(court.end(), top.begin(), top.end());
  EXPECT_EQ(closure_problem(mesh_of(court), &reason), "");
}

TEST(Lod2Cleanup, WholeChainOnTwoPartsSharingAWall) {
  auto p = box(0, 0, 10, 6, 0, 3, 1);
  auto q = box(10, 0, 16, 6, 0, 3, 2);
  p.insert(p.end(), q.begin(), q.end());
  const Lod2CleanupResult r = cleanup_lod2(p);
  ASSERT_EQ(r.skip_reason, "") << r.skip_detail;
  EXPECT_EQ(r.report.vertices_before, 12);
  EXPECT_EQ(r.report.edges_before, 20);
  EXPECT_EQ(r.report.coincident_faces_removed, 2);
  EXPECT_EQ(r.report.collinear_vertices_removed, 4);
  EXPECT_EQ(r.mesh.vertices.size(), 8u);
  EXPECT_EQ(r.mesh.faces.size(), 6u);
  EXPECT_EQ(std::count(r.mesh.labels.begin(), r.mesh.labels.end(), FaceLabel::Roof), 1);
  EXPECT_EQ(std::count(r.mesh.labels.begin(), r.mesh.labels.end(), FaceLabel::Base), 1);
}

TEST(Lod2Cleanup, OptionsAreChecked) {
  Lod2CleanupOptions o;
  o.weld_tol_m = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.coplanar_angle_deg = 90;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  EXPECT_EQ(cleanup_lod2({}).skip_reason, "no_polygons");
}

}  // namespace
}  // namespace lc2wf

#include "dataset/synthetic/surface_clutter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"

namespace lc2wf {
namespace {

// A hip-roof corner: apex 0 with three edges that bound three faces, standing on a 10 x 6 m footprint.
Wireframe tent() {
  Wireframe wf;
  wf.junctions = {{0, 0, 4}, {5, 3, 0}, {-5, 3, 0}, {0, -3, 0}};
  wf.edges = {{0, 1}, {0, 2}, {0, 3}};
  return wf;
}

double distance_to_plane(const Vec3& p, const Vec3& origin, const Vec3& u, const Vec3& v) {
  return std::abs((p - origin).dot(u.cross(v).normalized()));
}

TEST(SurfaceClutter, FaceLinesLieInACornerOfTheWireframe) {
  const Wireframe wf = tent();
  SurfaceClutterOptions o;
  o.face_lines = 300;
  DataRng rng(5);
  const std::vector<Segment3> lines = make_surface_clutter(wf, o, rng);
  ASSERT_EQ(lines.size(), 300u);
  const Vec3 apex = wf.junctions[0];
  std::array<int, 3> per_face{};
  for (const Segment3& s : lines) {
    EXPECT_GE(s.length(), o.min_length_m - 1e-12);
    EXPECT_LE(s.length(), o.max_length_m + 1e-12);
    int face = -1;
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = wf.junctions[1 + k] - apex, v = wf.junctions[1 + (k + 1) % 3] - apex;
      if (distance_to_plane(s.a, apex, u, v) < 1e-9 && distance_to_plane(s.b, apex, u, v) < 1e-9) face = k;
    }
    ASSERT_GE(face, 0) << "a face line off every face plane";
    ++per_face[face];
    // The centre is in the corner's triangle, which reaches corner_reach_m along each edge.
    EXPECT_LE(((s.a + s.b) / 2 - apex).norm(), o.corner_reach_m + 1e-9);
  }
  for (int count : per_face) EXPECT_GT(count, 50);  // every face gets lines
}

TEST(SurfaceClutter, GroundLinesSurroundTheFootprintOnTheGround) {
  const Wireframe wf = tent();
  SurfaceClutterOptions o;
  o.ground_lines = 500;
  o.ground_margin_m = 4.0;
  DataRng rng(7);
  const std::vector<Segment3> lines = make_surface_clutter(wf, o, rng);
  ASSERT_EQ(lines.size(), 500u);
  for (const Segment3& s : lines) {
    EXPECT_EQ(s.a.z(), 0.0);
    EXPECT_EQ(s.b.z(), 0.0);
    const Vec3 c = (s.a + s.b) / 2;
    EXPECT_FALSE(c.x() > -5 && c.x() < 5 && c.y() > -3 && c.y() < 3) << "under the roof";
    EXPECT_LE(std::abs(c.x()), 5 + 4 + 1e-9);
    EXPECT_LE(std::abs(c.y() - 0), 3 + 4 + 1e-9);
  }
}

TEST(SurfaceClutter, DeterministicAndEmptyWithoutAWireframe) {
  SurfaceClutterOptions o;
  o.face_lines = 20;
  o.ground_lines = 20;
  DataRng a(3), b(3);
  const auto x = make_surface_clutter(tent(), o, a), y = make_surface_clutter(tent(), o, b);
  ASSERT_EQ(x.size(), y.size());
  for (size_t i = 0; i < x.size(); ++i) EXPECT_EQ(x[i].a, y[i].a);
  DataRng c(3);
  EXPECT_TRUE(make_surface_clutter(Wireframe{}, o, c).empty());
  Wireframe line;  // one edge: no corner, so only ground lines
  line.junctions = {{0, 0, 0}, {3, 0, 0}};
  line.edges = {{0, 1}};
  EXPECT_EQ(make_surface_clutter(line, o, c).size(), 20u);
}

TEST(SurfaceClutter, ClutteredCloudsStayValidAndUnlabelledWhereAdded) {
  const LineCloud c = make_synthetic_line_cloud(make_random_building(2, "b"), 2);
  ASSERT_EQ(c.support.size(), c.segments.size());
  SurfaceClutterOptions o;
  o.face_lines = 40;
  o.ground_lines = 60;
  const LineCloud x = with_surface_clutter(c, o, 9);
  ASSERT_EQ(x.segments.size(), c.segments.size() + 100);
  ASSERT_EQ(x.labels.size(), x.segments.size());
  ASSERT_EQ(x.support.size(), x.segments.size());
  EXPECT_NO_THROW(validate_line_cloud(x, "cluttered"));
  for (size_t i = c.segments.size(); i < x.segments.size(); ++i) {
    EXPECT_FALSE(x.labels[i].f);
    EXPECT_TRUE(x.support[i].empty());
  }
  EXPECT_EQ(with_surface_clutter(c, o, 9).segments.back().a, x.segments.back().a);
}

TEST(SurfaceClutter, RejectsBadOptions) {
  SurfaceClutterOptions o;
  o.face_lines = -1;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.max_length_m = 0.01;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.ground_margin_m = std::nan("");
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

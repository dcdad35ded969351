// Which sides of a footprint the cameras see (dataset/photo/camera_coverage.h).
#include "dataset/photo/camera_coverage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"

namespace lc2wf {
namespace {

// Views of the ring whose azimuth (degrees) lies in [lo, hi].
std::vector<Camera> ring_arc(const Building& b, int views, double lo, double hi) {
  CameraRingOptions o;
  o.num_views = views;
  o.elevation_deg = 10;
  std::vector<Camera> out;
  const std::vector<Camera> ring = make_camera_ring(b, o);
  for (int i = 0; i < views; ++i) {
    double az = 360.0 * i / views;
    if (az > 180) az -= 360;
    if (az >= lo - 1e-9 && az <= hi + 1e-9) out.push_back(ring[i]);
  }
  return out;
}

const SideCoverage* side_facing(const CameraCoverage& c, double azimuth_deg) {
  for (const SideCoverage& s : c.sides)
    if (std::abs(std::remainder(s.outward_azimuth_deg - azimuth_deg, 360.0)) < 10) return &s;
  return nullptr;
}

TEST(CameraCoverage, AFullRingSeesEverySide) {
  const Building b = make_rect_building("box", RectBuildingSpec{});
  const CameraCoverage c = camera_coverage(ring_arc(b, 16, -180, 180), b.wireframe.junctions);
  EXPECT_EQ(c.cameras, 16);
  EXPECT_NEAR(c.azimuth_span_deg, 360 - 22.5, 1e-6);
  ASSERT_EQ(c.sides.size(), 4u);
  for (const SideCoverage& s : c.sides) EXPECT_TRUE(s.seen) << s.outward_azimuth_deg << ": " << s.cameras;
  EXPECT_NEAR(c.seen_outline_share, 1.0, 1e-9);
}

TEST(CameraCoverage, AnArcFromOneSideNamesThatSideAndTheUnseenOnes) {
  const Building b = make_rect_building("box", RectBuildingSpec{});  // long sides face +-y
  const CameraCoverage c = camera_coverage(ring_arc(b, 16, 45, 135), b.wireframe.junctions);
  EXPECT_EQ(c.cameras, 5);
  EXPECT_NEAR(c.azimuth_span_deg, 90, 1e-6);
  EXPECT_NEAR(c.azimuth_from_deg, 45, 1e-6);
  EXPECT_NEAR(c.azimuth_to_deg, 135, 1e-6);
  ASSERT_EQ(c.sides.size(), 4u);
  const SideCoverage* front = side_facing(c, 90);
  const SideCoverage* back = side_facing(c, -90);
  ASSERT_TRUE(front && back);
  EXPECT_TRUE(front->seen);
  EXPECT_EQ(front->cameras, 5);
  EXPECT_FALSE(back->seen);
  EXPECT_EQ(back->cameras, 0);
  EXPECT_GT(c.seen_outline_share, 0.2);
  EXPECT_LT(c.seen_outline_share, 0.99);
  EXPECT_NE(c.summary().find("unseen: facing"), std::string::npos) << c.summary();
  const nlohmann::json j = coverage_json(c);
  EXPECT_EQ(j["sides"].size(), 4u);
  EXPECT_FALSE(j["unseen_sides_facing_deg"].empty());
}

TEST(CameraCoverage, DegenerateInputsGiveAnEmptyButValidReport) {
  const CameraCoverage none = camera_coverage({}, std::vector<Vec3>{});
  EXPECT_EQ(none.cameras, 0);
  EXPECT_TRUE(none.sides.empty());
  EXPECT_EQ(none.seen_outline_share, 0.0);
  EXPECT_FALSE(none.summary().empty());
  // A wireframe on one line spans no footprint: the cloud's is used.
  Wireframe line;
  line.junctions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  const CameraCoverage c = camera_coverage({}, line, {{Vec3(0, 0, 0), Vec3(3, 0, 0)}, {Vec3(0, 2, 0), Vec3(0, 2, 3)}});
  EXPECT_EQ(c.outline, "cloud");
  EXPECT_EQ(c.sides.size(), 4u);
  CoverageOptions bad;
  bad.min_cameras = 0;
  EXPECT_THROW(camera_coverage({}, std::vector<Vec3>{}, bad), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

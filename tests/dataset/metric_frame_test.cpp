// Fixing an SfM frame's scale, up axis and ground (dataset/photo/metric_frame.h): a synthetic building seen by
// a ring of upright cameras is moved into a random similarity frame and brought back.
#include <gtest/gtest.h>

#include "dataset/photo/metric_frame.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "tests/common/constant_height_model.h"

namespace lc2wf {
namespace {

struct Scene {
  Building building = make_rect_building("box", RectBuildingSpec{});
  std::vector<Camera> cameras;
  std::vector<Segment3> segments;  // the GT edges: vertical wall corners, base outline at z = 0
  double height = 0;
};

Scene scene_in(const Similarity& sfm) {
  Scene s;
  CameraRingOptions ring;
  ring.num_views = 12;
  for (const Camera& c : make_camera_ring(s.building, ring)) s.cameras.push_back(sfm.apply(c));
  for (const auto& e : s.building.wireframe.edges)
    s.segments.push_back(sfm.apply(Segment3{s.building.wireframe.junctions[e[0]], s.building.wireframe.junctions[e[1]]}));
  for (const Vec3& j : s.building.wireframe.junctions) s.height = std::max(s.height, j.z());
  return s;
}

Similarity random_sfm_frame() {
  Similarity sfm;
  sfm.scale = 0.137;
  sfm.R = Eigen::AngleAxisd(0.7, Vec3(0.3, -0.8, 0.5).normalized()).toRotationMatrix();
  sfm.t = Vec3(3.0, -1.5, 12.0);
  return sfm;
}

TEST(MetricFrame, CamerasGiveUpAndTheCloudGivesGroundAndScale) {
  const Similarity sfm = random_sfm_frame();
  const Scene s = scene_in(sfm);
  MetricFrameOptions o;
  o.building_height_m = s.height;  // the user's word for the building's height
  o.min_vertical_lines = 4;
  const MetricFrame f = estimate_metric_frame(s.cameras, s.segments, o);
  EXPECT_EQ(f.up_source, "cameras+lines");
  EXPECT_EQ(f.scale_source, "building height");
  EXPECT_FALSE(f.needs_scale_search);
  EXPECT_NEAR(f.to_metric.scale * sfm.scale, 1.0, 1e-9);
  // Back in metres: z is up again (up to a turn about z) and the ground is at 0.
  const Eigen::Matrix3d back = f.to_metric.R * sfm.R;
  EXPECT_NEAR((back * Vec3::UnitZ() - Vec3::UnitZ()).norm(), 0.0, 1e-9);
  for (const Vec3& j : s.building.wireframe.junctions) {
    const Vec3 p = f.to_metric.apply(sfm.apply(j));
    EXPECT_NEAR(p.z(), j.z(), 1e-9);
  }
}

TEST(MetricFrame, GivenScaleAndKnownDistanceWinOverTheEstimate) {
  const Similarity sfm = random_sfm_frame();
  const Scene s = scene_in(sfm);
  MetricFrameOptions o;
  o.scale = 2.5;
  EXPECT_DOUBLE_EQ(estimate_metric_frame(s.cameras, s.segments, o).to_metric.scale, 2.5);
  o.scale = 0;
  o.known_view_a = 0, o.known_view_b = 5;
  const Vec3 ca = sfm.inverse().apply(s.cameras[0].center()), cb = sfm.inverse().apply(s.cameras[5].center());
  o.known_distance_m = (ca - cb).norm();  // metres in the building frame
  const MetricFrame f = estimate_metric_frame(s.cameras, s.segments, o);
  EXPECT_EQ(f.scale_source, "known distance");
  EXPECT_NEAR(f.to_metric.scale * sfm.scale, 1.0, 1e-9);
}

// No evidence, no assumed height: the frame's unit is the cloud's height, and the search's height scales it.
TEST(MetricFrame, WithoutEvidenceTheScaleIsLeftToTheSearch) {
  const Similarity sfm = random_sfm_frame();
  const Scene s = scene_in(sfm);
  MetricFrameOptions o;
  o.min_vertical_lines = 4;
  const MetricFrame f = estimate_metric_frame(s.cameras, s.segments, o);
  EXPECT_EQ(f.scale_source, "scale search");
  EXPECT_TRUE(f.needs_scale_search);
  EXPECT_NEAR(f.height_input * f.to_metric.scale, 1.0, 1e-9);
  const MetricFrame g = f.scaled_by(s.height);
  EXPECT_NEAR(g.to_metric.scale * sfm.scale, 1.0, 1e-9);
  for (const Vec3& j : s.building.wireframe.junctions) EXPECT_NEAR(g.to_metric.apply(sfm.apply(j)).z(), j.z(), 1e-9);
}

// A height model (line_height.h) reads the height when nothing before it gives the scale; a building height
// given by the user still wins, and a cloud too small for the statistics goes to the search, saying why.
TEST(MetricFrame, AHeightModelScalesWhatNothingElseDoes) {
  const Similarity sfm = random_sfm_frame();
  const Scene s = scene_in(sfm);
  ASSERT_GE(s.segments.size(), 10u);
  HeightModel model = test::constant_height_model(s.height);  // the frame must use exactly what it reads
  MetricFrameOptions o;
  o.min_vertical_lines = 4;
  o.height_model = model;
  const MetricFrame f = estimate_metric_frame(s.cameras, s.segments, o);
  EXPECT_EQ(f.scale_source, "line statistics");
  EXPECT_FALSE(f.needs_scale_search);
  EXPECT_NEAR(f.line_height_m, s.height, 1e-9 * s.height);
  EXPECT_NEAR(f.to_metric.scale * sfm.scale, 1.0, 1e-9);
  o.building_height_m = 2 * s.height;
  EXPECT_EQ(estimate_metric_frame(s.cameras, s.segments, o).scale_source, "building height");
  o.building_height_m = 0;
  const std::vector<Segment3> few(s.segments.begin(), s.segments.begin() + 6);
  const MetricFrame g = estimate_metric_frame(s.cameras, few, o);
  EXPECT_EQ(g.scale_source, "scale search");
  EXPECT_NE(g.line_height_why_not.find("10 lines"), std::string::npos) << g.line_height_why_not;
  model.stddev[0] = -1;  // a broken model is refused with the options
  o.height_model = model;
  EXPECT_THROW(estimate_metric_frame(s.cameras, s.segments, o), std::invalid_argument);
}

// Storeys and the height model agree within a factor of 3: the storeys (the finer ruler) give the scale; a
// model reading 4x the height overrules them (a wrong rhythm) and says so.
TEST(MetricFrame, StoreysThatDisagreeWithTheHeightModelAreOverruled) {
  const double storey = 3.0, units = 0.25;  // 5 storeys, 0.25 units per metre
  std::vector<Segment3> s;
  for (double x : {0.0, 20.0}) s.push_back({Vec3(x, 0, 0) * units, Vec3(x, 0, 5 * storey) * units});
  for (int k = 0; k < 5; ++k)
    for (double x = 1.0; x < 19; x += 2.5)
      for (double side : {x, x + 1.2}) s.push_back({Vec3(side, 0, k * storey + 0.9) * units, Vec3(side, 0, k * storey + 2.2) * units});
  MetricFrameOptions o;
  o.up = UpSource::kInputZ;
  const MetricFrame plain = estimate_metric_frame({}, s, o);
  ASSERT_EQ(plain.scale_source, "storeys") << plain.storeys.why_not;
  const double height_m = plain.height_input * plain.to_metric.scale;  // what the storeys make of it
  o.height_model = test::constant_height_model(2.5 * height_m);
  const MetricFrame agreed = estimate_metric_frame({}, s, o);
  EXPECT_EQ(agreed.scale_source, "storeys");
  EXPECT_DOUBLE_EQ(agreed.to_metric.scale, plain.to_metric.scale);
  o.height_model = test::constant_height_model(4 * height_m);
  const MetricFrame overruled = estimate_metric_frame({}, s, o);
  EXPECT_EQ(overruled.scale_source, "line statistics");
  EXPECT_NE(overruled.storeys_overruled.find("lower than the height model reads"), std::string::npos) << overruled.storeys_overruled;
  EXPECT_EQ(line_height_json(overruled, *o.height_model)["used"], true);
  o.max_storey_disagreement = 0.5;
  EXPECT_THROW(estimate_metric_frame({}, s, o), std::invalid_argument);
}

// Camera centres fitted to GPS give scale, up and north: x east, y north.
TEST(MetricFrame, GpsGivesScaleUpAndNorth) {
  const Similarity sfm = random_sfm_frame();
  const Scene s = scene_in(sfm);
  Similarity building_to_enu;  // the building stands turned 30 deg from east, 100 m east of the GPS origin
  building_to_enu.R = Eigen::AngleAxisd(0.52, Vec3::UnitZ()).toRotationMatrix();
  building_to_enu.t = Vec3(100, -20, 35);
  const Similarity inv = sfm.inverse();
  Similarity to_enu;  // sfm -> enu = building_to_enu o sfm^-1
  to_enu.scale = inv.scale, to_enu.R = building_to_enu.R * inv.R, to_enu.t = building_to_enu.R * inv.t + building_to_enu.t;
  MetricFrameOptions o;
  o.gps_to_enu = to_enu;
  o.building_height_m = 99;  // GPS comes first
  o.min_vertical_lines = 4;
  const MetricFrame f = estimate_metric_frame(s.cameras, s.segments, o);
  EXPECT_EQ(f.scale_source, "gps");
  EXPECT_EQ(f.up_source, "gps+lines");
  EXPECT_NEAR(f.to_metric.scale * sfm.scale, 1.0, 1e-9);
  // The output frame is the ENU frame up to a shift: its rotation is the GPS one.
  const Eigen::Matrix3d back = f.to_metric.R * sfm.R;
  EXPECT_LT((back - building_to_enu.R).norm(), 1e-9);
}

// A map without cameras: up from the lines alone, whatever the frame it came in.
TEST(MetricFrame, LinesAloneGiveUpForMapsWithoutCameras) {
  const Similarity sfm = random_sfm_frame();
  const Scene s = scene_in(sfm);
  MetricFrameOptions o;
  o.min_vertical_lines = 4;
  const MetricFrame f = estimate_metric_frame({}, s.segments, o);
  EXPECT_EQ(f.up_source, "line directions+lines");
  const Vec3 up = (f.to_metric.R * sfm.R).transpose() * Vec3::UnitZ();
  EXPECT_LT(std::acos(std::min(1.0, up.z())) * 180 / M_PI, 1e-6);
}

TEST(MetricFrame, CameraUpWithoutLinesAndTiltedCamerasStayClose) {
  Similarity sfm = random_sfm_frame();
  Scene s = scene_in(sfm);
  // Hand-held photos are not perfectly upright: 3 deg of roll on every other camera.
  for (size_t k = 0; k < s.cameras.size(); k += 2) s.cameras[k].R = Eigen::AngleAxisd(0.05, Vec3::UnitZ()).toRotationMatrix() * s.cameras[k].R;
  MetricFrameOptions o;
  o.up = UpSource::kCameras;
  const MetricFrame f = estimate_metric_frame(s.cameras, s.segments, o);
  EXPECT_EQ(f.up_source, "cameras");
  const Vec3 up_metres = (f.to_metric.R * sfm.R).transpose() * Vec3::UnitZ();
  EXPECT_LT(std::acos(std::min(1.0, up_metres.dot(Vec3::UnitZ()))) * 180 / M_PI, 2.0);
  // The vertical wall corners pull it back to the true up.
  o.up = UpSource::kAuto;
  o.min_vertical_lines = 4;
  const MetricFrame g = estimate_metric_frame(s.cameras, s.segments, o);
  const Vec3 refined = (g.to_metric.R * sfm.R).transpose() * Vec3::UnitZ();
  EXPECT_LT(std::acos(std::min(1.0, refined.dot(Vec3::UnitZ()))) * 180 / M_PI, 1e-6);
}

TEST(MetricFrame, SimilarityMapsCamerasConsistently) {
  const Similarity sfm = random_sfm_frame();
  const Building b = make_rect_building("box", RectBuildingSpec{});
  const Camera c = make_camera_ring(b).front();
  const Camera moved = sfm.apply(c);
  const Vec3 p(1.0, 2.0, 3.0);
  EXPECT_LT((moved.project(sfm.apply(p)) - c.project(p)).norm(), 1e-9);
  EXPECT_LT((sfm.inverse().apply(sfm.apply(p)) - p).norm(), 1e-12);
}

TEST(MetricFrame, BadInputIsRejected) {
  MetricFrameOptions o;
  EXPECT_THROW(estimate_metric_frame({}, {}, o), std::invalid_argument);
  o.known_distance_m = 3;
  EXPECT_THROW(o.Check(), std::invalid_argument);  // no views named
  o = {};
  o.building_height_m = -1;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

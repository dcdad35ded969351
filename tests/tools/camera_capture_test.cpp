// Camera placement of lc2wf-dataset --capture: the orbit is the ring of before, street captures stand in
// front of one facade or of two facades around a corner, at pedestrian height.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>

#include "dataset/geometry/footprint.h"
#include "dataset/synthetic/synthetic_building.h"
#include "tests/tools/camera_expectations.h"
#include "tools/render/camera_ring.h"
#include "tools/render/capture_kind.h"

namespace lc2wf {
namespace {

constexpr double kDeg = M_PI / 180.0;

Building house() {
  RectBuildingSpec spec;
  spec.west = RoofEnd::Gable;
  return make_rect_building("house", spec);
}

// The house turned 30 degrees and moved off the origin: its facades face no axis.
std::vector<Vec3> turned_house() {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(30 * kDeg, Vec3::UnitZ()).toRotationMatrix();
  std::vector<Vec3> v;
  for (const Vec3& p : house().mesh.vertices) v.push_back(R * p + Vec3(40, -25, 3));
  return v;
}

struct Side {
  Vec2 a, b, normal;  // outward normal
};

std::vector<Side> footprint_sides_of(const std::vector<Vec3>& points) {
  const std::vector<Vec2> r = footprint_rectangle(points);  // counter-clockwise
  std::vector<Side> sides;
  for (int k = 0; k < 4; ++k) {
    const Vec2 a = r[k], b = r[(k + 1) % 4], d = (b - a).normalized();
    sides.push_back({a, b, Vec2(d.y(), -d.x())});
  }
  return sides;
}

Vec2 footprint_centre(const std::vector<Vec3>& points) {
  Vec2 c = Vec2::Zero();
  for (const Vec2& p : footprint_rectangle(points)) c += 0.25 * p;
  return c;
}

double angle_deg(const Vec2& u, const Vec2& v) { return std::acos(std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0)) / kDeg; }

double lowest(const std::vector<Vec3>& points) {
  double z = std::numeric_limits<double>::infinity();
  for (const Vec3& p : points) z = std::min(z, p.z());
  return z;
}

// Pedestrian cameras: 1.5-3 m above the lowest point, aimed at the centre of a 7 m house: level (the aim
// point's jitter can bring it down to the camera's height) or slightly up.
void expect_street_level(const Camera& c, const std::vector<Vec3>& points) {
  const double h = c.center().z() - lowest(points);
  EXPECT_GE(h, 1.5 - 1e-9);
  EXPECT_LE(h, 3.0 + 1e-9);
  EXPECT_GT(c.R(2, 2), -std::sin(1 * kDeg)) << "looks down";
  EXPECT_LT(c.R(2, 2), std::sin(20 * kDeg)) << "looks up steeply";
}

CameraRingOptions capture_options(const std::string& kind, int views, uint64_t seed) {
  CameraRingOptions o = capture_ring(CameraRingOptions{}, kind);
  o.views = views;
  o.seed = seed;
  return o;
}

TEST(CameraCapture, OrbitKeepsTheCamerasOfBefore) {
  // Centres and optical axes of the ring before street captures existed (house, 6 views, seed 11).
  const double before[6][6] = {
      {2.9690690544495362, -18.044813251168282, 10.4167648908793, -0.14842549586175, 0.92678602346997574, -0.34501817180969346},
      {18.50284726017691, -7.4871343842853522, 16.339281290693673, -0.76433490544444904, 0.33352106924998953, -0.55186578865297375},
      {15.563625896044076, 9.2794018088034544, 21.608193293267135, -0.60498537404856001, -0.36605012933657588, -0.70710678118654746},
      {-2.9227031727911772, 18.247391675695727, 11.410123326397043, 0.14061662751381221, -0.91470574380277636, -0.37886721462915091},
      {-19.665111923076111, 7.8877573115289037, 16.92429160345673, 0.79445972111204788, -0.30428456364866696, -0.52558981711569286},
      {-14.673764329589197, -11.45789952642739, 20.121859638100048, 0.58201201573010786, 0.4558978955128154, -0.67336403409505219}};
  CameraRingOptions o;
  o.views = 6;
  o.seed = 11;
  const auto cams = make_camera_ring(house().mesh.vertices, capture_ring(o, "orbit"));
  ASSERT_EQ(cams.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    const Vec3 c = cams[i].center();
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], before[i][k], 1e-9) << "view " << i;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(cams[i].R(2, k), before[i][3 + k], 1e-12) << "view " << i;
  }
  const auto again = make_camera_ring(house().mesh.vertices, o);  // orbit = the options as they are
  for (int i = 0; i < 6; ++i) EXPECT_EQ(again[i].t, cams[i].t);
}

TEST(CameraCapture, StreetOneStaysInFrontOfOneLongFacade) {
  const std::vector<Vec3> points = turned_house();
  const std::vector<Side> sides = footprint_sides_of(points);
  const Vec2 centre = footprint_centre(points);
  std::set<int> facades_used;
  for (uint64_t seed = 0; seed < 8; ++seed) {
    const CameraRingOptions o = capture_options("street-1", 12, seed);
    const auto cams = make_camera_ring(points, o);
    ASSERT_EQ(cams.size(), 12u);
    // The facade every camera stands in front of, within the 90 degree sector around its normal.
    int facade = -1;
    for (int k = 0; k < 4; ++k) {
      bool all = true;
      for (const Camera& c : cams) {
        const Vec2 p = c.center().head<2>();
        all = all && (p - sides[k].a).dot(sides[k].normal) > 0 && angle_deg(p - centre, sides[k].normal) <= 45 + 3;
      }
      if (all) facade = k;
    }
    ASSERT_GE(facade, 0) << "seed " << seed << ": the cameras are not all in front of one facade";
    EXPECT_GT((sides[facade].b - sides[facade].a).norm(), 11.9) << "a long facade (12 m, not the 9 m end)";
    facades_used.insert(facade);
    double widest = 0;  // the views spread over the sector, not one spot
    for (const Camera& a : cams)
      for (const Camera& b : cams) widest = std::max(widest, angle_deg(a.center().head<2>() - centre, b.center().head<2>() - centre));
    EXPECT_GT(widest, 60) << "seed " << seed;
    for (const Camera& c : cams) {
      expect_street_level(c, points);
      expect_frames_every_point(c, points, o);
    }
  }
  EXPECT_EQ(facades_used.size(), 2u) << "the seed picks either long facade";
}

TEST(CameraCapture, StreetTwoSpansTwoFacadesAroundACorner) {
  const std::vector<Vec3> points = turned_house();
  const std::vector<Side> sides = footprint_sides_of(points);
  const Vec2 centre = footprint_centre(points);
  std::set<int> corners_used;
  for (uint64_t seed = 0; seed < 8; ++seed) {
    const CameraRingOptions o = capture_options("street-2", 16, seed);
    const auto cams = make_camera_ring(points, o);
    ASSERT_EQ(cams.size(), 16u);
    // The corner (between sides k and k+1) whose 180 degree half-plane holds every camera.
    int corner = -1;
    for (int k = 0; k < 4; ++k) {
      const Vec2 bisector = sides[k].normal + sides[(k + 1) % 4].normal;
      bool all = true;
      for (const Camera& c : cams) all = all && angle_deg(c.center().head<2>() - centre, bisector) <= 90 + 3;
      if (all) corner = k;
    }
    ASSERT_GE(corner, 0) << "seed " << seed << ": the cameras leave the 180 degree sector of every corner";
    corners_used.insert(corner);
    int in_front_of_first = 0, in_front_of_second = 0;  // both facades get views
    for (const Camera& c : cams) {
      const Vec2 d = c.center().head<2>() - centre;
      in_front_of_first += angle_deg(d, sides[corner].normal) < 45;
      in_front_of_second += angle_deg(d, sides[(corner + 1) % 4].normal) < 45;
      expect_street_level(c, points);
      expect_frames_every_point(c, points, o);
    }
    EXPECT_GE(in_front_of_first, 4) << "seed " << seed;
    EXPECT_GE(in_front_of_second, 4) << "seed " << seed;
  }
  EXPECT_GE(corners_used.size(), 2u) << "the seed picks the corner";
}

// A walk down the street: every camera on one straight line parallel to a long side, at eye height, at one
// distance from it, spread along it, each framing the whole building.
TEST(CameraCapture, WalkStaysOnOneLineAlongALongFacade) {
  const std::vector<Vec3> points = turned_house();
  const std::vector<Side> sides = footprint_sides_of(points);
  for (uint64_t seed = 0; seed < 4; ++seed) {
    const CameraRingOptions o = capture_options("walk", 10, seed);
    const auto cams = make_camera_ring(points, o);
    ASSERT_EQ(cams.size(), 10u);
    int facade = -1;
    for (int k = 0; k < 4; ++k) {
      bool all = true;
      for (const Camera& c : cams) all = all && (c.center().head<2>() - sides[k].a).dot(sides[k].normal) > 0;
      if (all && (sides[k].b - sides[k].a).norm() > 11.9) facade = k;
    }
    ASSERT_GE(facade, 0) << "seed " << seed << ": not all in front of one long facade";
    const Side& side = sides[facade];
    const double distance = (cams[0].center().head<2>() - side.a).dot(side.normal);
    double lo = 1e300, hi = -1e300;
    for (const Camera& c : cams) {
      const Vec2 p = c.center().head<2>();
      EXPECT_NEAR((p - side.a).dot(side.normal), distance, 1e-9 * distance) << "seed " << seed << ": off the line";
      const double along = (p - side.a).dot((side.b - side.a).normalized());
      lo = std::min(lo, along), hi = std::max(hi, along);
      const double h = c.center().z() - lowest(points);
      EXPECT_GE(h, 1.5 - 1e-9);
      EXPECT_LE(h, 1.8 + 1e-9);
      expect_frames_every_point(c, points, o);
    }
    EXPECT_GT(hi - lo, distance) << "seed " << seed << ": the views spread along the street";
  }
  CameraRingOptions bad = capture_ring(CameraRingOptions{}, "walk");
  bad.azimuth_span_deg = 170;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

TEST(CameraCapture, BadValuesNameTheField) {
  auto message = [](const CameraRingOptions& o) {
    try {
      o.Check();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CameraRingOptions o;
  for (double span : {0.0, -90.0, 361.0, std::nan("")}) {
    o.azimuth_span_deg = span;
    EXPECT_NE(message(o).find("CameraRingOptions.azimuth_span_deg"), std::string::npos) << span;
  }
  o = CameraRingOptions{};
  o.min_camera_height_m = 3, o.max_camera_height_m = 1.5;
  EXPECT_NE(message(o).find("CameraRingOptions.min/max_camera_height_m"), std::string::npos);
  o.min_camera_height_m = 0, o.max_camera_height_m = 2;
  EXPECT_NE(message(o).find("CameraRingOptions.min/max_camera_height_m"), std::string::npos);
  o.min_camera_height_m = o.max_camera_height_m = 0;
  EXPECT_EQ(message(o), "");
  EXPECT_EQ(message(capture_ring(o, "street-2")), "");
  try {
    capture_ring(o, "street-3");
    ADD_FAILURE() << "street-3 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("capture must be orbit, street-1, street-2 or walk, got 'street-3'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lc2wf

// Software rasteriser and camera rings.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <vector>
#include <opencv2/imgproc.hpp>

#include "dataset/synthetic/synthetic_building.h"
#include "tests/tools/camera_expectations.h"
#include "tools/render/camera_ring.h"
#include "tools/render/raster_renderer.h"

namespace lc2wf {
namespace {

Building house() {
  RectBuildingSpec spec;
  spec.west = RoofEnd::Gable;
  return make_rect_building("house", spec);
}

// The default ring of `views` cameras around a building.
std::vector<Camera> ring_around(const Building& b, int views) {
  CameraRingOptions o;
  o.views = views;
  return make_camera_ring(b.mesh.vertices, o);
}

TEST(CameraRing, FramesTheWholeBuildingWithinTheElevationBand) {
  const Building b = house();
  CameraRingOptions o;
  o.views = 16;
  o.seed = 3;
  const auto cams = make_camera_ring(b.mesh.vertices, o);
  ASSERT_EQ(cams.size(), 16u);
  for (const Camera& c : cams) {
    EXPECT_LT((c.R * c.R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(c.R.determinant(), 1.0, 1e-12);
    expect_frames_every_point(c, b.mesh.vertices, o);
    const Vec3 dir = (c.center() - Vec3(0, 0, 2)).normalized();
    const double elev = std::asin(dir.z()) * 180 / M_PI;
    EXPECT_GT(elev, o.min_elevation_deg - 5);
    EXPECT_LT(elev, o.max_elevation_deg + 5);
  }
  const auto again = make_camera_ring(b.mesh.vertices, o);
  EXPECT_EQ(again[5].t, cams[5].t);
  o.seed = 4;
  EXPECT_NE(make_camera_ring(b.mesh.vertices, o)[5].t, cams[5].t);
  o.views = 0;
  EXPECT_THROW(make_camera_ring(b.mesh.vertices, o), std::invalid_argument);
}

TEST(CameraRing, LargerBuildingsGetFinerPixelsInTheSameFraming) {
  CameraRingOptions o;  // 640 x 480
  const std::vector<Vec3> house{{0, 0, 0}, {12, 8, 6}};      // diagonal 15.6 m
  const std::vector<Vec3> block{{0, 0, 0}, {120, 40, 30}};   // diagonal 130 m
  EXPECT_EQ(view_scale_for(block, o, 0.0, 4096), 1.0);       // off
  EXPECT_EQ(view_scale_for(house, o, 0.05, 4096), 1.0);      // 0.024 m per pixel already
  const double k = view_scale_for(block, o, 0.05, 4096);     // 130 / (0.05 x 640) = 4.06
  EXPECT_NEAR(k, std::sqrt(120.0 * 120 + 40 * 40 + 30 * 30) / 32.0, 1e-12);
  EXPECT_EQ(view_scale_for(block, o, 0.05, 1280), 2.0);      // capped at 1280 px on the longer side
  EXPECT_EQ(view_scale_for(block, o, 0.05, 320), 1.0);       // a cap below the set size never shrinks
  CameraRingOptions big = scaled_ring(o, 2.0);
  EXPECT_EQ(big.width, 1280);
  EXPECT_EQ(big.height, 960);
  // Same framing: every camera of the scaled ring stands where the original does, with twice the focal length.
  o.seed = big.seed = 5;
  const auto a = make_camera_ring(block, o), b = make_camera_ring(block, big);
  ASSERT_EQ(a.size(), b.size());
  for (size_t v = 0; v < a.size(); ++v) {
    EXPECT_LT((a[v].center() - b[v].center()).norm(), 1e-3 * 130);
    EXPECT_NEAR(b[v].K(0, 0), 2.0 * a[v].K(0, 0), 1e-9);
  }
}

TEST(RasterRenderer, DepthMapMatchesTheMeshAndFaceIds) {
  const Building b = house();
  const auto cams = ring_around(b, 3);
  const RasterRenderer r(b.mesh, RasterOptions{});
  cv::Mat depth, ids;
  r.depth_map(cams[0], depth, ids);
  int hits = 0;
  for (int y = 0; y < depth.rows; y += 7)
    for (int x = 0; x < depth.cols; x += 7) {
      const int f = ids.at<int>(y, x);
      if (f < 0) continue;
      ++hits;
      // Back-project the pixel to the stored depth: the point lies on face f's plane.
      const double z = depth.at<float>(y, x);
      const Vec3 m((x - cams[0].K(0, 2)) / cams[0].K(0, 0), (y - cams[0].K(1, 2)) / cams[0].K(1, 1), 1.0);
      const Vec3 X = cams[0].R.transpose() * (m * z - cams[0].t);
      const FaceFrame& fr = r.mesh().frames[f];
      EXPECT_NEAR(fr.normal.dot(X), fr.offset, 2e-5 * z);
    }
  EXPECT_GT(hits, 500);
}

TEST(RasterRenderer, IsDeterministicAndShadowsDarkenTheGround) {
  const Building b = house();
  const auto cams = ring_around(b, 2);
  RasterOptions ro;
  ro.seed = 9;
  const RasterRenderer lit(b.mesh, ro);
  const cv::Mat a = lit.render(cams[0], 0).image, a2 = lit.render(cams[0], 0).image;
  ASSERT_EQ(a.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(a, a2, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, lit.render(cams[0], 1).image, cv::NORM_L1), 0.0);  // noise differs per view
  ro.shadows = false;
  const cv::Mat flat = RasterRenderer(b.mesh, ro).render(cams[0], 0).image;
  cv::Mat ga, gf;
  cv::cvtColor(a, ga, cv::COLOR_BGR2GRAY);
  cv::cvtColor(flat, gf, cv::COLOR_BGR2GRAY);
  EXPECT_LT(cv::mean(ga)[0], cv::mean(gf)[0] - 0.5);
  ro.supersample = 9;
  EXPECT_THROW(RasterRenderer(b.mesh, ro), std::invalid_argument);
  ro.supersample = 1;
  ro.blur_sigma_px = -1;
  EXPECT_THROW(RasterRenderer(b.mesh, ro), std::invalid_argument);
}

// Two walls in the sun's shade, seen at different angles, must get different shades, or their shared corner
// draws no line (the real validation split's clouds missed half the vertical edges' length with a constant
// ambient). The same render with a constant ambient is the reference: the ratio removes the texture.
TEST(RasterRenderer, WallsInShadeDifferByTheirAngleToTheCamera) {
  const Building b = house();
  const auto cams = ring_around(b, 24);
  RasterOptions ro;
  ro.noise_sigma = 0;
  ro.blur_sigma_px = 0;
  ro.shadows = false;
  ro.view_light = 0;
  const RasterRenderer constant(b.mesh, ro);
  ro.view_light = 0.5;
  const RasterRenderer dimmed(b.mesh, ro);
  const double az = ro.sun_azimuth_deg * M_PI / 180, el = ro.sun_elevation_deg * M_PI / 180;
  const Vec3 sun(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  double widest = 0;  // the largest difference between two shaded walls' dimming over the ring's views
  for (const Camera& cam : cams) {
    cv::Mat depth, ids, g0, g1;
    constant.depth_map(cam, depth, ids);
    cv::cvtColor(constant.render(cam, 0).image, g0, cv::COLOR_BGR2GRAY);
    cv::cvtColor(dimmed.render(cam, 0).image, g1, cv::COLOR_BGR2GRAY);
    std::map<int, std::array<double, 3>> walls;  // face -> sum constant, sum dimmed, pixels
    for (int y = 0; y < ids.rows; ++y)
      for (int x = 0; x < ids.cols; ++x) {
        const int f = ids.at<int>(y, x);
        if (f < 0) continue;
        const Vec3& n = constant.mesh().frames[f].normal;
        if (std::abs(n.z()) > 0.1) continue;  // roofs
        const Vec3 X = constant.mesh().frames[f].origin;
        const Vec3 towards_camera = (cam.center() - X).normalized();
        if ((n.dot(towards_camera) >= 0 ? n : Vec3(-n)).dot(sun) > 0) continue;  // lit by the sun
        auto& w = walls[f];
        w[0] += g0.at<uint8_t>(y, x), w[1] += g1.at<uint8_t>(y, x), w[2] += 1;
      }
    std::vector<double> dimming;
    for (const auto& [f, w] : walls)
      if (w[2] > 200 && w[0] > 0) dimming.push_back(w[1] / w[0]);
    for (double a : dimming) {
      EXPECT_LE(a, 1.0 + 1e-3);  // never brighter than the constant ambient
      for (double c : dimming) widest = std::max(widest, std::abs(a - c));
    }
  }
  EXPECT_GT(widest, 0.1);
  ro.view_light = 1.5;
  EXPECT_THROW(RasterRenderer(b.mesh, ro), std::invalid_argument);
}

TEST(RasterRenderer, SupersampledCameraKeepsPixelCentres) {
  Camera c;
  c.K << 600, 0, 319.5, 0, 600, 239.5, 0, 0, 1;
  c.width = 640;
  c.height = 480;
  const Camera s = supersampled_camera(c, 2);
  EXPECT_EQ(s.width, 1280);
  const Vec3 X(0.3, -0.2, 5.0);
  const Vec2 p = c.project(X), q = s.project(X);
  EXPECT_NEAR((q.x() + 0.5) / 2 - 0.5, p.x(), 1e-12);
  EXPECT_NEAR((q.y() + 0.5) / 2 - 0.5, p.y(), 1e-12);
}

TEST(FaceFrames, EarClippingCoversNonConvexPolygons) {
  // An L-shaped hexagon of area 3.
  const std::vector<Vec2> poly = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const auto tris = ear_clip(poly);
  ASSERT_EQ(tris.size(), 4u);
  double area = 0;
  for (const auto& t : tris) {
    const Vec2 a = poly[t[1]] - poly[t[0]], b = poly[t[2]] - poly[t[0]];
    area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
}

}  // namespace
}  // namespace lc2wf

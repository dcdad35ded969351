// The `--textures photo` surfaces carry the fine detail real materials have, and none of it repeats: SIFT
// (COLMAP's features) finds points on them and tells repeated elements apart. Before they had it, photo
// renders of a 3D BAG house gave COLMAP no initial pair from an orbit and folded its two facades onto one
// arc from the street (bench/README.md, "reconstruct").
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "dataset/synthetic/synthetic_building.h"
#include "tools/render/camera_ring.h"
#include "tools/render/face_frames.h"
#include "tools/render/photo_scene.h"
#include "tools/render/photo_textures.h"
#include "tools/render/raster_renderer.h"

namespace lc2wf {
namespace {

Building house() {
  RectBuildingSpec spec;
  spec.length = 12;
  spec.width = 9;
  spec.eave_height = 6;
  spec.west = spec.east = RoofEnd::Gable;
  return make_rect_building("house", spec);
}

std::vector<Vec3> centres(const std::vector<Camera>& cams) {
  std::vector<Vec3> out;
  for (const Camera& c : cams) out.push_back(c.center());
  return out;
}

double grey(const Rgb& c) { return 0.3 * c.r + 0.59 * c.g + 0.11 * c.b; }

// A point of a face at texture coordinates (u along axis_u, v along axis_v) from its origin.
Vec3 on_face(const FaceFrame& f, double u, double v) { return f.origin + u * f.axis_u + v * f.axis_v; }

// Fine detail: the mean absolute luminance step between samples 4 cm apart, relative to the mean
// luminance, over a size x size metre patch at (u, v) of a face.
template <class Colour>
double fine_detail(const Colour& colour, double size) {
  double steps = 0, sum = 0;
  int n = 0;
  for (double a = 0; a < size; a += 0.04)
    for (double b = 0; b < size; b += 0.04) {
      const double g = grey(colour(a, b));
      steps += std::abs(grey(colour(a + 0.04, b)) - g) + std::abs(grey(colour(a, b + 0.04)) - g);
      sum += g, ++n;
    }
  return steps / (2 * n) / (sum / n);
}

// Luminance samples of a patch (for comparing two patches).
template <class Colour>
std::vector<double> samples(const Colour& colour, double width, double height) {
  std::vector<double> out;
  for (double a = 0; a < width; a += 0.03)
    for (double b = 0; b < height; b += 0.03) out.push_back(grey(colour(a, b)));
  return out;
}

double mean_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, m = 0;
  for (size_t i = 0; i < a.size(); ++i) d += std::abs(a[i] - b[i]), m += a[i];
  return d / m;  // relative to the mean of a
}

struct Fixture {
  Building b = house();
  FacedMesh fm = build_faced_mesh(b.mesh);
  std::vector<Camera> cams;
  PhotoScene scene;
  Fixture() {
    CameraRingOptions ring;
    ring.seed = 3;
    cams = make_camera_ring(b.mesh.vertices, ring);
    scene = make_photo_scene(b.mesh, centres(cams), PhotoOptions{}, 3);
  }
};

TEST(PhotoTextures, EverySurfaceHasFineDetail) {
  const Fixture s;
  const PhotoTextures tex(s.scene, 3);
  int walls = 0, roofs = 0;
  for (size_t f = 0; f < s.fm.frames.size(); ++f) {
    const FaceFrame& fr = s.fm.frames[f];
    const FacadeLayout& L = s.scene.facades[f];
    if (L.wall && !L.windows.empty()) {
      // Plaster between the ground floor's first window and the sill above it.
      const FacadeRect& r = L.windows.front();
      const double u0 = 0.5 * (r.u0 + r.u1) - 0.25, z0 = r.z1 + 0.1 * L.storey_height;
      const double d = fine_detail([&](double a, double b) { return tex.building(static_cast<int>(f), fr, on_face(fr, u0 + a, -(z0 + b - fr.origin.z()))); }, 0.25);
      EXPECT_GT(d, 0.03) << "wall " << f;  // 0.07-0.10; the flat plaster of before 0.003-0.005
      ++walls;
    }
    if (fr.kind == SurfaceKind::SlopedRoof) {
      const double d = fine_detail([&](double a, double b) { return tex.building(static_cast<int>(f), fr, on_face(fr, 1 + a, 1 + b)); }, 0.5);
      EXPECT_GT(d, 0.1) << "roof " << f;  // 0.13-0.15; before 0.07 (tile edges alone)
      ++roofs;
    }
  }
  EXPECT_GE(walls, 2);
  EXPECT_EQ(roofs, 2);
  // Grass and asphalt: the road passes the point of the ground layout.
  EXPECT_GT(fine_detail([&](double a, double b) { return tex.ground(20 + a, -20 + b); }, 0.5), 0.05);  // 0.09; before 0.018
  ASSERT_TRUE(s.scene.ground.road);
  const Vec2 r = s.scene.ground.road_point;
  EXPECT_GT(fine_detail([&](double a, double b) { return tex.ground(r.x() + 0.5 + a, r.y() + 0.5 + b); }, 0.3), 0.05);  // 0.10; before 0.002
}

TEST(PhotoTextures, RepeatedElementsDiffer) {
  const Fixture s;
  const PhotoTextures tex(s.scene, 3);
  // Two windows of one wall, sampled at the same place in each: glass, reflections and curtains differ.
  int pairs = 0;
  for (size_t f = 0; f < s.fm.frames.size(); ++f) {
    const FaceFrame& fr = s.fm.frames[f];
    const FacadeLayout& L = s.scene.facades[f];
    if (!L.wall || L.windows.size() < 2) continue;
    auto window = [&](const FacadeRect& w) {
      const double h = L.storey_height;  // inside the frame, left of the mullion, below the transom
      return samples([&](double a, double b) { return tex.building(static_cast<int>(f), fr, on_face(fr, w.u0 + 0.06 * h + a, -(w.z0 + 0.06 * h + b - fr.origin.z()))); },
                     0.12 * h, 0.5 * (w.z1 - w.z0));
    };
    const auto first = window(L.windows[0]);
    for (size_t w = 1; w < L.windows.size(); ++w, ++pairs) EXPECT_GT(mean_abs_difference(first, window(L.windows[w])), 0.1) << "wall " << f << " window " << w;
  }
  EXPECT_GE(pairs, 3);
  // The two slopes of the gable roof, at the same place on each: their own tiles and weathering.
  std::vector<std::vector<double>> slopes;
  for (size_t f = 0; f < s.fm.frames.size(); ++f)
    if (s.fm.frames[f].kind == SurfaceKind::SlopedRoof)
      slopes.push_back(samples([&](double a, double b) { return tex.building(static_cast<int>(f), s.fm.frames[f], on_face(s.fm.frames[f], 1 + a, 1 + b)); }, 1.5, 1.5));
  ASSERT_EQ(slopes.size(), 2u);
  EXPECT_GT(mean_abs_difference(slopes[0], slopes[1]), 0.1);
}

// What COLMAP does, in miniature: SIFT on two neighbouring raster views of the photo scene, mutual nearest
// neighbours under the ratio test, and how many agree with the true epipolar geometry (within 1.5 px).
TEST(PhotoTextures, SiftMatchesNeighbouringViews) {
  const Fixture s;
  RasterOptions ro;
  ro.textures = "photo";
  ro.seed = 3;
  const RasterRenderer renderer(s.b.mesh, ro, s.scene);
  const Camera &c0 = s.cams[0], &c1 = s.cams[1];
  cv::Mat g0, g1;
  cv::cvtColor(renderer.render(c0, 0).image, g0, cv::COLOR_BGR2GRAY);
  cv::cvtColor(renderer.render(c1, 1).image, g1, cv::COLOR_BGR2GRAY);
  const auto sift = cv::SIFT::create(2000, 3, 0.02);  // COLMAP's 2,000 features and its peak threshold
  std::vector<cv::KeyPoint> k0, k1;
  cv::Mat d0, d1;
  sift->detectAndCompute(g0, cv::noArray(), k0, d0);
  sift->detectAndCompute(g1, cv::noArray(), k1, d1);
  EXPECT_GT(k0.size(), 600u);  // 949 and 706; the textures of before gave 417 and 321
  EXPECT_GT(k1.size(), 600u);
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> m01, m10;
  matcher.knnMatch(d0, d1, m01, 2);
  matcher.knnMatch(d1, d0, m10, 2);
  // F from the known cameras: x1' F x0 = 0.
  const Eigen::Matrix3d R = c1.R * c0.R.transpose();
  const Vec3 t = c1.t - R * c0.t;
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  const Eigen::Matrix3d F = c1.K.inverse().transpose() * tx * R * c0.K.inverse();
  int mutual = 0, correct = 0;
  for (const auto& m : m01) {
    if (m.size() < 2 || m[0].distance > 0.8f * m[1].distance) continue;
    const auto& back = m10[m[0].trainIdx];
    if (back.empty() || back[0].trainIdx != m[0].queryIdx) continue;
    ++mutual;
    const Eigen::Vector3d x0(k0[m[0].queryIdx].pt.x, k0[m[0].queryIdx].pt.y, 1), x1(k1[m[0].trainIdx].pt.x, k1[m[0].trainIdx].pt.y, 1);
    const Eigen::Vector3d line = F * x0;
    if (std::abs(x1.dot(line)) / line.head<2>().norm() < 1.5) ++correct;
  }
  // 94 of 122 agree with the cameras; before 24 of 56: too few, and more wrong than right
  EXPECT_GT(correct, 70) << mutual << " mutual matches";
  EXPECT_GT(correct, 0.65 * mutual) << mutual << " mutual matches";
}

}  // namespace
}  // namespace lc2wf

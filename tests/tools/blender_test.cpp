// Blender path end to end (render -> lines -> cloud -> labels) on two small synthetic buildings, and the
// OpenCV <-> Blender camera round trip. Skipped when `blender` is not installed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "dataset/synthetic/synthetic_building.h"
#include "tools/pipeline/cloud_builder.h"
#include "tools/render/blender_renderer.h"
#include "tools/render/camera_ring.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {
namespace fs = std::filesystem;

bool have_blender() { return std::system("command -v blender > /dev/null 2>&1") == 0; }

TEST(BlenderPipeline, RendersTwoBuildingsIntoLabelledClouds) {
  if (!have_blender()) GTEST_SKIP() << "blender not found on PATH (install the Debian package: apt-get install blender python3-numpy)";
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_blender_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  RectBuildingSpec rect;
  rect.west = RoofEnd::Gable;
  const std::vector<Building> buildings = {make_rect_building("rect", rect), make_l_building("l", LBuildingSpec{})};
  std::vector<BlenderBuilding> batch;
  for (size_t i = 0; i < buildings.size(); ++i) {
    CameraRingOptions ring;
    ring.views = 16;
    ring.seed = i;
    batch.push_back({&buildings[i], make_camera_ring(buildings[i].mesh.vertices, ring), dir / buildings[i].name, i});
  }
  const auto results = render_with_blender(batch, BlenderOptions{}, dir);
  ASSERT_EQ(results.size(), 2u);
  for (size_t i = 0; i < results.size(); ++i) {
    ASSERT_TRUE(results[i].error.empty()) << results[i].error;
    ASSERT_EQ(results[i].views.size(), batch[i].cameras.size());
    // Blender's own cameras, read back in the OpenCV convention, equal the ones we asked for
    // (float32 matrices inside Blender).
    for (size_t v = 0; v < batch[i].cameras.size(); ++v) {
      const Camera& want = batch[i].cameras[v];
      const Camera& got = results[i].views[v].camera;
      EXPECT_LT((want.K - got.K).cwiseAbs().maxCoeff(), 1e-3);
      EXPECT_LT((want.R - got.R).cwiseAbs().maxCoeff(), 1e-5);
      EXPECT_LT((want.t - got.t).cwiseAbs().maxCoeff(), 1e-4);
    }
    EXPECT_TRUE(fs::exists(batch[i].out_dir / "views.json"));
    const LineCloud cloud = build_line_cloud(buildings[i], results[i].views, CloudBuilderOptions{});
    const auto& wf = cloud.wireframe;
    std::vector<char> covered(wf.edges.size(), 0);
    for (const auto& l : cloud.labels)
      for (size_t e = 0; l.f && e < wf.edges.size(); ++e)
        if ((wf.edges[e][0] == l.i1 && wf.edges[e][1] == l.i2) || (wf.edges[e][0] == l.i2 && wf.edges[e][1] == l.i1)) covered[e] = 1;
    EXPECT_GE(std::count(covered.begin(), covered.end(), 1), static_cast<long>(0.6 * wf.edges.size())) << buildings[i].name;
  }
}

// The photo scene reaches Blender: walls with windows, clutter objects, the per-view exposure, the material detail.
TEST(BlenderPipeline, PhotoScenesRenderWithClutterAndWindows) {
  if (!have_blender()) GTEST_SKIP() << "blender not found on PATH (install the Debian package: apt-get install blender python3-numpy)";
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_blender_photo_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  RectBuildingSpec spec;
  spec.eave_height = 6.5;
  const Building b = make_rect_building("photo", spec);
  CameraRingOptions ring;
  ring.views = 3;
  const auto cams = make_camera_ring(b.mesh.vertices, ring);
  std::vector<Vec3> centres;
  for (const Camera& c : cams) centres.push_back(c.center());
  const PhotoScene scene = make_photo_scene(b.mesh, centres, PhotoOptions{}, 11);
  ASSERT_FALSE(scene.clutter.faces.empty());
  BlenderOptions photo;
  photo.textures = "photo";
  const auto with_scene = render_with_blender({{&b, cams, dir / "photo", 11, &scene}}, photo, dir);
  const auto paper = render_with_blender({{&b, cams, dir / "paper", 11}}, BlenderOptions{}, dir);
  ASSERT_TRUE(with_scene[0].error.empty()) << with_scene[0].error;
  ASSERT_TRUE(paper[0].error.empty()) << paper[0].error;
  // Material detail: SIFT (COLMAP's 2,000 features and peak threshold) finds features all over a photo
  // render: 1,231 / 2,000 / 1,446 on these views, where the flat colours of before gave 662 / 911 / 486.
  const auto sift = cv::SIFT::create(2000, 3, 0.02);
  for (size_t v = 0; v < cams.size(); ++v) {
    EXPECT_GT(cv::norm(with_scene[0].views[v].image, paper[0].views[v].image, cv::NORM_L1), 0.0) << v;
    cv::Mat grey;
    cv::cvtColor(with_scene[0].views[v].image, grey, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> keypoints;
    sift->detect(grey, keypoints);
    EXPECT_GT(keypoints.size(), 1000u) << "view " << v;
  }
  fs::remove_all(dir);
}

TEST(BlenderPipeline, AFailingBlenderIsReportedPerBuilding) {
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_blender_fail_" + std::to_string(getpid()));
  fs::remove_all(dir);
  const Building b = make_rect_building("rect", RectBuildingSpec{});
  CameraRingOptions ring;
  ring.views = 2;
  BlenderOptions o;
  o.executable = "/nonexistent/blender";
  const auto r = render_with_blender({{&b, make_camera_ring(b.mesh.vertices, ring), dir / "rect", 0}}, o, dir);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].views.empty());
  EXPECT_THAT(r[0].error, HasSubstr("/nonexistent/blender")) << r[0].error;
}

}  // namespace
}  // namespace lc2wf

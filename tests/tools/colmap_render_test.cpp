// COLMAP on Blender renders end to end: a small synthetic building rendered with the SfM textures, poses
// from COLMAP's mapper, compared with the cameras Blender rendered from; every third photo turned sideways (its
// own size and intrinsics, a second COLMAP camera), as a phone held upright for a tall facade; then again with
// focal lengths 12 % off and refined by bundle adjustment. Skipped when blender or colmap is not installed.
// 10 views and 2,000 features keep each COLMAP run near 10 s on 2 cores.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "dataset/synthetic/synthetic_building.h"
#include "tools/colmap/colmap_poses.h"
#include "tools/render/blender_renderer.h"
#include "tools/render/camera_ring.h"
#include "tests/common/turned_camera.h"

namespace lc2wf {
namespace {
namespace fs = std::filesystem;

bool on_path(const std::string& exe) { return std::system(("command -v " + exe + " > /dev/null 2>&1").c_str()) == 0; }

TEST(ColmapOnRenders, SfmTexturesGiveAccuratePoses) {
  if (!on_path("blender")) GTEST_SKIP() << "blender not found on PATH (apt-get install blender python3-numpy)";
  if (!on_path("colmap")) GTEST_SKIP() << "colmap not found on PATH (apt-get install colmap)";
  // Per process: several checkouts on one machine share the temporary folder.
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_colmap_render_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  const Building building = make_l_building("l", LBuildingSpec{});
  CameraRingOptions ring;
  ring.views = 10;
  ring.seed = 3;
  BlenderOptions blender;
  blender.textures = "sfm";
  blender.threads = 2;
  const auto rendered = render_with_blender({{&building, make_camera_ring(building.mesh.vertices, ring), dir / "l", 7}}, blender, dir);
  ASSERT_EQ(rendered.size(), 1u);
  ASSERT_TRUE(rendered[0].error.empty()) << rendered[0].error;
  std::vector<fs::path> images;
  std::vector<Camera> reference;
  std::vector<Eigen::Matrix3d> K;
  for (size_t i = 0; i < rendered[0].views.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%03zu.png", i);
    images.push_back(dir / "l" / name);
    reference.push_back(rendered[0].views[i].camera);
    if (i % 3 == 1) {
      cv::Mat image = cv::imread(images.back().string(), cv::IMREAD_COLOR);
      ASSERT_FALSE(image.empty()) << images.back();
      cv::rotate(image, image, cv::ROTATE_90_CLOCKWISE);
      images.back() = dir / "l" / ("sideways_" + std::string(name));
      ASSERT_TRUE(cv::imwrite(images.back().string(), image));
      reference.back() = test::turned_clockwise(reference.back());
    }
    K.push_back(reference.back().K);
  }
  ColmapOptions colmap;
  colmap.threads = 2;
  colmap.max_features = 2000;  // matching cost grows with the square of the feature count
  auto run = estimate_poses_with_colmap(images, K, dir / "colmap", colmap);
  const PoseComparison pc = align_to_reference(reference, run.cameras);
  EXPECT_GE(pc.registered, static_cast<int>(0.8 * ring.views + 0.5));
  EXPECT_LT(pc.median_rotation_deg, 1.0);
  EXPECT_LT(pc.median_centre_error, 0.02 * pc.camera_distance) << "camera distance " << pc.camera_distance;
  for (size_t i = 0; i < images.size(); ++i) {  // each photo registered with its own intrinsics and size
    if (!run.cameras[i]) continue;
    EXPECT_LT((run.cameras[i]->K - K[i]).norm(), 1e-6) << images[i];
    EXPECT_EQ(run.cameras[i]->width, reference[i].width) << images[i];
  }
  int sideways_registered = 0;
  for (size_t i = 1; i < images.size(); i += 3) sideways_registered += run.cameras[i].has_value();
  EXPECT_GE(sideways_registered, 2);

  // Photos whose focal length is a guess (no EXIF; 12 % too long here): bundle adjustment refines it.
  std::vector<Eigen::Matrix3d> guessed = K;
  for (Eigen::Matrix3d& k : guessed) k(0, 0) *= 1.12, k(1, 1) *= 1.12;
  colmap.refine_focal_length = true;
  auto refined = estimate_poses_with_colmap(images, guessed, dir / "colmap_refined", colmap);
  EXPECT_FALSE(run.focal_refined);
  EXPECT_TRUE(refined.focal_refined);
  const PoseComparison pr = align_to_reference(reference, refined.cameras);
  EXPECT_GE(pr.registered, static_cast<int>(0.8 * ring.views + 0.5));
  EXPECT_LT(pr.median_rotation_deg, 1.0);
  std::vector<double> focal_error;
  for (size_t i = 0; i < images.size(); ++i)
    if (refined.cameras[i]) focal_error.push_back(std::abs(refined.cameras[i]->K(0, 0) / K[i](0, 0) - 1));
  ASSERT_FALSE(focal_error.empty());
  std::sort(focal_error.begin(), focal_error.end());
  EXPECT_LT(focal_error[focal_error.size() / 2], 0.03) << "median relative focal error after refinement (12 % before)";
  std::printf("refined: registered %d/%d, rotation median %.3f deg, focal error median %.2f %%\n", pr.registered, pr.reference,
              pr.median_rotation_deg, 100 * focal_error[focal_error.size() / 2]);
  for (const auto& [step, seconds] : run.step_seconds) std::printf("%s: %.1f s\n", step.c_str(), seconds);
  std::printf("registered %d/%d, rotation median %.3f max %.3f deg, centre median %.4f max %.4f (camera distance %.2f)\n", pc.registered,
              pc.reference, pc.median_rotation_deg, pc.max_rotation_deg, pc.median_centre_error, pc.max_centre_error,
              pc.camera_distance);
  if (!HasFailure()) fs::remove_all(dir);  // kept for inspection when something failed
}

}  // namespace
}  // namespace lc2wf

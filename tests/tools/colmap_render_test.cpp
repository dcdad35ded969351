// COLMAP on Blender renders end to end: a small synthetic building rendered with the SfM textures, poses
// from COLMAP's mapper, compared with the cameras Blender rendered from. Skipped when blender or colmap
// is not installed. 10 views and 2,000 features keep it near 30 s of CPU (53 s wall at load 5 on 2 cores).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "dataset/synthetic/synthetic_building.h"
#include "tools/colmap/colmap_poses.h"
#include "tools/render/blender_renderer.h"
#include "tools/render/camera_ring.h"

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
  for (size_t i = 0; i < rendered[0].views.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%03zu.png", i);
    images.push_back(dir / "l" / name);
    reference.push_back(rendered[0].views[i].camera);
  }
  ColmapOptions colmap;
  colmap.threads = 2;
  colmap.max_features = 2000;  // matching cost grows with the square of the feature count
  auto run = estimate_poses_with_colmap(images, reference.front().K, dir / "colmap", colmap);
  const PoseComparison pc = align_to_reference(reference, run.cameras);
  EXPECT_GE(pc.registered, static_cast<int>(0.8 * ring.views + 0.5));
  EXPECT_LT(pc.median_rotation_deg, 1.0);
  EXPECT_LT(pc.median_centre_error, 0.02 * pc.camera_distance) << "camera distance " << pc.camera_distance;
  for (const auto& [step, seconds] : run.step_seconds) std::printf("%s: %.1f s\n", step.c_str(), seconds);
  std::printf("registered %d/%d, rotation median %.3f max %.3f deg, centre median %.4f max %.4f (camera distance %.2f)\n", pc.registered,
              pc.reference, pc.median_rotation_deg, pc.max_rotation_deg, pc.median_centre_error, pc.max_centre_error,
              pc.camera_distance);
  if (!HasFailure()) fs::remove_all(dir);  // kept for inspection when something failed
}

}  // namespace
}  // namespace lc2wf

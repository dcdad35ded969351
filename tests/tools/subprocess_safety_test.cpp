// External programs (Blender, COLMAP) are started from an argument vector, never a shell string, and never
// delete a folder the user named. Stand-in programs record what they were given, so these tests need
// neither Blender nor COLMAP.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "dataset/synthetic/synthetic_building.h"
#include "tools/colmap/colmap_poses.h"
#include "tools/render/blender_renderer.h"
#include "tools/render/camera_ring.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

class SubprocessSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    // Quotes, spaces and a shell metacharacter in the folder name: a shell string would split or run them.
    dir_ = fs::path(::testing::TempDir()) / ("lc2wf it's \"quoted\" $(touch pwned) " + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // An executable shell script that writes each argument on its own line to `record`, then exits `code`.
  fs::path stand_in(const std::string& name, const fs::path& record, int code) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << "#!/bin/sh\nfor a in \"$@\"; do printf '%s\\n' \"$a\"; done >> '" << record.string() << "'\nexit " << code << "\n";
    fs::permissions(p, fs::perms::owner_all);
    return p;
  }

  static std::vector<std::string> lines(const fs::path& p) {
    std::ifstream in(p);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  }

  fs::path dir_;
};

TEST_F(SubprocessSafety, BlenderGetsItsArgumentsVerbatim) {
  const fs::path record = fs::path(::testing::TempDir()) / ("blender_args_" + std::to_string(::getpid()));
  fs::remove(record);
  const Building building = make_rect_building("house", RectBuildingSpec{});
  CameraRingOptions ring;
  ring.views = 3;
  std::vector<BlenderBuilding> batch = {{&building, make_camera_ring(building.mesh.vertices, ring), dir_ / "house", 1}};
  BlenderOptions options;
  options.executable = stand_in("blender", record, 0).string();
  options.script = dir_ / "my script.py";
  const auto results = render_with_blender(batch, options, dir_ / "work");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_THAT(results[0].error, HasSubstr("no output"));  // the stand-in renders nothing
  EXPECT_THAT(lines(record), ElementsAre("-b", "--factory-startup", "--python-exit-code", "1", "--python",
                                         options.script.string(), "--", (dir_ / "work" / "job.json").string()));
  EXPECT_FALSE(fs::exists("pwned"));
  fs::remove(record);
}

TEST_F(SubprocessSafety, MissingBlenderIsAnErrorPerBuilding) {
  const Building building = make_rect_building("house", RectBuildingSpec{});
  std::vector<BlenderBuilding> batch = {{&building, {}, dir_ / "house", 1}};
  BlenderOptions options;
  options.executable = (dir_ / "no blender here").string();
  const auto results = render_with_blender(batch, options, dir_ / "work");
  EXPECT_THAT(results.at(0).error, HasSubstr("could not start Blender"));
}

TEST_F(SubprocessSafety, ColmapNeverDeletesItsWorkspace) {
  // A workspace holding the user's own files (e.g. the photo folder itself): a failing run leaves them.
  const fs::path workspace = dir_ / "photos";
  fs::create_directories(workspace);
  std::ofstream(workspace / "IMG_0001.jpg") << "not really a photo";
  std::ofstream(workspace / "notes.txt") << "mine";
  const fs::path record = fs::path(::testing::TempDir()) / ("colmap_args_" + std::to_string(::getpid()));
  fs::remove(record);
  ColmapOptions options;
  options.executable = stand_in("colmap", record, 1).string();
  try {
    estimate_poses_with_colmap({workspace / "IMG_0001.jpg"}, Eigen::Matrix3d::Identity(), workspace, options);
    FAIL() << "a failing COLMAP must throw";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("feature_extractor failed"));
  }
  EXPECT_TRUE(fs::exists(workspace / "IMG_0001.jpg"));
  EXPECT_TRUE(fs::exists(workspace / "notes.txt"));
  const std::vector<std::string> args = lines(record);
  ASSERT_GE(args.size(), 4u);
  EXPECT_EQ(args[0], "feature_extractor");
  EXPECT_EQ(args[2], (workspace / "database.db").string());  // one argument, spaces and quotes included
  fs::remove(record);
}

}  // namespace
}  // namespace lc2wf

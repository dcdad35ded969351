// lc2wf-dataset and lc2wf-colmap-poses as a user runs them: help, argument errors, exit codes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/common/run_cli.h"

namespace {
namespace fs = std::filesystem;

using lc2wf::testing::CliResult;

// Both streams in `out`: the tests look for a message wherever the program printed it.
CliResult run(const std::string& cmd) {
  CliResult r = lc2wf::testing::run_cli(cmd);
  r.out += r.err;
  return r;
}

const std::string kDataset = LC2WF_DATASET_EXE;
const std::string kColmap = LC2WF_COLMAP_POSES_EXE;

TEST(DatasetCli, HelpAndArgumentErrors) {
  CliResult r = run(kDataset + " --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("--renderer raster|blender"), std::string::npos);
  r = run(kDataset + " --meshes m --out o --views many");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("--views expects an integer"), std::string::npos) << r.out;
  r = run(kDataset + " --meshes m --out o --shard 3/2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("shard"), std::string::npos) << r.out;
  r = run(kDataset + " --out o");
  EXPECT_EQ(r.code, 2);
  r = run(kDataset + " --meshes m --out o --renderer blender --textures photo");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("--textures must be paper or sfm"), std::string::npos) << r.out;
  r = run(kDataset + " --meshes /nonexistent/meshes --out " + testing::TempDir() + "/cli_out_" + std::to_string(getpid()));
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.out.find("/nonexistent/meshes"), std::string::npos) << r.out;
}

TEST(DatasetCli, FailedBuildingGivesExitCodeOneAndASummary) {
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_fail_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "bad.polyshape") << "# Number of verts: 2\n0,0,0\n";
  const CliResult r = run(kDataset + " --meshes " + (dir / "meshes").string() + " --out " + (dir / "out").string() + " --no-progress");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("\"failed\""), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "out" / "status" / "bad.json"));
}

TEST(ColmapPosesCli, HelpAndMissingInputs) {
  CliResult r = run(kColmap + " --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("--intrinsics"), std::string::npos);
  r = run(kColmap + " --views /nonexistent/views");
  EXPECT_EQ(r.code, 2);
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_colmap_" + std::to_string(getpid()));
  fs::create_directories(dir);
  r = run(kColmap + " --views " + dir.string() + " --intrinsics 600,600,319.5,239.5 --matcher vocab");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("exhaustive or sequential"), std::string::npos) << r.out;
  r = run(kColmap + " --views " + dir.string() + " --intrinsics 600,600,319.5,239.5 --outlier-factor x");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("--outlier-factor expects a number"), std::string::npos) << r.out;
  r = run(kColmap + " --views " + dir.string() + " --intrinsics 600,600,319.5,239.5");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.out.find("fewer than 3 images"), std::string::npos) << r.out;
}

}  // namespace

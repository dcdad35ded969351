// lc2wf-dataset and lc2wf-colmap-poses as a user runs them: help, argument errors, exit codes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/common/run_cli.h"

using ::testing::HasSubstr;
using ::testing::Not;

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
  EXPECT_THAT(r.out, HasSubstr("--renderer raster|blender"));
  r = run(kDataset + " --meshes m --out o --views many");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("--views expects an integer")) << r.out;
  r = run(kDataset + " --meshes m --out o --shard 3/2");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("shard")) << r.out;
  r = run(kDataset + " --out o");
  EXPECT_EQ(r.code, 2);
  r = run(kDataset + " --meshes m --out o --renderer blender --textures oil");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("--textures must be paper, sfm or photo")) << r.out;
  r = run(kDataset + " --meshes m --out o --textures photo --photo-storey 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("--photo-storey")) << r.out;
  r = run(kDataset + " --meshes m --out o --textures photo --photo-exposure 9");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("--photo-exposure")) << r.out;
  r = run(kDataset + " --meshes m --out o --textures photo --photo-without trees,cows");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("--photo-without: unknown element 'cows'")) << r.out;
  r = run(kDataset + " --meshes m --out o --capture street-3");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("--capture must be orbit, street-1, street-2 or walk, got 'street-3'")) << r.out;
  EXPECT_THAT(r.out, Not(HasSubstr("DatasetRunOptions"))) << r.out;
  r = run(kDataset + " --meshes /nonexistent/meshes --out " + testing::TempDir() + "/cli_out_" + std::to_string(getpid()));
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.out, HasSubstr("/nonexistent/meshes")) << r.out;
}

TEST(DatasetCli, FailedBuildingGivesExitCodeOneAndASummary) {
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_fail_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "bad.polyshape") << "# Number of verts: 2\n0,0,0\n";
  const CliResult r = lc2wf::testing::run_cli(kDataset + " --meshes " + (dir / "meshes").string() + " --out " + (dir / "out").string() + " -q");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_THAT(r.out, HasSubstr("\"failed\"")) << r.out;
  EXPECT_TRUE(fs::exists(dir / "out" / "status" / "bad.json"));
  // Named on stderr with its reason, also with -q (it was only in the summary).
  EXPECT_THAT(r.err, HasSubstr("lc2wf-dataset: skipped bad: load: " + (dir / "meshes" / "bad.polyshape").string())) << r.err;
}

// Regression: one hostile mesh aborted the whole run (and every re-run): a name that is not UTF-8 made the
// status writer throw inside a worker, a 245-byte name overflowed the temporary file name, a FIFO blocked
// forever and 1e155 coordinates crashed the renderer. Each is now one failed building with a status.
TEST(DatasetCli, HostileMeshesFailAloneWithAStatus) {
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_hostile_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "meshes");
  const std::string bad = "# Number of verts: 2\n0,0,0\n";
  const std::string far = "# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1e155,0,0\n0,1e155,0\n1,2,3,1\n";
  const std::vector<std::string> names = {"bad\xff", std::string(245, 'n'), "far", "fifo"};
  std::ofstream(dir / "meshes" / (names[0] + ".polyshape")) << bad;
  std::ofstream(dir / "meshes" / (names[1] + ".polyshape")) << bad;
  std::ofstream(dir / "meshes" / (names[2] + ".polyshape")) << far;
  ASSERT_EQ(::mkfifo((dir / "meshes" / "fifo.polyshape").c_str(), 0600), 0);
  const std::string cmd = kDataset + " --meshes " + (dir / "meshes").string() + " --out " + (dir / "out").string() + " -q -j 2";
  for (int pass = 0; pass < 2; ++pass) {  // a re-run redoes the failed buildings and fails the same way
    const CliResult r = run(cmd);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_THAT(r.out, HasSubstr("\"failed\"")) << r.out;
    EXPECT_THAT(r.out, HasSubstr("not a regular file")) << r.out;
    EXPECT_THAT(r.out, HasSubstr("beyond +-1e9")) << r.out;
    for (const std::string& n : names) EXPECT_TRUE(fs::exists(dir / "out" / "status" / (n + ".json"))) << n;
  }
  fs::remove_all(dir);
}

TEST(DatasetCli, AValidMeshWhoseNameIsNotUtf8IsProcessed) {
  // The cloud's header holds the building name: writing it threw nlohmann's "invalid UTF-8" and failed the
  // building with a message naming neither file nor field.
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_non_utf8_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "meshes");
  const std::string name = "caf\xff\xfe";
  std::ifstream seed(std::string(LC2WF_SOURCE_DIR) + "/tests/fuzz/corpus/polyshape/gable_box.seed");
  std::ofstream(dir / "meshes" / (name + ".polyshape")) << seed.rdbuf();
  const CliResult r = run(kDataset + " --meshes " + (dir / "meshes").string() + " --out " + (dir / "out").string() +
                          " --views 6 --size 128x96 -j 1 -q");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_GT(fs::file_size(dir / "out" / "clouds" / (name + ".lcloud")), 0u);
  fs::remove_all(dir);
}

// What was captured is in the summary and every status; a building done with another capture is redone.
TEST(DatasetCli, StreetCaptureIsRecordedAndAnotherCaptureRedoesTheBuilding) {
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_capture_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "meshes");
  std::ifstream seed(std::string(LC2WF_SOURCE_DIR) + "/tests/fuzz/corpus/polyshape/gable_box.seed");
  std::ofstream(dir / "meshes" / "box.polyshape") << seed.rdbuf();
  const std::string cmd = kDataset + " --meshes " + (dir / "meshes").string() + " --out " + (dir / "out").string() +
                          " --views 8 --size 160x120 -j 1 -q --capture ";
  CliResult r = run(cmd + "street-2");
  EXPECT_THAT(r.out, HasSubstr("\"capture\": \"street-2\"")) << r.out;
  EXPECT_THAT(r.out, HasSubstr("\"processed_this_run\": 1")) << r.out;
  std::ifstream status(dir / "out" / "status" / "box.json");
  const std::string text((std::istreambuf_iterator<char>(status)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("\"capture\": \"street-2\"")) << text;
  r = run(cmd + "street-2");
  EXPECT_THAT(r.out, HasSubstr("\"skipped_already_done\": 1")) << r.out;
  r = run(cmd + "orbit");
  EXPECT_THAT(r.out, HasSubstr("\"capture\": \"orbit\"")) << r.out;
  EXPECT_THAT(r.out, HasSubstr("\"processed_this_run\": 1")) << r.out;
  fs::remove_all(dir);
}

TEST(DatasetCli, FloatFlagsRefuseNaN) {
  for (const char* v : {"nan", "inf", "-nan"}) {
    const CliResult r = run(kDataset + " --meshes m --out o --blur " + v);
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_THAT(r.out, HasSubstr("--blur expects a finite number")) << r.out;
  }
}

TEST(ColmapPosesCli, HelpAndMissingInputs) {
  CliResult r = run(kColmap + " --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("--intrinsics"));
  r = run(kColmap + " /nonexistent/views --intrinsics 600,600,319.5,239.5");
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.out, HasSubstr("/nonexistent/views"));
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_colmap_" + std::to_string(getpid()));
  fs::create_directories(dir);
  r = run(kColmap + " " + dir.string() + " --intrinsics 600,600,319.5,239.5 --matcher vocab");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("--matcher must be exhaustive or sequential"));
  EXPECT_THAT(r.out, Not(HasSubstr("ColmapOptions")));  // the flag the user typed, not the struct field
  r = run(kColmap + " " + dir.string() + " --intrinsics 600,600,319.5,239.5 --outlier-factor x");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("--outlier-factor expects a number"));
  r = run(kColmap + " " + dir.string() + " --intrinsics 600,600,319.5,239.5");
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.out, HasSubstr("fewer than 3 images"));
}

// An entry under an image's name that is not a file is left out and named on stderr, also with -q (it was
// dropped silently); here COLMAP (/bin/false) then fails, so the run ends as a data error.
TEST(ColmapPosesCli, ASkippedImageIsNamed) {
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_colmap_skip_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "d.png");
  for (const char* name : {"a.png", "b.png", "c.png"}) std::ofstream(dir / name) << "an image";
  const CliResult r = lc2wf::testing::run_cli(kColmap + " " + dir.string() + " --intrinsics 600,600,319.5,239.5 --colmap /bin/false -q --workspace " + (dir / "ws").string() + " -o " +
                                              (dir / "cams.json").string());
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_THAT(r.err, HasSubstr("lc2wf-colmap-poses: skipped " + (dir / "d.png").string() + ": not a regular file")) << r.err;
  fs::remove_all(dir);
}

// Regression: --workspace DIR was cleared with remove_all, so naming the photo folder deleted the photos.
TEST(ColmapPosesCli, ANamedWorkspaceWithTheUsersFilesIsRefusedAndKept) {
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_colmap_ws_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* name : {"a.png", "b.png", "c.png"}) std::ofstream(dir / name) << "photo";
  const CliResult r = run(kColmap + " " + dir.string() + " --intrinsics 600,600,319.5,239.5 --workspace " + dir.string());
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.out, HasSubstr("not made by lc2wf"));
  for (const char* name : {"a.png", "b.png", "c.png"}) EXPECT_TRUE(fs::exists(dir / name)) << name;
  EXPECT_FALSE(fs::exists(dir / "cameras_colmap.json"));
  fs::remove_all(dir);
}

// Regression: errors named the options struct (TriangulatorOptions.min_best_score) instead of the flag.
TEST(DatasetCli, ErrorsNameTheFlagTheUserTyped) {
  for (const auto& [args, flag] : std::vector<std::pair<std::string, std::string>>{
           {"--min-score -1", "--min-score"}, {"--views 0", "--views"}, {"--lsd-scale 2", "--lsd-scale"},
           {"--neighbour-max-angle 200", "--neighbour-max-angle"}, {"--label-min-views 0", "--label-min-views"},
           {"--seed 12abc", "--seed"}, {"--endpoint-angle 90", "--endpoint-angle"}}) {
    const CliResult r = run(kDataset + " --meshes m -o o " + args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_THAT(r.out, HasSubstr(flag)) << args;
    EXPECT_THAT(r.out, Not(HasSubstr("Options."))) << args;
  }
}

TEST(DatasetCli, AnEmptyMeshFolderIsNothingToDo) {
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_cli_empty_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "meshes");
  const CliResult r = run(kDataset + " --meshes " + (dir / "meshes").string() + " -o " + (dir / "out").string() + " -q");
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.out, HasSubstr("nothing to do"));
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

}  // namespace

// Runs lc2wf-make-splits and lc2wf-cloud-convert: errors name the folder and the flags the user typed, and
// an output path that is not a regular file is refused and left as it was.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/util/cli.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "tests/common/run_cli.h"
#include "test_util.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// Regression: one building with --test 2 --val 1 failed as "make_splits: fewer names than test_count +
// val_count", naming neither the folder nor a flag (found by the adversarial corpus).
TEST(MakeSplitsCli, TooFewBuildingsNameTheFolderAndTheFlags) {
  const fs::path dir = test::scratch_dir("make_splits_few");
  fs::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "b.polyshape") << "0 0 0\n";
  const auto r = testing::run_argv({LC2WF_MAKE_SPLITS_BIN, "--meshes", (dir / "meshes").string(), "-o", (dir / "out").string(),
                                    "--test", "2", "--val", "1"});
  EXPECT_EQ(r.code, kExitDataError) << r.err;
  EXPECT_THAT(r.err, HasSubstr((dir / "meshes").string() + ": 1 building(s), fewer than --test 2 + --val 1"));
  EXPECT_THAT(r.err, Not(HasSubstr("test_count")));
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

// A folder named like a mesh is left out of the splits and named on stderr, also with -q (it was split as a
// building that lc2wf-dataset could never read).
TEST(MakeSplitsCli, AnEntryThatIsNotAFileIsSkippedAndNamed) {
  const fs::path dir = test::scratch_dir("make_splits_skip");
  fs::create_directories(dir / "meshes" / "odd.polyshape");
  for (const char* name : {"a", "b", "c"}) std::ofstream(dir / "meshes" / (std::string(name) + ".polyshape")) << "0 0 0\n";
  const auto r = testing::run_argv({LC2WF_MAKE_SPLITS_BIN, "--meshes", (dir / "meshes").string(), "-o", (dir / "out").string(),
                                    "--test", "1", "--val", "1", "-q"});
  EXPECT_EQ(r.code, kExitPartly) << r.err;
  EXPECT_THAT(r.err, HasSubstr("lc2wf-make-splits: skipped " + (dir / "meshes" / "odd.polyshape").string() + ": not a regular file"));
  std::ifstream train(dir / "out" / "train.txt"), val(dir / "out" / "val.txt"), test(dir / "out" / "test.txt");
  const std::string all = std::string(std::istreambuf_iterator<char>(train), {}) + std::string(std::istreambuf_iterator<char>(val), {}) +
                          std::string(std::istreambuf_iterator<char>(test), {});
  EXPECT_EQ(all.size(), 6u) << all;  // a, b and c, one per line
  EXPECT_THAT(all, Not(HasSubstr("odd")));
  fs::remove_all(dir);
}

// Regression: run as root, `lc2wf-cloud-convert CLOUD -o /dev/null` renamed its temporary file over the
// device, leaving a regular file in its place for every program on the machine (a FIFO stands in here).
TEST(CloudConvertCli, AnOutputThatIsAFifoIsRefusedAndKept) {
  const fs::path dir = test::scratch_dir("convert_fifo");
  write_line_cloud(dir / "c.lcloud", make_synthetic_line_cloud(make_rect_building("box", RectBuildingSpec{}), 1));
  ASSERT_EQ(::mkfifo((dir / "out.txt").c_str(), 0600), 0);
  const auto r = testing::run_argv({LC2WF_CLOUD_CONVERT_BIN, (dir / "c.lcloud").string(), "-o", (dir / "out.txt").string()});
  EXPECT_EQ(r.code, kExitDataError) << r.err;
  EXPECT_THAT(r.err, HasSubstr((dir / "out.txt").string() + ": is not a regular file"));
  EXPECT_TRUE(fs::is_fifo(dir / "out.txt"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf

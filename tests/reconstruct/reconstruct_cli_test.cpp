// lc2wf-reconstruct's command line: help, usage errors (2), data errors naming the stage (3), OUT untouched.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/run_cli.h"
#include "test_scene.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

const std::string kBin = LC2WF_RECONSTRUCT_BIN;

TEST(ReconstructCli, HelpAndUsageErrors) {
  const auto help = testing::run_cli(kBin + " --help");
  EXPECT_EQ(help.code, 0);
  EXPECT_THAT(help.out, HasSubstr("--known-distance"));
  EXPECT_THAT(help.out, HasSubstr("Exit codes"));
  const fs::path dir = test::scratch("cli");
  EXPECT_EQ(testing::run_cli(kBin + " " + dir.string() + " --weights w -o o --frobnicate").code, 2);
  EXPECT_EQ(testing::run_cli(kBin + " " + dir.string() + " -o o").code, 2);  // no --weights
  EXPECT_EQ(testing::run_cli(kBin + " /no/such/folder --weights w -o o").code, 3);  // a missing input is a data error
  EXPECT_EQ(testing::run_cli(kBin + " " + dir.string() + " --weights w -o o --scale -1").code, 2);
  EXPECT_EQ(testing::run_cli(kBin + " " + dir.string() + " --weights w -o o --known-distance a.png,3").code, 2);
  // sscanf reads nan and inf: they passed as a vector/intrinsics ("given_up is zero" came much later).
  for (const std::string flag : {"--up nan,0,1", "--up 0,inf,1", "--intrinsics 500,nan,320,240"}) {
    const auto r = testing::run_cli(kBin + " " + dir.string() + " --weights w -o o " + flag);
    EXPECT_EQ(r.code, 2) << flag;
    EXPECT_NE(r.err.find(flag.substr(0, flag.find(' ')) + " expects finite"), std::string::npos) << r.err;
  }
  // Regression: a zero up vector failed as "MetricFrameOptions.given_up is zero", naming no flag.
  const auto zero_up = testing::run_cli(kBin + " " + dir.string() + " --weights w -o o --up 0,0,0");
  EXPECT_EQ(zero_up.code, 2);
  EXPECT_NE(zero_up.err.find("--up '0,0,0' is the zero vector"), std::string::npos) << zero_up.err;
  EXPECT_THAT(help.out, HasSubstr("--min-confirming-views"));
  const auto negative = testing::run_cli(kBin + " " + dir.string() + " --weights w -o o --min-confirming-views -1");
  EXPECT_EQ(negative.code, 2);
  EXPECT_THAT(negative.err, HasSubstr("--min-confirming-views")) << negative.err;
  const auto angle = testing::run_cli(kBin + " " + dir.string() + " --weights w -o o --endpoint-angle -1");
  EXPECT_EQ(angle.code, 2);
  EXPECT_THAT(angle.err, HasSubstr("--endpoint-angle must be in [0, 90)")) << angle.err;
  fs::remove_all(dir);
}

TEST(ReconstructCli, MissingWeightsIsADataErrorAndOutStaysUnwritten) {
  const fs::path dir = test::scratch("cli_weights");
  fs::create_directories(dir / "images");
  const auto r = testing::run_cli(kBin + " " + (dir / "images").string() + " --weights " + (dir / "none").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.err, HasSubstr("error: weights: ")) << r.err;
  EXPECT_THAT(r.err, HasSubstr("nothing was written to")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

TEST(ReconstructCli, EmptyImageFolderNamesTheStage) {
  const fs::path dir = test::scratch("cli_images");
  fs::create_directories(dir / "images");
  test::write_tiny_weights(dir / "w");
  const auto r = testing::run_cli(kBin + " " + (dir / "images").string() + " --weights " + (dir / "w").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.err, HasSubstr("error: images: 0 readable image(s)")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf

// Loading a split's buildings: a name in the split without a cloud, or a FIFO under a building's name, is
// reported through the file the user has to fix.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "dataset/errors.h"
#include "train/building_set.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

std::string error_of(const DataConfig& data, const fs::path& split) {
  try {
    load_building_set(data, split, "data.train_split", /*quiet=*/true);
  } catch (const DataError& e) {
    return e.what();
  }
  return "no error";
}

TEST(BuildingSet, ProblemsNameTheSplitOrTheCloudFile) {
  const fs::path dir = fs::temp_directory_path() / ("lc2wf_building_set_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "clouds");
  DataConfig data;
  data.dir = (dir / "clouds").string();
  // A split path that does not exist (a typo in the config) names the config key.
  EXPECT_EQ(error_of(data, dir / "nosuch.txt"), (dir / "nosuch.txt").string() + ": no such split file (named by data.train_split)");
  std::ofstream(dir / "split.txt") << "typo\n";
  EXPECT_EQ(error_of(data, dir / "split.txt"),
            (dir / "split.txt").string() + ": lists 'typo', but " + data.dir + ": no line-cloud file for building 'typo'");
  // A FIFO under the name was skipped, so the building looked missing; now its reader refuses it by name.
  ASSERT_EQ(::mkfifo((dir / "clouds" / "typo.lcloud").c_str(), 0600), 0);
  EXPECT_EQ(error_of(data, dir / "split.txt"), (dir / "clouds" / "typo.lcloud").string() + ": is not a regular file (a FIFO, socket or device)");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf

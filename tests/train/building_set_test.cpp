// Loading a split's buildings: a name in the split without a cloud is reported through the split file, a cloud
// that cannot be read is skipped naming the file; what training reads is kept, the 2D observations are not.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "dataset/formats/errors.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
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
  // A FIFO under the name was skipped, so the building looked missing; now its reader refuses it by name (and
  // with no other building the split has nothing to train on).
  ASSERT_EQ(::mkfifo((dir / "clouds" / "typo.lcloud").c_str(), 0600), 0);
  EXPECT_EQ(error_of(data, dir / "split.txt"), (dir / "split.txt").string() + ": none of its 1 buildings could be read; the first: typo: " +
                                                   (dir / "clouds" / "typo.lcloud").string() + ": is not a regular file (a FIFO, socket or device)");
  fs::remove_all(dir);
}

// The rendered clouds of a 30-view split hold four fifths of their memory in observations, which no training
// step reads: the set keeps segments, labels, wireframe, units and cameras (validation's edge rule) as written.
TEST(BuildingSet, KeepsWhatTrainingReadsAndDropsTheObservations) {
  const fs::path dir = fs::temp_directory_path() / ("lc2wf_building_set_keep_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "clouds");
  const LineCloud written = make_synthetic_line_cloud(make_rect_building("rect", RectBuildingSpec{}), 7);
  ASSERT_FALSE(written.support.empty());
  ASSERT_FALSE(written.cameras.empty());
  ASSERT_FALSE(written.labels.empty());
  write_line_cloud(dir / "clouds" / "rect.lcloud", written);
  std::ofstream(dir / "split.txt") << "rect\n";
  DataConfig data;
  data.dir = (dir / "clouds").string();
  const BuildingSet set = load_building_set(data, dir / "split.txt", "data.train_split", /*quiet=*/true);
  ASSERT_EQ(set.clouds.size(), 1u);
  const LineCloud& kept = set.clouds[0];
  const LineCloud read = read_line_cloud(dir / "clouds" / "rect.lcloud");
  EXPECT_EQ(kept.name, "rect");
  EXPECT_TRUE(kept.support.empty());
  EXPECT_EQ(kept.cameras.size(), read.cameras.size());
  EXPECT_EQ(segments_fingerprint(kept), segments_fingerprint(read));
  EXPECT_TRUE(kept.labels == read.labels);
  EXPECT_EQ(kept.wireframe.junctions.size(), read.wireframe.junctions.size());
  EXPECT_EQ(kept.wireframe.edges.size(), read.wireframe.edges.size());
  EXPECT_EQ(kept.units.raw_per_metre, read.units.raw_per_metre);
  validate_line_cloud(kept, "kept");  // an empty support list is a valid cloud
  fs::remove_all(dir);
}

// A bad cloud among good ones is skipped with the reader's message (lc2wf-train names it and exits 1).
TEST(BuildingSet, SkipsAnUnreadableCloudNamingIt) {
  const fs::path dir = fs::temp_directory_path() / ("lc2wf_building_set_skip_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "clouds");
  write_line_cloud(dir / "clouds" / "rect.lcloud", make_synthetic_line_cloud(make_rect_building("rect", RectBuildingSpec{}), 7));
  std::ofstream(dir / "clouds" / "broken.lcloud") << "not a cloud";
  LineCloud empty = make_synthetic_line_cloud(make_rect_building("empty", RectBuildingSpec{}), 7);
  empty.segments.clear(), empty.labels.clear(), empty.support.clear();
  write_line_cloud(dir / "clouds" / "empty.lcloud", empty);
  std::ofstream(dir / "split.txt") << "broken\nrect\nempty\n";
  DataConfig data;
  data.dir = (dir / "clouds").string();
  const BuildingSet set = load_building_set(data, dir / "split.txt", "data.train_split", /*quiet=*/true);
  ASSERT_EQ(set.clouds.size(), 1u);
  EXPECT_EQ(set.clouds[0].name, "rect");
  ASSERT_EQ(set.skipped.size(), 2u);
  EXPECT_EQ(set.skipped[0].rfind("broken: " + (dir / "clouds" / "broken.lcloud").string(), 0), 0u) << set.skipped[0];
  EXPECT_EQ(set.skipped[1], "empty: " + (dir / "clouds" / "empty.lcloud").string() + ": line cloud has no segments (cannot be trained on)");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf

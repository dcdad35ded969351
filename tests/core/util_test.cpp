// core/util: workspaces that never delete a folder the user named, the shared hash, median and quantile, items over threads.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "core/util/fnv1a.h"
#include "core/util/median.h"
#include "core/util/quantile.h"
#include "core/util/parallel_items.h"
#include "core/util/workspace.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("lc2wf_util_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

TEST(Workspace, AFolderWithTheUsersFilesIsRefusedAndLeftAlone) {
  const fs::path photos = scratch("photos");
  fs::create_directories(photos);
  std::ofstream(photos / "IMG_0001.jpg") << "photo";
  try {
    Workspace ws(photos, false);
    FAIL() << "a non-empty folder without the marker was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("not made by lc2wf"));
  }
  EXPECT_TRUE(fs::exists(photos / "IMG_0001.jpg"));
  EXPECT_FALSE(fs::exists(photos / Workspace::kMarker));
  fs::remove_all(photos);
}

TEST(Workspace, ANamedFolderIsMarkedReusedAndNeverDeleted) {
  const fs::path named = scratch("named");
  {
    Workspace ws(named, false);
    EXPECT_FALSE(ws.removed_at_exit());
    std::ofstream(ws.root() / "database.db") << "colmap";
  }
  ASSERT_TRUE(fs::exists(named / "database.db"));
  EXPECT_TRUE(fs::exists(named / Workspace::kMarker));
  Workspace again(named, false);  // an earlier run's folder is accepted
  EXPECT_EQ(again.root(), named);
  fs::remove_all(named);
}

TEST(Workspace, APrivateFolderIsRemovedUnlessKept) {
  fs::path removed, kept;
  {
    Workspace ws({}, false);
    removed = ws.root();
    Workspace keep({}, false);
    keep.keep();
    kept = keep.root();
    EXPECT_TRUE(fs::is_directory(ws.staging()));
  }
  EXPECT_FALSE(fs::exists(removed));
  EXPECT_TRUE(fs::exists(kept));
  fs::remove_all(kept);
}

TEST(Workspace, PublishCopiesTheStagedFiles) {
  const fs::path out = scratch("publish");
  Workspace ws({}, false);
  std::ofstream(ws.staging() / "b.txt") << "B";
  std::ofstream(ws.staging() / "a.txt") << "A";
  EXPECT_THAT(ws.publish(out), ::testing::ElementsAre("a.txt", "b.txt"));
  std::ifstream in(out / "b.txt");
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), "B");
  fs::remove_all(out);
}

TEST(Fnv1a, MatchesTheReferenceValues) {
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ull);
}

TEST(Median, OddEvenAndEmpty) {
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(median({3, 1, 2}), 2.0);
  EXPECT_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_EQ(median({5}), 5.0);
}

TEST(Quantile, NearestRankOfTheSortedValues) {
  EXPECT_EQ(quantile({}, 0.5), 0.0);
  const std::vector<double> v{50, 10, 40, 20, 30};  // sorted 10 20 30 40 50: rank round(q * 4)
  EXPECT_EQ(quantile(v, 0.0), 10.0);
  EXPECT_EQ(quantile(v, 1.0), 50.0);
  EXPECT_EQ(quantile(v, 0.5), 30.0);
  EXPECT_EQ(quantile(v, 0.3), 20.0);   // rank 1.2 -> 1
  EXPECT_EQ(quantile(v, 0.4), 30.0);   // rank 1.6 -> 2
  EXPECT_EQ(quantile(v, -1.0), 10.0);  // q clamped to [0, 1]
  EXPECT_EQ(quantile(v, 2.0), 50.0);
  EXPECT_EQ(quantile({7}, 0.9), 7.0);
}

TEST(ForEachItem, EveryItemOnceAtAnyThreadCount) {
  for (int threads : {1, 2, 7}) {
    std::vector<std::atomic<int>> done(1000);
    for_each_item(1000, threads, [&](int64_t i) { ++done[static_cast<size_t>(i)]; }, 9);
    for (size_t i = 0; i < done.size(); ++i) ASSERT_EQ(done[i].load(), 1) << "item " << i << ", " << threads << " threads";
  }
  for_each_item(0, 4, [](int64_t) { FAIL() << "no item to do"; });
}

TEST(ForEachItem, AnItemsExceptionReachesTheCaller) {
  std::atomic<int> started{0};
  EXPECT_THROW(for_each_item(10000, 3, [&](int64_t i) {
    ++started;
    if (i == 17) throw std::runtime_error("item 17");
  }, 4), std::runtime_error);
  EXPECT_LT(started.load(), 10000) << "the other threads stop at their next chunk";
}

}  // namespace
}  // namespace lc2wf

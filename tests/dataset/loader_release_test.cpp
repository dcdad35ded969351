#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <set>
#include <thread>

#include "dataset/sampling/batch_loader.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/release_json.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

struct Record {
  std::vector<size_t> items;
  uint64_t seed = 0;
};

std::vector<Record> run_epoch(int workers, int epoch, bool drop_last) {
  LoaderOptions o;
  o.batch_size = 3;
  o.workers = workers;
  o.drop_last = drop_last;
  BatchLoader<Record> loader(10, [](const std::vector<size_t>& items, uint64_t seed) { return Record{items, seed}; }, o);
  loader.start_epoch(epoch);
  std::vector<Record> out;
  while (auto b = loader.next()) out.push_back(*b);
  return out;
}

TEST(BatchLoader, SameSequenceForAnyWorkerCount) {
  const auto a = run_epoch(1, 0, false), b = run_epoch(4, 0, false);
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(b.size(), 4u);
  std::multiset<size_t> all;
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].items, b[k].items);
    EXPECT_EQ(a[k].seed, b[k].seed);
    all.insert(a[k].items.begin(), a[k].items.end());
  }
  EXPECT_EQ(all.size(), 10u);
  EXPECT_EQ(std::set<size_t>(all.begin(), all.end()).size(), 10u);  // a permutation
  EXPECT_EQ(a.back().items.size(), 1u);
  EXPECT_EQ(run_epoch(2, 0, true).size(), 3u);
  // Another epoch reshuffles.
  const auto c = run_epoch(2, 1, false);
  bool differs = false;
  for (size_t k = 0; k < a.size(); ++k) differs |= a[k].items != c[k].items;
  EXPECT_TRUE(differs);
}

TEST(BatchLoader, WindowIsBounded) {
  std::atomic<int> started{0};
  LoaderOptions o;
  o.batch_size = 1;
  o.workers = 3;
  o.prefetch_batches = 2;
  BatchLoader<int> loader(20, [&](const std::vector<size_t>& items, uint64_t) { ++started; return static_cast<int>(items[0]); }, o);
  loader.start_epoch(0);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_LE(started.load(), 2);  // nothing consumed yet: at most prefetch_batches built
  int taken = 0;
  while (loader.next()) {
    ++taken;
    EXPECT_LE(started.load(), taken + 2);
  }
  EXPECT_EQ(taken, 20);
}

TEST(BatchLoader, WorkerErrorsReachTheConsumerInOrder) {
  LoaderOptions o;
  o.batch_size = 1;
  o.shuffle = false;
  BatchLoader<int> loader(5, [](const std::vector<size_t>& items, uint64_t) {
    if (items[0] == 2) throw std::runtime_error("bad building 2");
    return static_cast<int>(items[0]);
  }, o);
  loader.start_epoch(0);
  EXPECT_EQ(*loader.next(), 0);
  EXPECT_EQ(*loader.next(), 1);
  EXPECT_THROW(loader.next(), std::runtime_error);
  EXPECT_EQ(*loader.next(), 3);
  loader.start_epoch(1);  // restarting mid-way is safe
  EXPECT_EQ(*loader.next(), 0);
  LoaderOptions bad;
  bad.workers = 0;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

const char* kRelease = R"({
  "junc3DList": [[0, 0, 75], [100, 0, 75], [0, 0, 75], [0, 0, 75], [10, 10, 10], [20, 10, 10]],
  "edgeList": [[0, 1], [2, 3], [4, 5]],
  "label": [0, 1, 0, 0, -1, -1],
  "objGTJunc3D": [[0, 0, 75], [100, 0, 75], [100, 0, 0]],
  "objGTSeg3D": [[0, 0, 75, 100, 0, 75]],
  "line_idx": [[0, 1], [2, 1]]
})";

TEST(ReleaseJson, ReadsAndConvertsToMetres) {
  ReleaseJsonReport report;
  const LineCloud c = parse_release_line_cloud(kRelease, "/x/BK39_1.json", {}, &report);
  EXPECT_EQ(c.name, "BK39_1");
  EXPECT_EQ(report.dropped_zero_length, 1);
  ASSERT_EQ(c.segments.size(), 2u);
  EXPECT_NEAR((c.segments[0].b - Vec3(5, 0, 3.75)).norm(), 0, 1e-12);
  EXPECT_EQ(c.wireframe.edges, (std::vector<std::array<int, 2>>{{0, 1}, {1, 2}}));
  EXPECT_TRUE(c.labels[0].f);
  EXPECT_EQ(c.labels[0].i2, 1);
  EXPECT_DOUBLE_EQ(c.labels[0].d1, 0.0);
  EXPECT_FALSE(c.labels[1].f);
  EXPECT_EQ(c.labels[1].d1, -1.0);
  EXPECT_EQ(endpoint_labels(c), (std::vector<int>{0, 1, -1, -1}));
}

TEST(ReleaseJson, BadInputsNameTheFile) {
  auto expect_error = [](const std::string& text, const std::string& needle) {
    try {
      parse_release_line_cloud(text, "r.json");
      FAIL() << needle;
    } catch (const DataError& e) {
      EXPECT_THAT(std::string(e.what()), HasSubstr("r.json")) << e.what();
      EXPECT_THAT(std::string(e.what()), HasSubstr(needle)) << e.what();
    }
  };
  const std::string good = kRelease;
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  expect_error(good.substr(0, 40), "malformed JSON");
  expect_error("[1, 2]", "top level must be an object");
  expect_error(with("\"label\"", "\"labels\""), "missing key 'label'");
  expect_error(with("[20, 10, 10]],", "[20, 10, 10], [1, 1, 1]],"), "odd number of endpoints");
  expect_error(with("-1, -1]", "-1]"), "'label' has 5 entries for 6 endpoints");
  expect_error(with("-1, -1]", "-1, 7]"), "'label'[5] = 7 out of range");
  expect_error(with("[2, 1]", "[2, 3]"), "'line_idx' edge (2, 3) out of range");
  expect_error(with("[0, 0, 75], [100", "[0, 0], [100"), "'junc3DList'[0] must have 3 numbers");
  expect_error(with("[10, 10, 10]", "[10, \"a\", 10]"), "non-number");
  expect_error(with("[10, 10, 10]", "[10, 1e999, 10]"), "malformed JSON");  // overflow
  // An empty cloud is valid data (no segments); consumers reject it where it matters.
  EXPECT_TRUE(parse_release_line_cloud(R"({"junc3DList": [], "label": [], "objGTJunc3D": [], "line_idx": []})", "e.json").segments.empty());
}

}  // namespace
}  // namespace lc2wf

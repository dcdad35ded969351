// The tile split of real city buildings: whole tiles on one side, every source on every side, shares kept,
// the same lists from the same inputs in any order.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "dataset/splits/city_split.h"
#include "dataset/splits/tile_splits.h"

namespace lc2wf {
namespace {

// `tiles` tiles of `per_tile` buildings each, 1 km apart, in one file per source.
std::vector<TileSplitEntry> grid(const std::string& source, int tiles, int per_tile) {
  std::vector<TileSplitEntry> out;
  for (int t = 0; t < tiles; ++t)
    for (int b = 0; b < per_tile; ++b)
      out.push_back({source + "_" + std::to_string(t) + "_" + std::to_string(b), source, source + ".json", 1000.0 * t + 3 * b, 17.0});
  return out;
}

std::string split_of(const Splits& s, const std::string& name) {
  if (std::binary_search(s.test.begin(), s.test.end(), name)) return "test";
  if (std::binary_search(s.val.begin(), s.val.end(), name)) return "val";
  if (std::binary_search(s.train.begin(), s.train.end(), name)) return "train";
  return "";
}

TEST(TileSplits, WholeTilesPerSideEverySourceOnEverySide) {
  std::vector<TileSplitEntry> all = grid("a", 40, 5);
  const auto b = grid("b", 25, 3);
  all.insert(all.end(), b.begin(), b.end());
  TileSplitRule rule;
  rule.test_share = 0.1;
  rule.val_share = 0.1;
  const Splits s = make_tile_splits(all, rule);
  EXPECT_EQ(s.train.size() + s.val.size() + s.test.size(), all.size());
  std::map<std::string, std::set<std::string>> sides_of_tile;
  std::map<std::string, std::set<std::string>> sides_of_source;
  for (const TileSplitEntry& e : all) {
    const std::string side = split_of(s, e.name);
    ASSERT_FALSE(side.empty()) << e.name;
    sides_of_tile[tile_key(e, rule.tile_size_m)].insert(side);
    sides_of_source[e.source].insert(side);
  }
  for (const auto& [tile, sides] : sides_of_tile) EXPECT_EQ(sides.size(), 1u) << tile;
  for (const auto& [source, sides] : sides_of_source) EXPECT_EQ(sides.size(), 3u) << source;
  // Shares: the first tile that reaches a share closes it, so each side is within one tile above it.
  EXPECT_GE(s.test.size(), 20u + 8u);
  EXPECT_LE(s.test.size(), 25u + 12u);
}

TEST(TileSplits, SameListsInAnyInputOrderAndSeedMatters) {
  std::vector<TileSplitEntry> all = grid("a", 30, 4);
  std::vector<TileSplitEntry> reversed(all.rbegin(), all.rend());
  const Splits s1 = make_tile_splits(all), s2 = make_tile_splits(reversed);
  EXPECT_EQ(s1.test, s2.test);
  EXPECT_EQ(s1.val, s2.val);
  EXPECT_EQ(s1.train, s2.train);
  TileSplitRule other;
  other.seed = 7;
  EXPECT_NE(make_tile_splits(all, other).test, s1.test);
}

TEST(TileSplits, ASourceOfOneTileGoesWholeToTest) {
  std::vector<TileSplitEntry> all = grid("a", 30, 4);
  const auto tiny = grid("tiny", 1, 3);
  all.insert(all.end(), tiny.begin(), tiny.end());
  const Splits s = make_tile_splits(all);
  for (const auto& e : tiny) EXPECT_EQ(split_of(s, e.name), "test");
}

TEST(TileSplits, BadInputIsNamed) {
  auto all = grid("a", 2, 2);
  all.push_back(all.front());
  EXPECT_THROW(make_tile_splits(all), std::invalid_argument);
  auto nan = grid("a", 2, 2);
  nan[1].x = std::nan("");
  EXPECT_THROW(make_tile_splits(nan), std::invalid_argument);
  TileSplitRule bad;
  bad.test_share = 0.7;
  bad.val_share = 0.4;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

TEST(TileSplits, SourceRulesFirstMatchWins) {
  const std::vector<std::string> rules = {"citygml/nrw/*=nrw", "cityjson/*vienna*=vienna", "cityjson/*=3dbag"};
  EXPECT_EQ(source_of("citygml/nrw/LoD2_32_324_5729_1_NW.gml.gz", rules), "nrw");
  EXPECT_EQ(source_of("cityjson/cjdb__vienna.jsonl", rules), "vienna");
  EXPECT_EQ(source_of("cityjson/cjdb__5870_ext.jsonl", rules), "3dbag");
  EXPECT_EQ(source_of("elsewhere/x.gml", rules), "");
  EXPECT_THROW(source_of("x", {"no-equals"}), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

namespace lc2wf {
namespace {

// The whole city split over the hand-made city models: every loadable building in exactly one split, its
// source from the rules, statistics for each source and split.
TEST(CitySplit, HandMadeCityModelsSplitByTileWithStatistics) {
  CitySplitOptions o;
  o.root = std::filesystem::path(LC2WF_SOURCE_DIR) / "tests" / "data";
  o.inputs = {o.root / "citymodels"};
  o.source_rules = {"citymodels/*.gml*=gml", "citymodels/*=json"};
  o.rule.test_share = 0.3;
  o.rule.val_share = 0.2;
  o.threads = 2;
  const CitySplitResult r = make_city_split(o);
  ASSERT_GE(r.buildings.size(), 4u);
  std::set<std::string> seen;
  for (const auto* list : {&r.splits.train, &r.splits.val, &r.splits.test})
    for (const std::string& n : *list) EXPECT_TRUE(seen.insert(n).second) << n << " in two splits";
  EXPECT_EQ(seen.size(), r.buildings.size());
  for (const CitySplitBuilding& b : r.buildings) {
    EXPECT_TRUE(b.source == "gml" || b.source == "json") << b.name << " " << b.file;
    EXPECT_FALSE(b.split.empty()) << b.name;
    EXPECT_GT(b.height_m, 0) << b.name;
    EXPECT_GE(b.long_side_m, b.short_side_m) << b.name;
    EXPECT_GT(b.edges, 0) << b.name;
  }
  const std::string md = city_split_statistics_markdown(r);
  EXPECT_NE(md.find("| gml | all |"), std::string::npos) << md;
  EXPECT_NE(md.find("| json | all |"), std::string::npos) << md;
  EXPECT_NE(md.find("| all | all | " + std::to_string(r.buildings.size()) + " |"), std::string::npos) << md;
  // Deterministic with any thread count.
  o.threads = 1;
  EXPECT_EQ(make_city_split(o).splits.test, r.splits.test);
}

}  // namespace
}  // namespace lc2wf

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>

#include "dataset/geometry/building.h"
#include "dataset/formats/errors.h"
#include "dataset/splits/splits.h"
#include "test_util.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

const std::filesystem::path kSplits = std::filesystem::path(LC2WF_SOURCE_DIR) / "configs" / "splits";

TEST(Splits, PublishedListsFollowTheRule) {
  const auto train = read_name_list(kSplits / "train.txt");
  const auto val = read_name_list(kSplits / "val.txt");
  const auto test = read_name_list(kSplits / "test.txt");
  EXPECT_EQ(test.size(), 757u);
  EXPECT_EQ(val.size(), 200u);
  EXPECT_EQ(train.size(), 2626u);
  std::vector<std::string> all = train;
  all.insert(all.end(), val.begin(), val.end());
  all.insert(all.end(), test.begin(), test.end());
  EXPECT_EQ(std::set<std::string>(all.begin(), all.end()).size(), 3583u);  // disjoint
  const Splits s = make_splits(all);
  EXPECT_EQ(s.train, train);
  EXPECT_EQ(s.val, val);
  EXPECT_EQ(s.test, test);
}

TEST(Splits, ListsCoverTheRoofImageFolder) {
  const auto dir = test::shared_data_dir() / "roof-image" / "res_building";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "Roof-Image data not found at " << dir << " (set LC2WF_DATA_DIR)";
  std::vector<std::string> all;
  for (const char* f : {"train.txt", "val.txt", "test.txt"}) {
    const auto l = read_name_list(kSplits / f);
    all.insert(all.end(), l.begin(), l.end());
  }
  std::sort(all.begin(), all.end());
  EXPECT_EQ(all, list_polyshape_names(dir));
}

TEST(Splits, KeyIsStableAndSeeded) {
  // Pinned values: changing the hash would silently move buildings between splits.
  EXPECT_EQ(split_key("BK39_500_017028_00107", 1555), 0x764AFCB4753EE0D8ull);
  EXPECT_NE(split_key("a", 1), split_key("a", 2));
  const std::vector<std::string> names = {"a", "b", "c", "d", "e"};
  SplitRule r;
  r.test_count = 2;
  r.val_count = 1;
  const Splits s = make_splits(names, r);
  EXPECT_EQ(s.test.size(), 2u);
  EXPECT_EQ(s.val.size(), 1u);
  EXPECT_EQ(s.train.size(), 2u);
  EXPECT_THROW(make_splits({"a", "a", "b", "c"}, r), std::invalid_argument);
  EXPECT_THROW(make_splits({"a", "b"}, r), std::invalid_argument);
}

TEST(Splits, NameListErrors) {
  const auto dir = test::scratch_dir("splits");
  write_name_list(dir / "x.txt", {"a", "b"});
  EXPECT_EQ(read_name_list(dir / "x.txt"), (std::vector<std::string>{"a", "b"}));
  {
    std::ofstream f(dir / "bad.txt");
    f << "# header\na\nb c\n";
  }
  try {
    read_name_list(dir / "bad.txt");
    FAIL();
  } catch (const DataError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("bad.txt:3:")) << e.what();
  }
  EXPECT_THROW(read_name_list(dir / "missing.txt"), DataError);
  // Names that would address a folder or a path cut at NUL are refused with the line.
  for (const std::string& bad : std::vector<std::string>{"..", ".", std::string("a\0b", 3)})
    EXPECT_THROW(parse_name_list("ok\n" + bad + "\n", "s.txt"), DataError) << bad;
}

}  // namespace
}  // namespace lc2wf

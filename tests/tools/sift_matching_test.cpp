// Our SIFT matcher and the COLMAP database reader: exact mutual nearest neighbours with the ratio test,
// pair lists, a match list COLMAP can import, and clear errors for databases that are not what COLMAP
// writes.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "tools/colmap/colmap_database.h"
#include "tools/colmap/sift_matching.h"

namespace lc2wf {
namespace {
namespace fs = std::filesystem;

// n random unit descriptors (non-negative, as SIFT's are).
ImageDescriptors random_descriptors(int n, uint32_t seed, const std::string& name) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  ImageDescriptors im;
  im.name = name;
  im.rows = n;
  im.descriptors.resize(static_cast<size_t>(n) * kSiftDimensions);
  for (int r = 0; r < n; ++r) {
    double norm = 0;
    float* row = im.descriptors.data() + static_cast<size_t>(r) * kSiftDimensions;
    for (int c = 0; c < kSiftDimensions; ++c) norm += (row[c] = u(rng) * u(rng) * u(rng)) * row[c];
    for (int c = 0; c < kSiftDimensions; ++c) row[c] = static_cast<float>(row[c] / std::sqrt(norm));
  }
  return im;
}

// b's feature perm[i] is a's feature i with a little noise, renormalised.
ImageDescriptors noisy_permutation(const ImageDescriptors& a, const std::vector<int>& perm, float noise, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, noise);
  ImageDescriptors b = a;
  b.name = "b.png";
  for (int i = 0; i < a.rows; ++i) {
    float* dst = b.descriptors.data() + static_cast<size_t>(perm[i]) * kSiftDimensions;
    const float* src = a.descriptors.data() + static_cast<size_t>(i) * kSiftDimensions;
    double norm = 0;
    for (int c = 0; c < kSiftDimensions; ++c) norm += (dst[c] = std::max(0.0f, src[c] + g(rng))) * dst[c];
    for (int c = 0; c < kSiftDimensions; ++c) dst[c] = static_cast<float>(dst[c] / std::sqrt(norm));
  }
  return b;
}

TEST(SiftMatching, FindsEveryPlantedMatchAcrossRowBlocks) {
  const int n = 600;  // more than one 256-row block
  const ImageDescriptors a = random_descriptors(n, 1, "a.png");
  std::vector<int> perm(n);
  for (int i = 0; i < n; ++i) perm[i] = (i * 7 + 3) % n;  // 7 is coprime with 600
  const ImageDescriptors b = noisy_permutation(a, perm, 0.01f, 2);
  const FeatureMatches m = match_descriptors(a, b, SiftMatchOptions{});
  ASSERT_EQ(m.size(), static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(m[i].first, i);
    EXPECT_EQ(m[i].second, perm[i]);
  }
}

TEST(SiftMatching, RatioTestDropsAmbiguousFeatures) {
  ImageDescriptors a = random_descriptors(50, 3, "a.png");
  std::vector<int> identity(50);
  for (int i = 0; i < 50; ++i) identity[i] = i;
  ImageDescriptors b = noisy_permutation(a, identity, 0.01f, 4);
  // b gets a second noisy copy of a's feature 10: two neighbours at about the same angle.
  const ImageDescriptors twin = noisy_permutation(a, identity, 0.01f, 5);
  b.descriptors.insert(b.descriptors.end(), twin.descriptors.begin() + 10 * kSiftDimensions,
                       twin.descriptors.begin() + 11 * kSiftDimensions);
  b.rows = 51;
  const FeatureMatches m = match_descriptors(a, b, SiftMatchOptions{});
  EXPECT_EQ(m.size(), 49u);
  for (const auto& [i, j] : m) EXPECT_NE(i, 10);
  SiftMatchOptions no_ratio;
  no_ratio.max_ratio = 1.0;  // only the strictly nearer of the two is needed now
  EXPECT_EQ(match_descriptors(a, b, no_ratio).size(), 50u);
}

TEST(SiftMatching, CrossCheckAndMaxAngleRejectOneSidedAndDistantMatches) {
  // a: two features; b: one feature close to both (b's nearest is a0): a1 -> b0 is one-sided.
  ImageDescriptors a, b;
  a.name = "a.png", b.name = "b.png";
  a.rows = 2, b.rows = 1;
  a.descriptors.assign(2 * kSiftDimensions, 0.0f);
  b.descriptors.assign(kSiftDimensions, 0.0f);
  a.descriptors[0] = 1.0f;                                                 // a0 = e0
  a.descriptors[kSiftDimensions + 0] = 0.8f, a.descriptors[kSiftDimensions + 1] = 0.6f;  // a1, 37 degrees off e0
  b.descriptors[0] = 1.0f;                                                 // b0 = e0
  FeatureMatches m = match_descriptors(a, b, SiftMatchOptions{});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0], std::make_pair(0, 0));
  SiftMatchOptions one_sided;
  one_sided.cross_check = false;
  EXPECT_EQ(match_descriptors(a, b, one_sided).size(), 2u);
  one_sided.max_angle = 0.5;  // a1 is 0.6435 rad from b0
  EXPECT_EQ(match_descriptors(a, b, one_sided).size(), 1u);
  ImageDescriptors empty;
  EXPECT_TRUE(match_descriptors(a, empty, SiftMatchOptions{}).empty());
}

TEST(SiftMatching, PairListsAreExhaustiveOrSequential) {
  EXPECT_EQ(image_pairs(4, 0), (std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}));
  EXPECT_EQ(image_pairs(4, 1), (std::vector<std::pair<int, int>>{{0, 1}, {1, 2}, {2, 3}}));
  EXPECT_EQ(image_pairs(20, 0).size(), 190u);
  EXPECT_TRUE(image_pairs(1, 0).empty());
}

fs::path temp_dir(const std::string& tag) {
  const fs::path d = fs::path(testing::TempDir()) / ("lc2wf_sift_" + tag + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(SiftMatching, MatchListHasColmapsLayoutAndIgnoresTheThreadCount) {
  const ImageDescriptors a = random_descriptors(300, 5, "000000.png");
  std::vector<int> perm(300);
  for (int i = 0; i < 300; ++i) perm[i] = 299 - i;
  ImageDescriptors b = noisy_permutation(a, perm, 0.01f, 6);
  b.name = "000001.png";
  ImageDescriptors c = random_descriptors(200, 7, "000002.png");
  const std::vector<ImageDescriptors> images = {a, b, c};
  const fs::path dir = temp_dir("list");
  SiftMatchOptions one, two;
  one.threads = 1, two.threads = 2;
  const int64_t n1 = write_match_list(images, image_pairs(3, 0), one, dir / "one.txt");
  const int64_t n2 = write_match_list(images, image_pairs(3, 0), two, dir / "two.txt");
  EXPECT_EQ(n1, n2);
  EXPECT_GE(n1, 300);
  std::ifstream f1(dir / "one.txt"), f2(dir / "two.txt");
  std::stringstream s1, s2;
  s1 << f1.rdbuf(), s2 << f2.rdbuf();
  EXPECT_EQ(s1.str(), s2.str());
  std::istringstream in(s1.str());
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "000000.png 000001.png");
  std::getline(in, line);
  EXPECT_EQ(line, "0 299");
  ImageDescriptors spaced = c;
  spaced.name = "my photo.png";
  EXPECT_THROW(write_match_list({a, spaced}, image_pairs(2, 0), one, dir / "bad.txt"), std::invalid_argument);
  EXPECT_THROW(write_match_list({a, b}, {{0, 2}}, one, dir / "bad.txt"), std::invalid_argument);
  fs::remove_all(dir);
}

// A database with COLMAP's two tables, rows of descriptors given as (name, rows, cols, bytes).
void write_database(const fs::path& path, const std::vector<std::tuple<std::string, int, int, std::vector<uint8_t>>>& images) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_exec(db,
               "CREATE TABLE images (image_id INTEGER PRIMARY KEY NOT NULL, name TEXT NOT NULL UNIQUE, camera_id INTEGER);"
               "CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB);",
               nullptr, nullptr, nullptr);
  int id = 1;
  for (const auto& [name, rows, cols, bytes] : images) {
    sqlite3_stmt* s = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO images VALUES (?, ?, 1)", -1, &s, nullptr);
    sqlite3_bind_int(s, 1, id);
    sqlite3_bind_text(s, 2, name.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_step(s);
    sqlite3_finalize(s);
    sqlite3_prepare_v2(db, "INSERT INTO descriptors VALUES (?, ?, ?, ?)", -1, &s, nullptr);
    sqlite3_bind_int(s, 1, id);
    sqlite3_bind_int(s, 2, rows);
    sqlite3_bind_int(s, 3, cols);
    sqlite3_bind_blob(s, 4, bytes.data(), static_cast<int>(bytes.size()), SQLITE_TRANSIENT);
    sqlite3_step(s);
    sqlite3_finalize(s);
    ++id;
  }
  sqlite3_close(db);
}

TEST(ColmapDatabase, ReadsUnitDescriptorsInNameOrder) {
  const fs::path dir = temp_dir("db");
  std::vector<uint8_t> two(2 * kSiftDimensions, 0), one(kSiftDimensions, 0);
  two[0] = 3, two[1] = 4;                   // row 0 -> (0.6, 0.8, 0, ...)
  two[kSiftDimensions + 5] = 200;           // row 1 -> e5
  one[127] = 1;
  write_database(dir / "database.db", {{"b.png", 2, 128, two}, {"a.png", 1, 128, one}, {"c.png", 0, 128, {}}});
  const auto images = read_colmap_descriptors(dir / "database.db");
  ASSERT_EQ(images.size(), 3u);
  EXPECT_EQ(images[0].name, "a.png");
  EXPECT_EQ(images[1].name, "b.png");
  EXPECT_EQ(images[2].rows, 0);
  EXPECT_FLOAT_EQ(images[0].descriptors[127], 1.0f);
  EXPECT_FLOAT_EQ(images[1].descriptors[0], 0.6f);
  EXPECT_FLOAT_EQ(images[1].descriptors[1], 0.8f);
  EXPECT_FLOAT_EQ(images[1].descriptors[kSiftDimensions + 5], 1.0f);
  fs::remove_all(dir);
}

void expect_error(const fs::path& db, const std::string& part) {
  try {
    read_colmap_descriptors(db);
    ADD_FAILURE() << "no error for " << db << ", expected one saying " << part;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(db.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(ColmapDatabase, BadDatabasesNameTheFileAndTheProblem) {
  const fs::path dir = temp_dir("baddb");
  expect_error(dir / "missing.db", "not found");
  std::ofstream(dir / "text.db") << "not a database\n";
  expect_error(dir / "text.db", "COLMAP database");
  write_database(dir / "cols.db", {{"a.png", 1, 64, std::vector<uint8_t>(64, 1)}});
  expect_error(dir / "cols.db", "64 columns");
  // A row count far beyond the blob: refused before anything is allocated.
  write_database(dir / "rows.db", {{"a.png", 1000000000, 128, std::vector<uint8_t>(128, 1)}});
  expect_error(dir / "rows.db", "blob holds 128 bytes");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf

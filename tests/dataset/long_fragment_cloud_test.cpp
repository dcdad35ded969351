#include "dataset/synthetic/long_fragment_cloud.h"

#include <gtest/gtest.h>

#include <map>

#include "dataset/formats/errors.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"

namespace lc2wf {
namespace {

LineCloud labelled_cloud(uint64_t seed) { return make_synthetic_line_cloud(make_random_building(seed, "b"), seed); }

TEST(LongFragmentCloud, CutsEveryEdgeIntoFewPiecesAlongIt) {
  const LineCloud c = labelled_cloud(4);
  LongFragmentOptions o;
  o.noise_m = 0.0;
  o.clutter_keep = 0.0;
  o.min_length_m = 1e-6;
  const LineCloud f = make_long_fragment_cloud(c, o, 1);
  std::map<std::pair<int, int>, int> pieces;
  std::map<std::pair<int, int>, double> covered;
  for (size_t i = 0; i < f.segments.size(); ++i) {
    const SegmentLabel& l = f.labels[i];
    ASSERT_TRUE(l.f);
    const auto key = std::make_pair(std::min(l.i1, l.i2), std::max(l.i1, l.i2));
    ++pieces[key];
    covered[key] += f.segments[i].length();
    const Vec3 a = c.wireframe.junctions[l.i1], d = (c.wireframe.junctions[l.i2] - a).normalized();
    for (const Vec3& p : {f.segments[i].a, f.segments[i].b}) EXPECT_LT(((p - a) - d.dot(p - a) * d).norm(), 1e-9);
  }
  EXPECT_EQ(pieces.size(), c.wireframe.edges.size());
  for (const auto& [j, k] : c.wireframe.edges) {
    const auto key = std::make_pair(std::min(j, k), std::max(j, k));
    EXPECT_GE(pieces[key], 2);
    EXPECT_LE(pieces[key], 5);
    const double length = (c.wireframe.junctions[j] - c.wireframe.junctions[k]).norm();
    EXPECT_GE(covered[key], (1.0 - 4 * o.gap_fraction_max) * length - 1e-9);  // at most 4 cuts' gaps
    EXPECT_LE(covered[key], length + 1e-9);
  }
  EXPECT_NO_THROW(validate_line_cloud(f, "fragments"));
}

TEST(LongFragmentCloud, KeepsTheAskedShareOfClutterAndIsDeterministic) {
  const LineCloud c = labelled_cloud(6);
  int clutter = 0;
  for (const SegmentLabel& l : c.labels) clutter += !l.f;
  ASSERT_GT(clutter, 20);
  LongFragmentOptions o;
  o.clutter_keep = 1.0;
  const LineCloud all = make_long_fragment_cloud(c, o, 2);
  int kept = 0;
  for (const SegmentLabel& l : all.labels) kept += !l.f;
  EXPECT_EQ(kept, clutter);
  o.clutter_keep = 0.0;
  for (const SegmentLabel& l : make_long_fragment_cloud(c, o, 2).labels) EXPECT_TRUE(l.f);
  const LineCloud x = make_long_fragment_cloud(c, LongFragmentOptions{}, 9), y = make_long_fragment_cloud(c, LongFragmentOptions{}, 9);
  ASSERT_EQ(x.segments.size(), y.segments.size());
  for (size_t i = 0; i < x.segments.size(); ++i) EXPECT_EQ(x.segments[i].b, y.segments[i].b);
}

TEST(LongFragmentCloud, NamesTheCloudWhenItCannotBeMade) {
  LineCloud c = labelled_cloud(1);
  c.name = "unlabelled-one";
  c.labels.clear();
  try {
    make_long_fragment_cloud(c, LongFragmentOptions{}, 1);
    FAIL() << "an unlabelled cloud was accepted";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("unlabelled-one"), std::string::npos) << e.what();
  }
  LongFragmentOptions bad;
  bad.max_pieces = 1;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

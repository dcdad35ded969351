#include "dataset/sampling/cloud_augmentation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "dataset/formats/errors.h"
#include "dataset/sampling/network_input.h"
#include "dataset/geometry/segment_split.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"

namespace lc2wf {
namespace {

CloudAugmentOptions nothing() {
  CloudAugmentOptions o;
  o.merge_prob_max = o.split_prob_max = o.densify_prob_max = o.drop_max = o.endpoint_noise_max_m = 0.0;
  return o;
}

// Distance from p to the infinite line through s.
double distance_to_line(const Vec3& p, const Segment3& s) {
  const Vec3 d = (s.b - s.a).normalized();
  return ((p - s.a) - d.dot(p - s.a) * d).norm();
}

// A square of 4 junctions; edge (0, 1) is seen as three collinear fragments, edge (1, 2) as one, plus a
// clutter segment with a one-sided label at its endpoint a.
LineCloud fragmented_square() {
  LineCloud c;
  c.name = "square";
  c.wireframe.junctions = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  c.wireframe.edges = {{0, 1}, {1, 2}, {2, 3}, {0, 3}};
  c.segments = {{{0.5, 0, 0}, {3, 0, 0}}, {{3.5, 0, 0}, {6, 0, 0}}, {{9, 0, 0}, {6.5, 0, 0}},
                {{10, 1, 0}, {10, 9, 0}}, {{0.2, 0.2, 1}, {2, 3, 1}}};
  for (int i = 0; i < 3; ++i) c.labels.push_back(make_edge_label(c.segments[i], c.wireframe, 0, 1));
  c.labels.push_back(make_edge_label(c.segments[3], c.wireframe, 1, 2));
  SegmentLabel one_sided;
  one_sided.i1 = 0;
  one_sided.d1 = (c.segments[4].a - c.wireframe.junctions[0]).norm();
  c.labels.push_back(one_sided);
  return c;
}

TEST(CloudAugmentation, ZeroStrengthKeepsTheCloud) {
  const LineCloud c = make_synthetic_line_cloud(make_random_building(3, "b"), 3);
  const LineCloud a = augment_cloud_statistics(c, nothing(), 42);
  ASSERT_EQ(a.segments.size(), c.segments.size());
  for (size_t i = 0; i < c.segments.size(); ++i) {
    EXPECT_EQ(a.segments[i].a, c.segments[i].a);
    EXPECT_EQ(a.segments[i].b, c.segments[i].b);
    EXPECT_EQ(a.labels[i].f, c.labels[i].f);
    EXPECT_EQ(a.labels[i].i1, c.labels[i].i1);
    EXPECT_EQ(a.labels[i].i2, c.labels[i].i2);
  }
  EXPECT_TRUE(a.support.empty());
  EXPECT_EQ(a.wireframe.junctions.size(), c.wireframe.junctions.size());
}

TEST(CloudAugmentation, FusesTheFragmentsOfAnEdgeIntoOneLine) {
  CloudAugmentOptions o = nothing();
  o.merge_prob_max = 1.0;
  // The merge probability is drawn in [0, 1): find a seed whose draw fuses edge (0, 1).
  for (uint64_t seed = 0; seed < 50; ++seed) {
    const LineCloud a = augment_cloud_statistics(fragmented_square(), o, seed);
    if (a.segments.size() != 3) continue;
    EXPECT_NEAR(a.segments[0].length(), 8.5, 1e-9);  // from x = 0.5 to x = 9
    EXPECT_TRUE(a.labels[0].f);
    EXPECT_EQ(std::min(a.labels[0].i1, a.labels[0].i2), 0);
    EXPECT_EQ(std::max(a.labels[0].i1, a.labels[0].i2), 1);
    EXPECT_NEAR(a.labels[0].d1 + a.labels[0].d2, 0.5 + 1.0, 1e-9);
    EXPECT_EQ(a.segments[1].a, fragmented_square().segments[3].a);  // a single fragment stays as it was
    return;
  }
  FAIL() << "no seed in 50 fused the three fragments of edge (0, 1)";
}

TEST(CloudAugmentation, SplitPiecesStayOnTheLineAndKeepOneSidedLabelsOnlyAtTheirEnd) {
  CloudAugmentOptions o = nothing();
  o.split_prob_max = 1.0;
  const LineCloud c = fragmented_square();
  int split_clutter = 0;
  for (uint64_t seed = 0; seed < 40; ++seed) {
    const LineCloud a = augment_cloud_statistics(c, o, seed);
    ASSERT_EQ(a.labels.size(), a.segments.size());
    std::map<int, int> clutter_pieces_with_label;
    for (size_t i = 0; i < a.segments.size(); ++i) {
      const SegmentLabel& l = a.labels[i];
      if (l.f) {
        const Segment3 edge{c.wireframe.junctions[l.i1], c.wireframe.junctions[l.i2]};
        EXPECT_LT(distance_to_line(a.segments[i].a, edge), 1e-9);
        EXPECT_LT(distance_to_line(a.segments[i].b, edge), 1e-9);
        EXPECT_NEAR(l.d1, (a.segments[i].a - c.wireframe.junctions[l.i1]).norm(), 1e-12);
      } else {
        EXPECT_LT(distance_to_line(a.segments[i].a, c.segments[4]), 1e-9);
        EXPECT_EQ(l.i2, -1);
        if (l.i1 == 0) {
          EXPECT_EQ(a.segments[i].a, c.segments[4].a);  // only the piece that still ends there
          ++clutter_pieces_with_label[0];
        }
      }
    }
    EXPECT_EQ(clutter_pieces_with_label[0], 1);
    if (a.segments.size() > c.segments.size()) ++split_clutter;
  }
  EXPECT_GT(split_clutter, 20);  // split probability drawn in [0, 1): most seeds split something
}

TEST(CloudAugmentation, DropsButNeverEmptiesAndIsDeterministic) {
  CloudAugmentOptions o = nothing();
  o.drop_max = 0.99;
  LineCloud one = fragmented_square();
  one.segments.resize(1);
  one.labels.resize(1);
  for (uint64_t seed = 0; seed < 20; ++seed) EXPECT_EQ(augment_cloud_statistics(one, o, seed).segments.size(), 1u);

  const LineCloud c = make_synthetic_line_cloud(make_random_building(5, "b"), 5);
  const CloudAugmentOptions all;  // every augmentation at its default strength
  const LineCloud x = augment_cloud_statistics(c, all, 7), y = augment_cloud_statistics(c, all, 7);
  const LineCloud z = augment_cloud_statistics(c, all, 8);
  ASSERT_EQ(x.segments.size(), y.segments.size());
  for (size_t i = 0; i < x.segments.size(); ++i) EXPECT_EQ(x.segments[i].a, y.segments[i].a);
  EXPECT_TRUE(x.segments.size() != z.segments.size() || x.segments[0].a != z.segments[0].a);
}

TEST(CloudAugmentation, EveryDrawGivesAValidLabelledCloud) {
  CloudAugmentOptions strong;
  strong.merge_prob_max = strong.split_prob_max = 1.0;
  strong.densify_prob_max = 1.0;
  strong.drop_max = 0.9;
  strong.endpoint_noise_max_m = 0.2;
  for (uint64_t seed = 0; seed < 30; ++seed) {
    const LineCloud c = make_synthetic_line_cloud(make_random_building(seed, "b"), seed);
    const LineCloud a = augment_cloud_statistics(c, strong, seed);
    EXPECT_NO_THROW(validate_line_cloud(a, "augmented"));
    EXPECT_FALSE(a.segments.empty());
  }
}

TEST(CloudAugmentation, ClutterAddsUnlabelledSurfaceLinesAndLeavesTheRestAsItWas) {
  const LineCloud c = make_synthetic_line_cloud(make_random_building(4, "b"), 4);
  CloudAugmentOptions o = nothing();
  o.face_clutter_max = 2.0;
  o.ground_clutter_max = 3.0;
  size_t most = 0;
  for (uint64_t seed = 0; seed < 10; ++seed) {
    const LineCloud a = augment_cloud_statistics(c, o, seed);
    EXPECT_NO_THROW(validate_line_cloud(a, "cluttered"));
    ASSERT_GE(a.segments.size(), c.segments.size());
    EXPECT_LE(a.segments.size(), c.segments.size() * 6);
    for (size_t i = 0; i < c.segments.size(); ++i) {
      EXPECT_EQ(a.segments[i].a, c.segments[i].a);
      EXPECT_EQ(a.labels[i].f, c.labels[i].f);
    }
    for (size_t i = c.segments.size(); i < a.segments.size(); ++i) {
      EXPECT_FALSE(a.labels[i].f);
      EXPECT_EQ(a.labels[i].i1, -1);
      EXPECT_EQ(a.labels[i].i2, -1);
    }
    most = std::max(most, a.segments.size() - c.segments.size());
  }
  EXPECT_GT(most, c.segments.size());  // strengths reach well above one clutter line per segment
  // The other steps draw as they did before clutter: same pieces first, clutter only appended.
  CloudAugmentOptions plain;
  CloudAugmentOptions cluttered = plain;
  cluttered.face_clutter_max = 1.0;
  const LineCloud p = augment_cloud_statistics(c, plain, 11), q = augment_cloud_statistics(c, cluttered, 11);
  ASSERT_GE(q.segments.size(), p.segments.size());
  for (size_t i = 0; i < p.segments.size(); ++i) EXPECT_EQ(p.segments[i].a, q.segments[i].a);
}

// A merged-map building: every edge's fragments fused, then cut into the staggered pieces inference cuts a
// merged line map into; a one-sided label stays only on the piece still ending at its junction.
TEST(CloudAugmentation, MergedMapsAreFusedThenCutAsInferenceCutsThem) {
  CloudAugmentOptions o = nothing();
  o.merged_map_prob = 1.0;
  LineCloud c = fragmented_square();
  c.segments[4] = {{0.2, 0.2, 1}, {2.2, 3.2, 1}};  // clutter longer than a piece: cut too
  c.labels[4].d1 = (c.segments[4].a - c.wireframe.junctions[0]).norm();
  const LineCloud a = augment_cloud_statistics(c, o, 5);
  // What inference would make of the fused map: the edge (0, 1) as one 8.5 m line, then cut.
  LineCloud fused = c;
  fused.segments = {{{0.5, 0, 0}, {9, 0, 0}}, c.segments[3], c.segments[4]};
  fused.labels.clear();
  const LineCloud expected = split_long_segments(fused, kMergedMapPieceLength);
  ASSERT_EQ(a.segments.size(), expected.segments.size());
  ASSERT_EQ(a.labels.size(), a.segments.size());
  int labelled_clutter = 0;
  for (size_t i = 0; i < a.segments.size(); ++i) {
    EXPECT_LT((a.segments[i].a - expected.segments[i].a).norm(), 1e-9);
    EXPECT_LT((a.segments[i].b - expected.segments[i].b).norm(), 1e-9);
    EXPECT_LE(a.segments[i].length(), kMergedMapPieceLength + 1e-9);
    if (!a.labels[i].f && a.labels[i].i1 == 0) {
      EXPECT_EQ(a.segments[i].a, c.segments[4].a);
      ++labelled_clutter;
    }
  }
  EXPECT_EQ(labelled_clutter, 2);  // both chains start at the clutter line's endpoint a
  // A building left as it is draws everything else as without the key (the coin has its own generator).
  CloudAugmentOptions plain;
  CloudAugmentOptions rarely = plain;
  rarely.merged_map_prob = 1e-12;
  const LineCloud syn = make_synthetic_line_cloud(make_random_building(6, "b"), 6);
  const LineCloud p = augment_cloud_statistics(syn, plain, 3), q = augment_cloud_statistics(syn, rarely, 3);
  ASSERT_EQ(p.segments.size(), q.segments.size());
  for (size_t i = 0; i < p.segments.size(); ++i) EXPECT_EQ(p.segments[i].a, q.segments[i].a);
  o.merged_map_prob = 1.5;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

TEST(CloudAugmentation, UnlabelledCloudsStayUnlabelled) {
  LineCloud c = fragmented_square();
  c.labels.clear();
  const LineCloud a = augment_cloud_statistics(c, CloudAugmentOptions{}, 1);
  EXPECT_TRUE(a.labels.empty());
  EXPECT_FALSE(a.segments.empty());
}

TEST(CloudAugmentation, RejectsBadOptionsAndEmptyClouds) {
  CloudAugmentOptions o;
  o.drop_max = 1.0;
  EXPECT_THROW(augment_cloud_statistics(fragmented_square(), o, 1), std::invalid_argument);
  o = {};
  o.endpoint_noise_max_m = std::nan("");
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.ground_clutter_max = -1.0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.clutter_length_max_m = 0.01;  // below min_length_m
  EXPECT_THROW(o.Check(), std::invalid_argument);
  LineCloud empty;
  empty.name = "empty-cloud";
  try {
    augment_cloud_statistics(empty, CloudAugmentOptions{}, 1);
    FAIL() << "an empty cloud was accepted";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("empty-cloud"), std::string::npos) << e.what();
  }
}

// Off by default: the junction sample of the paper's configuration does not change.
TEST(CloudAugmentation, JunctionSamplesChangeOnlyWhenEnabled) {
  const LineCloud c = make_synthetic_line_cloud(make_random_building(9, "b"), 9);
  JunctionSampleOptions o;
  o.patch.lines_per_patch = 16;
  o.sampling.num_samples = 8;
  const JunctionPatches plain = make_junction_sample(c, o, 3);
  o.cloud_augment = CloudAugmentOptions{};
  EXPECT_EQ(make_junction_sample(c, o, 3).features, plain.features);
  o.cloud_augment_enabled = true;
  EXPECT_NE(make_junction_sample(c, o, 3).features, plain.features);
  EXPECT_EQ(make_junction_sample(c, o, 3).features, make_junction_sample(c, o, 3).features);
}

}  // namespace
}  // namespace lc2wf

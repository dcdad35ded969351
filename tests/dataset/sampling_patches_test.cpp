#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dataset/sampling/augmentation.h"
#include "dataset/sampling/batch_loader.h"
#include "dataset/formats/errors.h"
#include "dataset/sampling/pair_sampling.h"
#include "dataset/sampling/patches.h"
#include "dataset/selection/point_nms.h"
#include "dataset/sampling/rng.h"
#include "dataset/sampling/network_input.h"
#include "dataset/sampling/sampling.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/geometry/spatial_grid.h"
#include "dataset/synthetic/synthetic_line_cloud.h"

namespace lc2wf {
namespace {

PatchOptions unit_frame(int lines, int negative) {
  PatchOptions o;
  o.lines_per_patch = lines;
  o.negative_noise_count = negative;
  o.frame.centre_m = Vec3::Zero();
  o.frame.scale_m = 1.0;
  return o;
}

TEST(Constants, ReleaseValuesInMetres) {
  const NetworkFrame f;
  EXPECT_NEAR(f.scale_m, 13.310675, 1e-6);
  EXPECT_NEAR(f.centre_m.z(), 3.525700, 1e-6);
  EXPECT_NEAR(PatchOptions{}.radius_m, 2.662135, 1e-6);
  const SamplingOptions s;
  EXPECT_DOUBLE_EQ(s.density_radius_m * 20, 6.0);
  EXPECT_DOUBLE_EQ(s.density_inner_radius_m * 20, 3.0);
  EXPECT_DOUBLE_EQ(s.seeds.nms_m * 20, 1.5);
  EXPECT_EQ(s.seeds.min_count, 12);
  EXPECT_DOUBLE_EQ(s.seeds.min_ratio, 0.7);
  EXPECT_EQ(s.num_samples, 256);
  const PairSamplingOptions p;
  EXPECT_DOUBLE_EQ(p.fp_distance_m * 20, 7.0);
  const JunctionSelectionOptions j = JunctionSelectionOptions::release();
  EXPECT_DOUBLE_EQ(j.nms_radius_m * 20, 5.0);
  EXPECT_DOUBLE_EQ(j.min_confidence, 0.85);
  EXPECT_TRUE(std::isinf(j.max_offset_m));
  EXPECT_EQ(j.top_k, 100);
  // Metres -> network units reproduces the release's (raw - MEAN) / STD.
  const Vec3 raw(100, -40, 75);
  const Vec3 release = (raw - Vec3(0.12249484, -0.3440005, 70.5140106)) / 266.2135032067564;
  EXPECT_NEAR((f.to_network(raw / 20) - release).norm(), 0, 1e-12);
}

TEST(SpatialGrid, MatchesBruteForceIncludingSparseExtents) {
  DataRng rng(2);
  std::vector<Vec3> p;
  for (int i = 0; i < 400; ++i) p.push_back(Vec3(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(0, 2)));
  p.push_back(Vec3(500, 0, 0));  // a far outlier forces the enlarged-cell path
  const SpatialGrid grid(p, 0.2);
  std::vector<int> got;
  for (int t = 0; t < 50; ++t) {
    const Vec3 q = p[rng.below(p.size())];
    for (double r : {0.2, 0.5}) {
      grid.query(q, r, got);
      std::sort(got.begin(), got.end());
      std::vector<int> want;
      int inner = 0;
      for (int i = 0; i < static_cast<int>(p.size()); ++i) {
        if ((p[i] - q).norm() <= r) want.push_back(i);
        inner += (p[i] - q).norm() <= 0.1;
      }
      EXPECT_EQ(got, want);
      int a = 0, b = 0;
      grid.count_within(q, r, 0.1, a, b);
      EXPECT_EQ(a, static_cast<int>(want.size()));
      EXPECT_EQ(b, inner);
    }
  }
  EXPECT_THROW(SpatialGrid({Vec3(0, 0, std::nan(""))}, 1.0), std::invalid_argument);
}

// Regression: a point 6e8 m away wrapped the int cell count (vector larger than max_size()), and an extent
// that overflows to inf (finite +-1.7e308 coordinates) looped forever enlarging cells.
TEST(SpatialGrid, FarAndOverflowingExtentsStayBoundedAndExact) {
  for (const double far : {6e8, 1.7e308}) {
    std::vector<Vec3> p = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(far, -far, far), Vec3(-far, far, -far)};
    const SpatialGrid grid(p, 0.01);
    std::vector<int> got;
    grid.query(p[0], 0.2, got);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, (std::vector<int>{0, 1})) << far;
    grid.query(p[2], 1.0, got);
    EXPECT_EQ(got, (std::vector<int>{2})) << far;
    int outer = 0, inner = 0;
    grid.count_within(p[1], 0.2, 0.05, outer, inner);
    EXPECT_EQ(outer, 2) << far;
    EXPECT_EQ(inner, 1) << far;
  }
}

TEST(PointNms, SuppressorRuleOnAChainKeepsOnlyTheTop) {
  const std::vector<Vec3> p = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(10, 0, 0)};
  const std::vector<double> s = {0.9, 0.8, 0.7, 0.1};
  // A-B and B-C closer than 1.5, A-C not: greedy NMS would keep C, the release rule does not.
  EXPECT_EQ(point_nms(p, s, 1.5, PointNmsRule::kSuppressor), (std::vector<int>{0, 3}));
  // Equal scores: the earlier one wins; strict <: points exactly at the radius survive.
  EXPECT_EQ(point_nms({Vec3(0, 0, 0), Vec3(0.5, 0, 0)}, {0.5, 0.5}, 1.0, PointNmsRule::kSuppressor), (std::vector<int>{0}));
  EXPECT_EQ(point_nms({Vec3(0, 0, 0), Vec3(1, 0, 0)}, {0.5, 0.6}, 1.0, PointNmsRule::kSuppressor), (std::vector<int>{1, 0}));
}

TEST(Sampling, DensitySeedsOnePerCluster) {
  std::vector<Vec3> p;
  DataRng rng(5);
  for (int c = 0; c < 2; ++c) {
    for (int k = 0; k < 15; ++k) p.push_back(Vec3(c * 1.0, 0, 0) + 0.015 * Vec3(rng.normal(), rng.normal(), rng.normal()).cwiseMin(2).cwiseMax(-2));
  }
  for (int k = 0; k < 20; ++k) p.push_back(Vec3(3 + k, 3, 0));  // sparse
  // 13 points (A = 13 > 12) form a cluster; 12 do not.
  for (int k = 0; k < 12; ++k) p.push_back(Vec3(0, 5, 0) + Vec3(0.001 * k, 0, 0));
  const auto seeds = density_seeds(p, SamplingOptions{});
  EXPECT_EQ(seeds, (std::vector<int>{0, 15}));
}

// The loose rule also seeds small clusters (A > 4) and keeps one seed per 0.3 m.
TEST(Sampling, LooseDensitySeedsTakeSmallClusters) {
  std::vector<Vec3> p;
  // Two groups of 6 endpoints 0.14 m apart (A = 12: not a release seed) leave one loose seed; 6 alone, one.
  for (int k = 0; k < 6; ++k) p.push_back(Vec3(0.001 * k, 0, 0));
  for (int k = 0; k < 6; ++k) p.push_back(Vec3(0.14 + 0.001 * k, 0, 0));
  for (int k = 0; k < 6; ++k) p.push_back(Vec3(2 + 0.001 * k, 0, 0));
  EXPECT_TRUE(density_seeds(p, SamplingOptions{}).empty());
  SamplingOptions o;
  o.seeds = DensitySeedRule::loose();
  const std::vector<int> seeds = density_seeds(p, o);
  ASSERT_EQ(seeds.size(), 2u);
  EXPECT_LT(seeds[0], 12);
  EXPECT_GE(seeds[1], 12);
}

TEST(Sampling, DensitySeedRuleText) {
  EXPECT_EQ(DensitySeedRule::release().str(), "release");
  EXPECT_EQ(DensitySeedRule::loose().str(), "loose");
  EXPECT_EQ(DensitySeedRule::parse("release"), DensitySeedRule::release());
  EXPECT_EQ(DensitySeedRule::parse("4,0.5,0.3"), DensitySeedRule::loose());
  const DensitySeedRule other = DensitySeedRule::parse("6,0.45,0.25");
  EXPECT_EQ(other.str(), "6,0.45,0.25");
  EXPECT_EQ(DensitySeedRule::parse(other.str()), other);
  for (const char* bad : {"", "dense", "4,0.5", "4,0.5,0.3,1", "4,0.5,0.3x", "4.5,0.5,0.3", "-1,0.5,0.3", "4,1.5,0.3",
                          "4,0.5,-0.1", "4,nan,0.3"}) {
    EXPECT_THROW(DensitySeedRule::parse(bad), std::invalid_argument) << bad;
  }
}

TEST(Sampling, FarthestPointSampling) {
  std::vector<Vec3> p;
  for (int i = 0; i < 10; ++i) p.push_back(Vec3(i, 0, 0));
  EXPECT_EQ(farthest_point_sampling(p, 3, {0}), (std::vector<int>{0, 9, 4}));
  EXPECT_EQ(farthest_point_sampling(p, 3, {}), (std::vector<int>{0, 9, 4}));  // no seed: starts at 0
  EXPECT_EQ(farthest_point_sampling(p, 4, {5, 5, 2}), (std::vector<int>{5, 2, 9, 0}));
  EXPECT_EQ(farthest_point_sampling(p, 12, {}), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 0, 1}));
  EXPECT_TRUE(farthest_point_sampling({}, 5, {}).empty());
}

// More passes keep the one-pass sample first, also when the endpoints are too few for every pass.
TEST(Sampling, PassesContinueAfterTheOnePassSample) {
  for (int n : {40, 12, 7, 3}) {  // more endpoints than passes x samples, between, and fewer than one pass
    std::vector<Vec3> p;
    for (int i = 0; i < n; ++i) p.push_back(Vec3(0.37 * i, std::sin(i), 0));
    SamplingOptions o;
    o.num_samples = 5;
    o.seeds.min_count = 1000;  // no density seeds: plain farthest-point sampling
    const std::vector<int> one = sample_endpoints(p, o);
    o.passes = 3;
    const std::vector<int> three = sample_endpoints(p, o);
    ASSERT_EQ(three.size(), 15u) << n;
    EXPECT_EQ(std::vector<int>(three.begin(), three.begin() + 5), one) << n;
    std::vector<int> distinct = three;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    EXPECT_EQ(distinct.size(), static_cast<size_t>(std::min(n, 15))) << n;  // every endpoint before any repeat
  }
  SamplingOptions bad;
  bad.passes = 0;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

TEST(Sampling, NearGtPositivesComeFirstAndAreSeeded) {
  std::vector<Vec3> p;
  for (int i = 0; i < 300; ++i) p.push_back(Vec3(0.1 * i, 0, 0));
  const std::vector<Vec3> gt = {Vec3(5, 0, 0)};
  SamplingOptions o;
  o.num_samples = 20;
  o.near_gt_samples = 3;
  DataRng r1(9), r2(9);
  const auto a = sample_endpoints(p, o, &gt, &r1);
  const auto b = sample_endpoints(p, o, &gt, &r2);
  EXPECT_EQ(a, b);
  ASSERT_EQ(a.size(), 20u);
  for (int k = 0; k < 3; ++k) EXPECT_LE((p[a[k]] - gt[0]).norm(), o.near_gt_radius_m);
  EXPECT_THROW(sample_endpoints(p, o), std::invalid_argument);
}

// Hand-made patch: three segments, query at segment 0's first endpoint.
// Three segments around the origin (the third far away), their endpoint labels and GT junctions.
struct ThreeSegmentScene {
  std::vector<Segment3> segs = {{Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(0, 1.5, 0), Vec3(0, 0.5, 0)}, {Vec3(5, 5, 5), Vec3(6, 5, 5)}};
  std::vector<int> labels = {0, 1, -1, 2, -1, -1};
  std::vector<Vec3> gt = {Vec3(0.1, 0.1, 0), Vec3(1, 0, 0), Vec3(0, 0.5, 0)};
};

TEST(JunctionPatch, FeaturesPaddingAndLabel) {
  const ThreeSegmentScene scene;
  const std::vector<int>& labels = scene.labels;
  const std::vector<Vec3>& gt = scene.gt;
  const SegmentSet set(scene.segs);
  const auto P = build_junction_patches(set, labels, gt, {0}, unit_frame(3, 2));
  ASSERT_EQ(P.features.size(), 3u * 7);
  const float* f = P.features.data();
  // Slot 0: segment 0 (line distance 0), near = x itself.
  EXPECT_FLOAT_EQ(f[0], 0);
  EXPECT_FLOAT_EQ(f[3], 1);
  EXPECT_FLOAT_EQ(f[6], 0);
  // Slot 1: segment 1, its line passes through x (distance 0); endpoints reordered near-first.
  EXPECT_FLOAT_EQ(f[7 + 1], 0.5f);
  EXPECT_FLOAT_EQ(f[7 + 4], 1.5f);
  EXPECT_FLOAT_EQ(f[7 + 6], 0.5f);
  // Slot 2: segment 2 is 7.07 m from x's line -> padding with segment 0's coordinates and segment 2's distance.
  EXPECT_EQ(P.padded, (std::vector<uint8_t>{0, 0, 1}));
  EXPECT_FLOAT_EQ(f[14 + 3], 1);
  EXPECT_NEAR(f[14 + 6], std::sqrt(75.0), 1e-5);
  // Line labels [0, 2, 0(pad = segment 0)] -> junction 0; offset = gt[0] - x.
  EXPECT_EQ(P.label[0], 0);
  EXPECT_FLOAT_EQ(P.offset[0], 0.1f);
  EXPECT_FLOAT_EQ(P.offset[1], 0.1f);
  EXPECT_EQ(P.endpoint[0], 0);

  PatchOptions zero = unit_frame(3, 2);
  zero.padding = PaddingMode::Zero;
  const auto Z = build_junction_patches(set, labels, gt, {0}, zero);
  for (int k = 0; k < 7; ++k) EXPECT_EQ(Z.features[14 + k], 0.0f);

  // Half or more padded -> negative; two noise lines of three (threshold 2) -> negative.
  EXPECT_EQ(build_junction_patches(set, labels, gt, {0}, unit_frame(4, 2)).label[0], -1);
  const std::vector<int> noisy = {-1, 1, -1, -1, -1, -1};
  EXPECT_EQ(build_junction_patches(set, noisy, gt, {0}, unit_frame(3, 2)).label[0], -1);
  // Query at segment 1's far end (0,1.5,0): near endpoint there is labelled -1.
  const auto Q = build_junction_patches(set, labels, gt, {2}, unit_frame(3, 3));
  EXPECT_FLOAT_EQ(Q.points[1], 1.5f);
}

TEST(JunctionPatch, TiesBreakToTheSmallestJunctionAndZeroLengthIsFar) {
  const std::vector<Segment3> segs = {{Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(0, 0, 0), Vec3(0, 1, 0)}, {Vec3(0.1, 0, 0), Vec3(0.1, 0, 0)}};
  const std::vector<int> labels = {3, -1, 2, -1, 0, 0};
  const std::vector<Vec3> gt(4, Vec3::Zero());
  const auto P = build_junction_patches(SegmentSet(segs), labels, gt, {0}, unit_frame(3, 3));
  EXPECT_EQ(P.padded, (std::vector<uint8_t>{0, 0, 1}));  // zero-length segment at distance 1e5
  // Line labels [3, 2, 3 (pad = segment 0)] -> 3 wins 2:1; with L = 2: [3, 2] tie -> 2.
  EXPECT_EQ(P.label[0], 3);
  EXPECT_EQ(build_junction_patches(SegmentSet(segs), labels, gt, {0}, unit_frame(2, 2)).label[0], 2);
}

// positive_radius_m: the majority junction only counts when it lies within the radius of the sample point.
TEST(JunctionPatch, PositiveRadiusMakesFarJunctionsNegative) {
  const ThreeSegmentScene scene;
  const std::vector<int>& labels = scene.labels;
  const std::vector<Vec3>& gt = scene.gt;
  const SegmentSet set(scene.segs);
  PatchOptions o = unit_frame(3, 2);
  o.positive_radius_m = 0.2;  // junction 0 is 0.141 away from the sample point (0, 0, 0)
  const auto kept = build_junction_patches(set, labels, gt, {0}, o);
  EXPECT_EQ(kept.label[0], 0);
  EXPECT_FLOAT_EQ(kept.offset[0], 0.1f);
  o.positive_radius_m = 0.1;
  const auto dropped = build_junction_patches(set, labels, gt, {0}, o);
  EXPECT_EQ(dropped.label[0], -1);
  EXPECT_EQ(dropped.offset[0], 0.0f);
  EXPECT_EQ(dropped.features, kept.features);  // the input is the same, only the target changes
  o.positive_radius_m = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

// Segment distance: a long collinear line far along its extension fills the release's patch, not the
// segment-distance one, which takes the short line beside the corner instead.
TEST(JunctionPatch, SegmentDistancePicksTheLinesAtTheCorner) {
  const std::vector<Segment3> segs = {{Vec3(0, 0, 0), Vec3(0, 0, 1)},    // at the corner
                                      {Vec3(5, 0, 0), Vec3(9, 0, 0)},    // 5 m away, its line through the corner
                                      {Vec3(0.3, 0.3, 0), Vec3(0.3, 0.8, 0)}};  // 0.42 m away, its line 0.3 m
  const SegmentSet set(segs);
  std::vector<int> idx;
  std::vector<double> dist;
  set.nearest(Vec3::Zero(), 2, PatchDistance::InfiniteLine, idx, dist);
  EXPECT_EQ(idx, (std::vector<int>{0, 1}));
  set.nearest(Vec3::Zero(), 2, PatchDistance::Segment, idx, dist);
  EXPECT_EQ(idx, (std::vector<int>{0, 2}));
  EXPECT_NEAR(dist[1], std::sqrt(0.18), 1e-12);
  for (int i = 0; i < 3; ++i) {  // the distance a patch selects by is the feature it stores
    set.nearest(Vec3(0.2, -0.4, 0.7), 3, PatchDistance::Segment, idx, dist);
    EXPECT_NEAR(dist[static_cast<size_t>(std::find(idx.begin(), idx.end(), i) - idx.begin())],
                set.segment_distance(i, Vec3(0.2, -0.4, 0.7)), 1e-6);
  }
  PatchOptions o = unit_frame(2, 2);
  o.radius_m = 1.0;
  o.distance = PatchDistance::Segment;
  const auto P = build_junction_patches(set, {}, {}, {0}, o);
  EXPECT_EQ(P.padded, (std::vector<uint8_t>{0, 0}));
  EXPECT_NEAR(P.features[7 + 6], std::sqrt(0.18), 1e-6);  // slot 1 is segment 2
  o.distance = PatchDistance::InfiniteLine;
  EXPECT_EQ(build_junction_patches(set, {}, {}, {0}, o).padded, (std::vector<uint8_t>{0, 0}));  // segment 1
  EXPECT_EQ(parse_patch_distance("segment", "k"), PatchDistance::Segment);
  EXPECT_STREQ(patch_distance_name(parse_patch_distance("infinite_line", "k")), "infinite_line");
  EXPECT_THROW(parse_patch_distance("line", "junction_net.patch_distance"), std::invalid_argument);
}

TEST(JunctionPatch, BadInputs) {
  EXPECT_THROW(build_junction_patches(SegmentSet({}), {}, {}, {0}, unit_frame(3, 2)), std::invalid_argument);
  const std::vector<Segment3> segs = {{Vec3(0, 0, 0), Vec3(1, 0, 0)}};
  EXPECT_THROW(build_junction_patches(SegmentSet(segs), {}, {}, {2}, unit_frame(3, 2)), std::out_of_range);
  EXPECT_THROW(build_junction_patches(SegmentSet(segs), {0}, {}, {0}, unit_frame(3, 2)), std::invalid_argument);
  EXPECT_THROW(build_junction_patches(SegmentSet(segs), {5, 5}, {Vec3::Zero()}, {0}, unit_frame(1, 1)), std::out_of_range);
  PatchOptions bad;
  bad.negative_noise_count = 40;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

TEST(PairPatch, SixtyFourSlotsCentredAtTheMidpoint) {
  const std::vector<Segment3> segs = {{Vec3(1, 0, 0), Vec3(0, 0, 0)}, {Vec3(3, 0, 0), Vec3(3, 1, 0)}};
  JunctionPair pr;
  pr.u = Vec3(0, 0, 0);
  pr.v = Vec3(3, 0, 0);
  pr.label = 1;
  const auto P = build_pair_patches(SegmentSet(segs), {pr}, unit_frame(2, 1));
  ASSERT_EQ(P.lines, 4);
  ASSERT_EQ(P.features.size(), 4u * 6);
  // Around u: segment 0 (distance 0) then segment 1 (line x = 3, distance 3 > radius 2.66: padded).
  // Around v: both lines pass through v (distance 0): tie -> lower index first (segment 0, then 1).
  EXPECT_EQ(P.padded, (std::vector<uint8_t>{0, 1, 0, 0}));
  const float* f = P.features.data();
  // Midpoint m = (1.5, 0, 0): segment 0 near end (1,0,0) -> -0.5, far end (0,0,0) -> -1.5.
  EXPECT_FLOAT_EQ(f[0], -0.5f);
  EXPECT_FLOAT_EQ(f[3], -1.5f);
  EXPECT_FLOAT_EQ(f[12], -0.5f);  // slot 2 = segment 0 again
  EXPECT_FLOAT_EQ(f[18], 1.5f);   // slot 3 = segment 1, near end (3,0,0), far end (3,1,0)
  EXPECT_FLOAT_EQ(f[21], 1.5f);
  EXPECT_FLOAT_EQ(f[22], 1.0f);
  EXPECT_EQ(P.label[0], 1);
}

Wireframe path4() {
  Wireframe w;
  for (int i = 0; i < 4; ++i) w.junctions.push_back(Vec3(2.0 * i, 0, 0));
  w.edges = {{0, 1}, {1, 2}, {2, 3}};
  return w;
}

TEST(Pairs, ClassesOfTheRelease) {
  const PairClassifier c(path4());
  EXPECT_EQ(c.classify(1, 1), kPairIdentical);
  EXPECT_EQ(c.classify(0, 1), kPairConnected);
  EXPECT_EQ(c.classify(0, 2), kPairDistance2);
  EXPECT_EQ(c.classify(0, 3), kPairFarther);
  EXPECT_EQ(c.classify(-1, 3), kPairFalsePositive);
  EXPECT_EQ(c.classify(-1, -1), kPairFalsePositive);
  EXPECT_EQ(assign_junction_labels({Vec3(0.3, 0, 0), Vec3(0.36, 0, 0), Vec3(1.9, 0.1, 0)}, path4().junctions, 0.35),
            (std::vector<int>{0, -1, 1}));
}

TEST(Pairs, TrainingOrderAndCyclicFill) {
  PredictedJunctions pred;
  pred.positions = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(50, 0, 0), Vec3(0.1, 0, 0)};
  pred.confidence = {0.9, 0.8, 0.7, 0.6};
  JunctionSelectionOptions so = JunctionSelectionOptions::release();  // its NMS radius and cut
  so.nms = PointNmsRule::kGreedy;
  const JunctionSelection sel = select_junctions(pred, {}, so, SelectionCut::kTopK);
  PairSamplingOptions o;
  o.pairs_per_building = 10;
  o.max_static_pairs = 10;
  const auto pairs = sample_training_pairs(path4(), sel, o);
  std::vector<int> labels;
  for (const auto& p : pairs) labels.push_back(p.label);
  EXPECT_EQ(labels, (std::vector<int>{1, 1, 1, 2, 2, 3, 1, 4, 4, 1}));
  EXPECT_TRUE(pairs[0].from_gt);
  EXPECT_FALSE(pairs[6].from_gt);
  EXPECT_EQ(pairs[7].i, 0);
  EXPECT_EQ(pairs[7].j, 2);
  // Static pairs are truncated first.
  o.max_static_pairs = 2;
  EXPECT_EQ(sample_training_pairs(path4(), sel, o)[2].label, 1);
  EXPECT_FALSE(sample_training_pairs(path4(), sel, o)[2].from_gt);
  // No predictions: static pairs are repeated, never a crash.
  const auto only_gt = sample_training_pairs(path4(), JunctionSelection{}, o);
  ASSERT_EQ(only_gt.size(), 10u);
  EXPECT_TRUE(only_gt[9].from_gt);
  Wireframe one;
  one.junctions = {Vec3::Zero()};
  EXPECT_TRUE(sample_training_pairs(one, sel, o).empty());
}

TEST(Pairs, TestPairsKeepConfidentJunctions) {
  PredictedJunctions pred;
  pred.positions = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(50, 0, 0), Vec3(0.1, 0, 0)};
  pred.confidence = {0.9, 0.8, 0.7, 0.6};
  JunctionSelectionOptions so = JunctionSelectionOptions::release();  // its NMS radius and cut
  so.nms = PointNmsRule::kGreedy;
  const JunctionSelection one = select_junctions(pred, {}, so);
  EXPECT_TRUE(selection_pairs(one, nullptr, 0.35).empty());  // only one junction > 0.85
  EXPECT_EQ(one.kept, (std::vector<int>{0}));
  so.min_confidence = 0.5;
  const JunctionSelection s = select_junctions(pred, {}, so);
  EXPECT_EQ(s.kept, (std::vector<int>{0, 1, 2}));  // 3 is suppressed by 0 (NMS 0.25 m)
  const Wireframe gt = path4();
  const auto pairs = selection_pairs(s, &gt, 0.35);
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0].label, 1);
  EXPECT_EQ(pairs[1].label, 4);
  EXPECT_EQ(selection_pairs(s, nullptr, 0.35).at(1).j, 2);
}

TEST(Augmentation, IsScaleAndShiftInNetworkUnits) {
  const NetworkFrame f;
  DataRng rng(3);
  const Augmentation a = draw_augmentation(rng, AugmentOptions{}, f);
  EXPECT_GE(a.scale, 0.8);
  EXPECT_LE(a.scale, 1.25);
  EXPECT_LE(a.shift_m.cwiseAbs().maxCoeff(), 0.1 * f.scale_m);
  const Vec3 p(3, -2, 5);
  const Vec3 expected = a.scale * f.to_network(p) + a.shift_m / f.scale_m;
  EXPECT_NEAR((f.to_network(a.apply(p)) - expected).norm(), 0, 1e-12);
  DataRng r2(3);
  EXPECT_EQ(draw_augmentation(r2, AugmentOptions{}, f).scale, a.scale);
  AugmentOptions rot;
  rot.rotate_z = true;
  DataRng r3(4);
  const Augmentation b = draw_augmentation(r3, rot, f);
  EXPECT_NE(b.angle_rad, 0.0);
  // A rotation about the vertical through the centre keeps horizontal distances and heights (times scale).
  const Vec3 d = b.apply(p) - b.centre_m - b.shift_m;
  EXPECT_NEAR(d.head<2>().norm(), b.scale * (p - b.centre_m).head<2>().norm(), 1e-12);
  EXPECT_NEAR(d.z(), b.scale * (p - b.centre_m).z(), 1e-12);
}

TEST(Samples, JunctionSampleOnASyntheticBuilding) {
  const Building b = make_l_building("l", LBuildingSpec{});
  const LineCloud c = make_synthetic_line_cloud(b, 11);
  JunctionSampleOptions o;
  const auto P = make_junction_sample(c, o, 1);
  EXPECT_EQ(P.num_patches, 256);
  EXPECT_EQ(P.lines, 32);
  EXPECT_EQ(P.features.size(), 256u * 32 * 7);
  int pos = 0;
  for (int g = 0; g < 256; ++g) {
    if (P.label[g] < 0) continue;
    ++pos;
    const Vec3 off(P.offset[3 * g], P.offset[3 * g + 1], P.offset[3 * g + 2]);
    // Endpoint labels name the ends of the segment's GT edge, so the target junction can be an edge length away.
    EXPECT_LT(off.norm() * o.patch.frame.scale_m, o.patch.radius_m + 16.0 + 0.5);
  }
  EXPECT_GT(pos, 20);
  EXPECT_LT(pos, 256);
  // Same seed -> same sample; augmentation changes it.
  EXPECT_EQ(make_junction_sample(c, o, 1).features, P.features);
  o.augment_enabled = true;
  const auto A1 = make_junction_sample(c, o, 1);
  EXPECT_EQ(make_junction_sample(c, o, 1).features, A1.features);
  EXPECT_NE(make_junction_sample(c, o, 2).features, A1.features);
  EXPECT_NE(A1.features, P.features);
  EXPECT_EQ(A1.endpoint, P.endpoint);  // sampling happens before augmentation
  EXPECT_THROW(make_junction_sample(LineCloud{}, o, 1), DataError);
}

TEST(Samples, NearGtAndEndpointDistanceOptions) {
  const Building b = make_rect_building("r", RectBuildingSpec{});
  const LineCloud c = make_synthetic_line_cloud(b, 21);
  JunctionSampleOptions o;
  const auto plain = make_junction_sample(c, o, 3);
  o.endpoint_label_max_distance_m = 0.5;
  const auto near_only = make_junction_sample(c, o, 3);
  int pos_plain = 0, pos_near = 0;
  for (int g = 0; g < 256; ++g) {
    pos_plain += plain.label[g] >= 0;
    pos_near += near_only.label[g] >= 0;
    if (near_only.label[g] >= 0) {
      const Vec3 off(near_only.offset[3 * g], near_only.offset[3 * g + 1], near_only.offset[3 * g + 2]);
      EXPECT_LT(off.norm() * o.patch.frame.scale_m, o.patch.radius_m + 0.5);  // junction near some patch endpoint
    }
  }
  EXPECT_LT(pos_near, pos_plain);
  EXPECT_GT(pos_near, 0);
  o.sampling.near_gt_samples = 64;
  const auto boosted = make_junction_sample(c, o, 3);
  int pos_boosted = 0;
  for (int g = 0; g < 256; ++g) pos_boosted += boosted.label[g] >= 0;
  EXPECT_GT(pos_boosted, pos_near);
  o.endpoint_label_max_distance_m = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

TEST(Samples, SliceUndoesStackForJunctionPatches) {
  JunctionSampleOptions jo;
  jo.augment_enabled = true;
  const LineCloud c = make_synthetic_line_cloud(make_random_building(2, "b"), 2);
  const JunctionPatches a = make_junction_sample(c, jo, 1), b = make_junction_sample(c, jo, 2);
  const JunctionPatches two = stack(std::vector<JunctionPatches>{a, b});
  const JunctionPatches back = slice(two, 1, 1);
  EXPECT_EQ(back.batch, 1);
  EXPECT_EQ(back.features, b.features);
  EXPECT_EQ(back.padded, b.padded);
  EXPECT_EQ(back.points, b.points);
  EXPECT_EQ(back.label, b.label);
  EXPECT_EQ(back.offset, b.offset);
  EXPECT_EQ(back.endpoint, b.endpoint);
  EXPECT_EQ(slice(two, 0, 1).features, a.features);
}

TEST(Samples, LoaderStacksJunctionSamplesDeterministically) {
  std::vector<LineCloud> clouds;
  for (uint64_t s = 0; s < 5; ++s) clouds.push_back(make_synthetic_line_cloud(make_random_building(s, "b"), s));
  JunctionSampleOptions jo;
  jo.augment_enabled = true;
  auto build = [&](const std::vector<size_t>& items, uint64_t seed) {
    std::vector<JunctionPatches> parts;
    for (size_t k = 0; k < items.size(); ++k) parts.push_back(make_junction_sample(clouds[items[k]], jo, mix_seed(seed, k)));
    return stack(parts);
  };
  auto run = [&](int workers) {
    LoaderOptions lo;
    lo.batch_size = 2;
    lo.workers = workers;
    BatchLoader<JunctionPatches> loader(clouds.size(), build, lo);
    loader.start_epoch(3);
    std::vector<JunctionPatches> out;
    while (auto b = loader.next()) out.push_back(std::move(*b));
    return out;
  };
  const auto a = run(1), b = run(3);
  ASSERT_EQ(a.size(), 2u);  // drop_last: 5 buildings -> 2 batches of 2
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].batch, 2);
    EXPECT_EQ(a[k].features.size(), 2u * 256 * 32 * 7);
    EXPECT_EQ(a[k].features, b[k].features);
    EXPECT_EQ(a[k].label, b[k].label);
  }
}

TEST(Samples, PairSamplesOnASyntheticBuilding) {
  const Building b = make_rect_building("r", RectBuildingSpec{});
  const LineCloud c = make_synthetic_line_cloud(b, 12);
  PredictedJunctions pred;
  for (size_t i = 0; i < c.wireframe.junctions.size(); ++i) {
    pred.positions.push_back(c.wireframe.junctions[i] + Vec3(0.05, 0, 0));
    pred.confidence.push_back(0.99 - 0.01 * i);
  }
  pred.positions.push_back(Vec3(30, 30, 0));
  pred.confidence.push_back(0.95);
  pred.offset_m.assign(pred.positions.size(), 0.0);  // regressed onto their sample points
  PairSampleOptions o;
  o.augment_enabled = true;
  // The false vote lies in empty space on the ground: the corner and footing checks would drop it, and its
  // pairs are what is tested.
  JunctionSelectionOptions every;
  every.corner.radius_m = 0;
  every.footing.radius_m = 0;
  EXPECT_EQ(select_junctions(pred, c.segments, {}).kept.size(), c.wireframe.junctions.size());
  const auto T = make_pair_training_sample(c, select_junctions(pred, c.segments, every, SelectionCut::kTopK), o, 5);
  EXPECT_EQ(T.num_pairs, 512);
  EXPECT_EQ(T.lines, 64);
  EXPECT_EQ(T.features.size(), 512u * 64 * 6);
  const std::vector<JunctionPair> pairs = selection_pairs(select_junctions(pred, c.segments, every), &c.wireframe, 0.35);
  const auto E = build_pair_patches(SegmentSet(c.segments), pairs, o.patch);
  EXPECT_EQ(E.num_pairs, 55);  // C(11, 2)
  int connected = 0, fp = 0;
  for (const auto& p : pairs) {
    connected += p.label == kPairConnected;
    fp += p.label == kPairFalsePositive;
  }
  EXPECT_EQ(connected, 17);
  EXPECT_EQ(fp, 10);
  LineCloud no_gt = c;
  no_gt.wireframe = {};
  no_gt.labels.clear();
  EXPECT_THROW(make_pair_training_sample(no_gt, JunctionSelection{}, o, 1), DataError);
  const auto stacked = stack(std::vector<PairPatches>{T, T});
  EXPECT_EQ(stacked.batch, 2);
  EXPECT_EQ(stacked.features.size(), 2 * T.features.size());
  // slice() undoes stack(): micro-batches see exactly their buildings' patches.
  const auto T2 = make_pair_training_sample(c, select_junctions(pred, c.segments, {}, SelectionCut::kTopK), o, 6);
  const auto two = stack(std::vector<PairPatches>{T, T2});
  const PairPatches second = slice(two, 1, 1);
  EXPECT_EQ(second.batch, 1);
  EXPECT_EQ(second.features, T2.features);
  EXPECT_EQ(second.padded, T2.padded);
  EXPECT_EQ(second.label, T2.label);
  EXPECT_EQ(slice(two, 0, 2).features, two.features);
  EXPECT_THROW(slice(two, 1, 2), std::invalid_argument);
  EXPECT_THROW(slice(two, 0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

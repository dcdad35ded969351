#include "model/post_process.h"
#include "infer/post_process_flags.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

using Probs = std::map<std::pair<int, int>, std::pair<double, double>>;  // (i, j) -> (merge, connect)

PostProcessInput make_input(std::vector<Vec3> pts, std::vector<double> conf, const Probs& probs) {
  PostProcessInput in;
  const int n = static_cast<int>(pts.size());
  in.junctions = std::move(pts);
  in.confidences = std::move(conf);
  for (const auto& [i, j] : all_pairs(n)) {
    const auto it = probs.find({i, j});
    const auto [m, c] = it == probs.end() ? std::pair<double, double>{0.0, 0.0} : it->second;
    in.pairs.push_back({i, j, m, c});
  }
  return in;
}

// Final edges as a set of coordinate pairs (independent of output order).
std::set<std::pair<std::array<double, 3>, std::array<double, 3>>> edge_set(const ScoredWireframe& w) {
  std::set<std::pair<std::array<double, 3>, std::array<double, 3>>> out;
  for (const auto& [a, b] : w.wireframe.edges) {
    const Vec3& p = w.wireframe.junctions[a];
    const Vec3& q = w.wireframe.junctions[b];
    std::array<double, 3> x{p.x(), p.y(), p.z()}, y{q.x(), q.y(), q.z()};
    out.insert({std::min(x, y), std::max(x, y)});
  }
  return out;
}

const std::vector<Vec3> kSquare{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};

PostProcessOptions no_merge_no_nms(PostProcessOptions o) {
  o.hamming_threshold = 0;    // Hamming < 0 never holds
  o.line_nms_distance = 0.0;  // distance < 0 never holds
  return o;
}

TEST(PostProcess, AllPairsInLexicographicOrder) {
  EXPECT_EQ(all_pairs(4), (std::vector<std::array<int, 2>>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}));
  EXPECT_TRUE(all_pairs(1).empty());
  EXPECT_EQ(all_pairs(40).size(), 780u);
}

TEST(PostProcess, CleanSquareSurvivesWithNoIdenticalPairNote) {
  const auto in = make_input(kSquare, {.99, .98, .97, .96},
                             {{{0, 1}, {0, .9}}, {{1, 2}, {0, .8}}, {{2, 3}, {0, .7}}, {{0, 3}, {0, .6}},
                              {{0, 2}, {0, .1}}});
  for (const auto& o : {PostProcessOptions{}, PostProcessOptions::release_quirks()}) {
    const PostProcessResult r = post_process(in, o);
    ASSERT_EQ(r.wireframe.wireframe.edges.size(), 4u);
    // Ascending score order; junctions in first-appearance order over that list.
    EXPECT_EQ(r.wireframe.edge_scores, (std::vector<double>{.6, .7, .8, .9}));
    EXPECT_EQ(r.wireframe.wireframe.junctions[0], kSquare[0]);
    EXPECT_EQ(r.wireframe.wireframe.junctions[1], kSquare[3]);
    EXPECT_EQ(r.wireframe.junction_scores[1], .96);
    EXPECT_EQ(r.stats.candidate_edges, 4);
    ASSERT_EQ(r.notes.size(), 1u);  // the "no identical pair" case of the release is handled, not fatal
    EXPECT_THAT(r.notes[0], HasSubstr("identical"));
  }
}

TEST(PostProcess, IdenticalPairPruningChains) {
  // Three copies of one corner; merge(0,1) = .9 is handled first and deletes 1; then merge(1,2) = .5:
  // the release lets the deleted 1 delete 2 as well, the default skips it.
  std::vector<Vec3> p = kSquare;
  p.push_back({0.5, 0, 0});
  p.push_back({1.0, 0, 0});
  Probs probs{{{0, 1}, {0, .9}}, {{1, 2}, {0, .9}}, {{2, 3}, {0, .9}}, {{0, 3}, {0, .9}},
              {{0, 4}, {.9, 0}}, {{4, 5}, {.5, .9}}, {{5, 2}, {0, .9}}};
  // Junction ids: 0..3 square, 4 and 5 the copies; pairs use (min, max).
  probs.erase({5, 2});
  probs[{2, 5}] = {0, .9};
  const auto in = make_input(p, {.99, .98, .97, .96, .95, .94}, probs);
  const auto sound = post_process(in, no_merge_no_nms(PostProcessOptions{}));
  EXPECT_EQ(sound.stats.pruned_junctions, 1);
  EXPECT_EQ(sound.stats.candidate_edges, 5);  // square + 2-5; 4-5 goes with the deleted 4
  auto release_opts = no_merge_no_nms(PostProcessOptions::release_quirks());
  const auto release = post_process(in, release_opts);
  EXPECT_EQ(release.stats.pruned_junctions, 2);
  EXPECT_EQ(release.stats.candidate_edges, 4);
  EXPECT_EQ(edge_set(release.wireframe).size(), 4u);
}

TEST(PostProcess, IsolatedThenDanglingEdgesRemoved) {
  std::vector<Vec3> p = kSquare;
  p.push_back({30, 0, 0});  // 4-5: an isolated edge
  p.push_back({40, 0, 0});
  p.push_back({-5, -5, 0});  // 0-6: a dangling tail
  const auto in = make_input(p, {.99, .98, .97, .96, .95, .94, .93},
                             {{{0, 1}, {0, .9}}, {{1, 2}, {0, .9}}, {{2, 3}, {0, .9}}, {{0, 3}, {0, .9}},
                              {{4, 5}, {0, .9}}, {{0, 6}, {0, .9}}});
  const auto r = post_process(in, PostProcessOptions{});
  EXPECT_EQ(r.stats.isolated_edges, 1);
  EXPECT_EQ(r.stats.dangling_edges, 1);
  EXPECT_EQ(r.wireframe.wireframe.edges.size(), 4u);
  EXPECT_EQ(r.wireframe.wireframe.junctions.size(), 4u);
  EXPECT_EQ(r.candidates.wireframe.edges.size(), 6u);  // "before process" keeps everything
}

TEST(PostProcess, DanglingRemovalIsASinglePass) {
  // A path 0-1-2-3: one pass removes the two end edges and leaves 1-2 even though it now dangles.
  const auto in = make_input(kSquare, {.99, .98, .97, .96},
                             {{{0, 1}, {0, .9}}, {{1, 2}, {0, .9}}, {{2, 3}, {0, .9}}});
  const auto r = post_process(in, PostProcessOptions{});
  EXPECT_EQ(r.stats.dangling_edges, 2);
  EXPECT_EQ(r.wireframe.wireframe.edges.size(), 1u);
}

TEST(PostProcess, HammingMergeTransfersEdgesOrDropsThem) {
  // Junction 4 sits 0.42 m from corner 0 and carries the edge to corner 3; corner 0 only has the edge to 1.
  // Rows of 0 ({1}) and 4 ({3}) differ in 2 entries < 3 -> 4 merges into the more confident 0.
  std::vector<Vec3> p = kSquare;
  p.push_back({0.3, 0.3, 0});
  const auto in = make_input(p, {.99, .98, .97, .96, .9},
                             {{{0, 1}, {0, .9}}, {{1, 2}, {0, .9}}, {{2, 3}, {0, .9}}, {{3, 4}, {0, .8}}});
  const auto sound = post_process(in, PostProcessOptions{});
  EXPECT_EQ(sound.stats.merged_junctions, 1);
  EXPECT_EQ(sound.stats.transferred_edges, 1);
  EXPECT_EQ(sound.wireframe.wireframe.edges.size(), 4u);  // the full square, edge 3-4 became 3-0
  EXPECT_EQ(sound.wireframe.wireframe.junctions.size(), 4u);
  const auto release = post_process(in, PostProcessOptions::release_quirks());
  EXPECT_EQ(release.stats.merged_junctions, 1);
  EXPECT_EQ(release.stats.merge_removed_edges, 1);
  // Without the transfer corners 0 and 3 dangle and the single cleaning pass leaves only 1-2.
  EXPECT_EQ(edge_set(release.wireframe), edge_set(ScoredWireframe::with_unit_scores({{kSquare[1], kSquare[2]}, {{0, 1}}})));
}

TEST(PostProcess, HammingMergeNeedsBothDistanceAndSimilarRows) {
  std::vector<Vec3> p = kSquare;
  p.push_back({2.0, 0.0, 0});  // 2 m from corner 0: too far to merge
  const auto in = make_input(p, {.99, .98, .97, .96, .9},
                             {{{0, 1}, {0, .9}}, {{1, 2}, {0, .9}}, {{2, 3}, {0, .9}}, {{0, 3}, {0, .9}},
                              {{3, 4}, {0, .9}}, {{2, 4}, {0, .9}}});
  EXPECT_EQ(post_process(in, PostProcessOptions{}).stats.merged_junctions, 0);
}

TEST(PostProcess, PrunedJunctionsTakePartInTheReleaseMerge) {
  // 4 is pruned as identical to 0; 5 (less confident than 4, 1 m from 4, 3 m from 0) has two edges.
  // In the release the edge-less, deleted 4 still absorbs 5 (rows differ in 2 entries) and 5's edges go.
  std::vector<Vec3> p = kSquare;
  p.push_back({0, -2, 0});
  p.push_back({0, -3, 0});
  p.push_back({10, -3, 0});
  const Probs probs{{{0, 1}, {0, .9}}, {{1, 2}, {0, .9}}, {{2, 3}, {0, .9}}, {{0, 3}, {0, .9}},
                    {{0, 4}, {.9, 0}}, {{5, 6}, {0, .9}}, {{1, 6}, {0, .9}}, {{1, 5}, {0, .9}}};
  const auto in = make_input(p, {.99, .98, .97, .96, .95, .94, .93}, probs);
  auto release = PostProcessOptions::release_quirks();
  release.line_nms_distance = 0.0;
  EXPECT_EQ(post_process(in, release).stats.merge_removed_edges, 2);
  auto sound = PostProcessOptions{};
  sound.line_nms_distance = 0.0;
  const auto r = post_process(in, sound);
  EXPECT_EQ(r.stats.merged_junctions, 0);
  EXPECT_EQ(r.wireframe.wireframe.edges.size(), 7u);
}

TEST(PostProcess, LineNmsKeepsHigherOrLowerScore) {
  // Edge 4-1 (score .6) nearly duplicates 0-1 (.8): summed endpoint distance 0.3 m < 1 m.
  std::vector<Vec3> p = kSquare;
  p.push_back({0.3, 0, 0});
  const auto in = make_input(p, {.99, .98, .97, .96, .9},
                             {{{0, 1}, {0, .8}}, {{1, 2}, {0, .9}}, {{2, 3}, {0, .9}}, {{0, 3}, {0, .9}},
                              {{1, 4}, {0, .6}}});
  PostProcessOptions sound;
  sound.hamming_threshold = 0;
  const auto s = post_process(in, sound);
  EXPECT_EQ(s.stats.line_nms_edges, 1);
  EXPECT_EQ(edge_set(s.wireframe).size(), 4u);  // the square; 4 lost its only edge
  EXPECT_EQ(s.wireframe.wireframe.junctions.size(), 4u);
  auto release = PostProcessOptions::release_quirks();
  release.hamming_threshold = 0;
  const auto r = post_process(in, release);
  EXPECT_EQ(r.stats.line_nms_edges, 1);
  // 0-1 went, so 0 and 4 dangle: the final pass removes 0-3 and 4-1, leaving 1-2 and 2-3.
  EXPECT_EQ(r.wireframe.wireframe.edges.size(), 2u);
  EXPECT_EQ(r.stats.dangling_edges, 2);
}

TEST(PostProcess, CrossingEdgesKeepTheHigherScore) {
  // The square 0-1-2-3 of 10 m and both its diagonals: 0-2 (.7) crosses 1-3 (.5) at the centre.
  const auto in = make_input(kSquare, {.99, .98, .97, .96},
                             {{{0, 1}, {0, .9}}, {{1, 2}, {0, .9}}, {{2, 3}, {0, .9}}, {{0, 3}, {0, .9}},
                              {{0, 2}, {0, .7}}, {{1, 3}, {0, .5}}});
  PostProcessOptions o = no_merge_no_nms(PostProcessOptions{});
  o.crossing_distance_m = 0.0;  // off: both diagonals stay
  EXPECT_EQ(post_process(in, o).wireframe.wireframe.edges.size(), 6u);
  o.crossing_distance_m = 0.25;  // the default
  const auto r = post_process(in, o);
  EXPECT_EQ(r.stats.crossing_edges, 1);
  const auto kept = edge_set(r.wireframe);
  EXPECT_EQ(kept.size(), 5u);
  EXPECT_TRUE(kept.count({{0, 0, 0}, {10, 10, 0}}));   // the higher diagonal stays
  EXPECT_FALSE(kept.count({{0, 10, 0}, {10, 0, 0}}));  // the lower one goes
  EXPECT_EQ(PostProcessOptions{}.crossing_distance_m, 0.25);
  EXPECT_EQ(PostProcessOptions::release_quirks().crossing_distance_m, 0.0);  // the release keeps both
  o.crossing_distance_m = -1.0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

TEST(PostProcess, FourReleaseCrashInputsGiveEmptyOrValidResults) {
  // Empty input.
  const auto empty = post_process(PostProcessInput{}, PostProcessOptions{});
  EXPECT_TRUE(empty.wireframe.wireframe.edges.empty());
  EXPECT_FALSE(empty.notes.empty());
  // One junction (no pair).
  const auto one = post_process(make_input({{0, 0, 0}}, {.9}, {}), PostProcessOptions{});
  EXPECT_TRUE(one.wireframe.wireframe.junctions.empty());
  EXPECT_FALSE(one.notes.empty());
  // No candidate edge.
  const auto none = post_process(make_input(kSquare, {.99, .98, .97, .96}, {{{0, 1}, {0.0, 0.3}}}),
                                 PostProcessOptions::release_quirks());
  EXPECT_TRUE(none.wireframe.wireframe.edges.empty());
  EXPECT_EQ(none.stats.candidate_edges, 0);
  EXPECT_THAT(none.notes.back(), HasSubstr("connected"));
  // No identical pair: covered by CleanSquareSurvivesWithNoIdenticalPairNote; everything pruned here.
  const auto pruned = post_process(make_input({{0, 0, 0}, {0.1, 0, 0}}, {.9, .9}, {{{0, 1}, {1.0, 0.0}}}),
                                   PostProcessOptions{});
  EXPECT_EQ(pruned.stats.pruned_junctions, 1);
  EXPECT_TRUE(pruned.wireframe.wireframe.edges.empty());
}

TEST(PostProcess, RejectsMalformedInputAndOptions) {
  auto in = make_input(kSquare, {.9, .9, .9, .9}, {});
  in.pairs.push_back({1, 0, 0, 0});
  EXPECT_THROW(post_process(in, PostProcessOptions{}), std::invalid_argument);  // repeated pair
  in = make_input(kSquare, {.9, .9, .9, .9}, {});
  in.pairs[0].connect = 1.5;
  EXPECT_THROW(post_process(in, PostProcessOptions{}), std::invalid_argument);
  in.pairs[0] = {0, 9, 0, 0};
  EXPECT_THROW(post_process(in, PostProcessOptions{}), std::invalid_argument);
  PostProcessOptions o;
  o.connect_threshold = 2.0;
  try {
    o.Check();
    FAIL() << "bad threshold accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("connect_threshold"));
  }
  o = PostProcessOptions{};
  o.pruned_junctions_in_merge = true;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  EXPECT_NO_THROW(PostProcessOptions::release_quirks().Check());
}

}  // namespace
}  // namespace lc2wf

namespace lc2wf {
namespace {

// Parses a command line's worth of post-processing flags the way the inference commands do.
PostProcessFlags parse_flags(std::vector<std::string> words) {
  std::vector<char*> argv{const_cast<char*>("cmd")};
  for (std::string& w : words) argv.push_back(w.data());
  PostProcessFlags flags;
  for (int i = 1; i < static_cast<int>(argv.size()); ++i)
    EXPECT_TRUE(flags.parse(argv[i], static_cast<int>(argv.size()), argv.data(), i)) << argv[i];
  return flags;
}

TEST(PostProcessFlags, AnyOrderGivesTheSameOptions) {
  const PostProcessOptions a =
      parse_flags({"--pair-support", "0.2", "--nms-radius", "0.5", "--min-confidence", "0.5", "--release-quirks"}).options();
  const PostProcessOptions b =
      parse_flags({"--release-quirks", "--min-confidence", "0.5", "--pair-support", "0.2", "--nms-radius", "0.5"}).options();
  for (const PostProcessOptions& o : {a, b}) {
    EXPECT_DOUBLE_EQ(o.pair_support.min_support, 0.2);
    EXPECT_DOUBLE_EQ(o.selection.min_confidence, 0.5);
    EXPECT_DOUBLE_EQ(o.selection.nms_radius_m, 0.5);
    EXPECT_FALSE(o.transfer_edges_on_merge);  // the release's rule
  }
  // Without flags: the selection chosen on the validation split (experiments/README.md), not the release's.
  const PostProcessOptions none = PostProcessFlags{}.options();
  EXPECT_DOUBLE_EQ(none.selection.min_confidence, 0.05);
  EXPECT_DOUBLE_EQ(none.pair_support.min_support, 0.0);
  EXPECT_DOUBLE_EQ(none.selection.nms_radius_m, 0.5);
  EXPECT_DOUBLE_EQ(none.selection.max_offset_m, 0.75);
  EXPECT_DOUBLE_EQ(none.selection.corner.radius_m, 0.3);
  EXPECT_DOUBLE_EQ(parse_flags({"--corner-radius", "0"}).options().selection.corner.radius_m, 0.0);
  EXPECT_TRUE(parse_flags({"--corner-radius", "0.4"}).any());
  EXPECT_DOUBLE_EQ(none.selection.footing.radius_m, 0.3);
  EXPECT_DOUBLE_EQ(parse_flags({"--footing-radius", "0"}).options().selection.footing.radius_m, 0.0);
  EXPECT_TRUE(parse_flags({"--footing-radius", "0.4"}).any());
  EXPECT_DOUBLE_EQ(parse_flags({"--max-offset", "1"}).options().selection.max_offset_m, 1.0);
  EXPECT_TRUE(std::isinf(parse_flags({"--max-offset", "0"}).options().selection.max_offset_m));  // every candidate
  const PostProcessOptions release = parse_flags({"--release-quirks"}).options();
  EXPECT_DOUBLE_EQ(release.selection.min_confidence, 0.85);
  EXPECT_DOUBLE_EQ(release.selection.nms_radius_m, 0.25);  // the release's 5 raw units
  EXPECT_TRUE(std::isinf(release.selection.max_offset_m));  // every candidate, as the release
  EXPECT_DOUBLE_EQ(release.selection.corner.radius_m, 0.0);  // every junction paired, as the release
  EXPECT_DOUBLE_EQ(release.selection.footing.radius_m, 0.0);
  EXPECT_GT(none.selection.refine.radius, 0.0);
  EXPECT_EQ(parse_flags({"--no-junction-refine"}).options().selection.refine.radius, 0.0);
  EXPECT_DOUBLE_EQ(parse_flags({"--crossing-distance", "0.2"}).options().crossing_distance_m, 0.2);
  EXPECT_FALSE(PostProcessFlags{}.any());
  EXPECT_TRUE(parse_flags({"--min-confidence", "0.85"}).any());
}

TEST(PostProcessFlags, BadValuesAreUsageErrorsNamingTheFlag) {
  auto message = [](std::vector<std::string> words) {
    try {
      parse_flags(std::move(words)).options();
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(message({"--min-confidence", "1.5"}), HasSubstr("--min-confidence must be in [0, 1]"));
  EXPECT_THAT(message({"--pair-support", "-1"}), HasSubstr("--pair-support must be in [0, 1]"));
  EXPECT_THAT(message({"--min-confidence", "high"}), HasSubstr("--min-confidence expects a number"));
  EXPECT_THAT(message({"--pair-support"}), HasSubstr("--pair-support"));
  EXPECT_THAT(message({"--nms-radius", "0"}), HasSubstr("--nms-radius must be a positive distance"));
  EXPECT_THAT(message({"--max-offset", "inf"}), HasSubstr("--max-offset expects a finite number"));
  EXPECT_EQ(message({"--max-offset", "-1"}), "");  // <= 0: every candidate
  EXPECT_THAT(message({"--corner-radius", "-0.1"}), HasSubstr("--corner-radius must be a distance >= 0"));
  EXPECT_THAT(message({"--footing-radius", "-0.1"}), HasSubstr("--footing-radius must be a distance >= 0"));
  EXPECT_THAT(message({"--sampling-passes", "0"}), HasSubstr("--sampling-passes"));
  EXPECT_THAT(message({"--crossing-distance", "-1"}), HasSubstr("--crossing-distance must be in [0, 10]"));
  EXPECT_THAT(message({"--sampling-passes", "9"}), HasSubstr("--sampling-passes must be in [1, 8]"));
  EXPECT_EQ(parse_flags({"--sampling-passes", "2"}).options().selection.sampling_passes, 2);
  EXPECT_EQ(PostProcessFlags{}.options().selection.sampling_passes, 1);  // the release's one pass
  EXPECT_EQ(parse_flags({"--release-quirks"}).options().selection.sampling_passes, 1);
  EXPECT_THAT(message({"--density-seeds", "dense"}), HasSubstr("--density-seeds: 'dense' is not release, loose"));
  EXPECT_THAT(message({"--density-seeds", "4,2,0.3"}), HasSubstr("--density-seeds: DensitySeedRule.min_ratio must be in [0, 1]"));
  EXPECT_EQ(PostProcessFlags{}.options().selection.density_seeds, DensitySeedRule::loose());
  EXPECT_EQ(parse_flags({"--density-seeds", "release"}).options().selection.density_seeds, DensitySeedRule::release());
  EXPECT_EQ(parse_flags({"--density-seeds", "6,0.45,0.25"}).options().selection.density_seeds.str(), "6,0.45,0.25");
  EXPECT_EQ(parse_flags({"--release-quirks"}).options().selection.density_seeds, DensitySeedRule::release());
  EXPECT_THAT(message({"--test-time-views", "3"}), HasSubstr("--test-time-views must be 1, 2, 4 or 8"));
  EXPECT_THAT(message({"--test-time-views", "0"}), HasSubstr("--test-time-views"));
  EXPECT_EQ(parse_flags({"--test-time-views", "8"}).options().selection.test_time_views, 8);
  EXPECT_EQ(PostProcessFlags{}.options().selection.test_time_views, 1);  // the release's one view
  EXPECT_THAT(message({"--edge-test-time-views", "5"}), HasSubstr("--edge-test-time-views must be 1, 2, 4 or 8"));
  EXPECT_EQ(parse_flags({"--edge-test-time-views", "4"}).options().edge_test_time_views, 4);
  EXPECT_THAT(message({"--max-segment-length", "0.01"}), HasSubstr("--max-segment-length must be 0 (off) or in [0.05, 100]"));
  EXPECT_THAT(message({"--max-segment-length", "nan"}), HasSubstr("--max-segment-length"));
  EXPECT_EQ(parse_flags({"--max-segment-length", "2.5"}).options().max_segment_length_m, 2.5);
  EXPECT_FALSE(parse_flags({"--max-segment-length", "2.5"}).options().merged_maps_only);  // a number: every cloud
  EXPECT_EQ(parse_flags({"--max-segment-length", "0"}).options().max_segment_length_m, 0.0);
  const PostProcessOptions automatic = parse_flags({"--max-segment-length", "2.5", "--max-segment-length", "auto"}).options();
  EXPECT_EQ(automatic.max_segment_length_m, kMergedMapPieceLength);
  EXPECT_TRUE(automatic.merged_maps_only);
  EXPECT_EQ(PostProcessFlags{}.options().max_segment_length_m, kMergedMapPieceLength);  // auto by default
  EXPECT_TRUE(PostProcessFlags{}.options().merged_maps_only);
  EXPECT_EQ(parse_flags({"--release-quirks"}).options().max_segment_length_m, 0.0);  // the release's cloud as it is
  PostProcessFlags flags;
  int i = 1;
  char* argv[] = {const_cast<char*>("cmd"), const_cast<char*>("--other")};
  EXPECT_FALSE(flags.parse("--other", 2, argv, i));
  EXPECT_EQ(i, 1);
}

}  // namespace
}  // namespace lc2wf

// The inference pipeline with small randomly initialised networks: shapes and bookkeeping, degenerate
// clouds (no segments, one segment, nothing above threshold) giving valid empty results with notes,
// checkpoint loading errors, and the preview PNG.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/constant_height_model.h"
#include "tests/common/tiny_weights.h"
#include "tests/common/windowed_box.h"
#include <algorithm>
#include <limits>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/geometry/segment_split.h"
#include "core/rng.h"
#include "core/util/cli.h"
#include "infer/batch_inference.h"
#include "infer/map_frame.h"
#include <Eigen/Geometry>
#include <cmath>
#include "dataset/sampling/sampling.h"
#include "model/inference.h"
#include "infer/preview.h"
#include "model/test_time_symmetry.h"
#include "dataset/geometry/network_frame.h"
#include "nn/checkpoint.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;


class Inference : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lc2wf_inference_test_" + std::to_string(::getpid()));
    test::write_tiny_weights(dir_);
    cloud_ = make_synthetic_line_cloud(make_rect_building("rect", RectBuildingSpec{}), 5);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  LineCloud cloud_;
};

PostProcessOptions keep_every_junction() {
  PostProcessOptions o;
  o.selection.min_confidence = 0.0;  // random weights are never confident: let every candidate through
  o.selection.max_offset_m = std::numeric_limits<double>::infinity();  // nor regressed near their sample points
  o.selection.corner.radius_m = 0.0;  // nor on the cloud's corners
  return o;
}

// The junction model run in `passes` passes and `views` views (the other selection options do not matter).
JunctionSelectionOptions run_as(int passes = 1, int views = 1) {
  JunctionSelectionOptions o;
  o.sampling_passes = passes;
  o.test_time_views = views;
  return o;
}

// More passes add candidates after the one-pass ones, which stay exactly as they were.
TEST_F(Inference, SamplingPassesAppendCandidatesToTheFirstPass) {
  const WireframePredictor predictor(dir_);
  const PredictedJunctions one = predict_junction_candidates(predictor.junction_net(), cloud_, run_as(1));
  const PredictedJunctions two = predict_junction_candidates(predictor.junction_net(), cloud_, run_as(2));
  ASSERT_EQ(one.positions.size(), 32u);
  ASSERT_EQ(two.positions.size(), 64u);
  ASSERT_EQ(two.confidence.size(), 64u);
  ASSERT_EQ(two.offset_m.size(), 64u);
  for (size_t k = 0; k < one.positions.size(); ++k) {
    EXPECT_NEAR((two.positions[k] - one.positions[k]).norm(), 0.0, 1e-9) << k;
    EXPECT_NEAR(two.confidence[k], one.confidence[k], 1e-9) << k;
  }
  // The second pass samples other points: its candidates are not the first pass's again.
  int moved = 0;
  for (size_t k = 0; k < one.positions.size(); ++k) moved += (two.positions[32 + k] - one.positions[k]).norm() > 1e-6;
  EXPECT_GT(moved, 16);
  PostProcessOptions o = keep_every_junction();
  o.selection.sampling_passes = 2;
  EXPECT_EQ(predictor.predict(cloud_, o).junctions.positions.size(), 64u);
  EXPECT_THROW(predict_junction_candidates(predictor.junction_net(), cloud_, run_as(0)), std::invalid_argument);
}

// A large cloud gets sample points for its size: 12 times the house's footprint is sampled in one pass per
// 40 m of its longer side (the first pass as before), the house itself in one; --metres-per-pass 0 turns it off.
TEST_F(Inference, ALargeCloudIsSampledInMorePasses) {
  const WireframePredictor predictor(dir_);
  LineCloud large = cloud_;
  for (Segment3& s : large.segments) s.a.head<2>() *= 12.0, s.b.head<2>() *= 12.0;
  const int passes = passes_for_extent(large.segments, 40.0);
  ASSERT_GE(passes, 3);
  EXPECT_EQ(passes_for_extent(cloud_.segments, 40.0), 1);
  EXPECT_EQ(predict_junction_candidates(predictor.junction_net(), cloud_, run_as(1)).positions.size(), 32u);
  EXPECT_EQ(predict_junction_candidates(predictor.junction_net(), large, run_as(1)).positions.size(), 32u * passes);
  JunctionSelectionOptions off = run_as(1);
  off.metres_per_pass = 0;
  EXPECT_EQ(predict_junction_candidates(predictor.junction_net(), large, off).positions.size(), 32u);
  const InferenceResult r = predictor.predict(large, keep_every_junction());
  EXPECT_EQ(r.junctions.positions.size(), 32u * passes);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.front().find("large cloud"), std::string::npos) << r.notes.front();
}

// The cloud turned about the vertical through the network frame's centre by `view`.
LineCloud turned(const LineCloud& cloud, const PlaneSymmetry& view) {
  const Vec3 c = NetworkFrame{}.centre_m;
  LineCloud out = cloud;
  for (Segment3& s : out.segments)
    for (Vec3* p : {&s.a, &s.b}) {
      Vec3 d = *p - c;
      view.apply(d.data());
      *p = c + d;
    }
  return out;
}

// Averaged over a group of views, the candidates turn with the cloud (the network alone does not): the
// views of the turned cloud are those of the cloud, and each offset is turned back before the mean.
TEST_F(Inference, TestTimeViewsMakeTheCandidatesTurnWithTheCloud) {
  const WireframePredictor predictor(dir_);
  JunctionNet& net = predictor.junction_net();
  const PredictedJunctions plain = predict_junction_candidates(net, cloud_, run_as(1, 1));
  EXPECT_EQ(predict_junction_candidates(net, cloud_, run_as()).confidence, plain.confidence);  // one view: as before
  for (const auto& [count, which] : {std::pair{2, 1}, std::pair{8, 4}}) {
    const PlaneSymmetry view = test_time_symmetries(8)[static_cast<size_t>(which)];
    const LineCloud other = turned(cloud_, view);
    const PredictedJunctions a = predict_junction_candidates(net, cloud_, run_as(1, count));
    const PredictedJunctions b = predict_junction_candidates(net, other, run_as(1, count));
    const PredictedJunctions b_plain = predict_junction_candidates(net, other, run_as(1, 1));
    ASSERT_EQ(a.positions.size(), 32u);
    ASSERT_EQ(b.positions.size(), 32u);
    double worst = 0.0, worst_plain = 0.0;
    for (size_t k = 0; k < a.positions.size(); ++k) {
      const Vec3 c = NetworkFrame{}.centre_m;
      Vec3 expect = a.positions[k] - c;
      view.apply(expect.data());
      expect += c;
      worst = std::max(worst, (b.positions[k] - expect).norm());
      EXPECT_NEAR(b.confidence[k], a.confidence[k], 1e-5) << count << " views, candidate " << k;
      EXPECT_NEAR(b.offset_m[k], a.offset_m[k], 1e-4) << count << " views, candidate " << k;
      Vec3 expect_plain = plain.positions[k] - c;
      view.apply(expect_plain.data());
      worst_plain = std::max(worst_plain, (b_plain.positions[k] - (expect_plain + c)).norm());
    }
    EXPECT_LT(worst, 1e-4) << count << " views";
    EXPECT_GT(worst_plain, 1e-3) << "one view already turns with the cloud: the test would not see a wrong mean";
  }
  PostProcessOptions o = keep_every_junction();
  o.selection.test_time_views = 4;
  EXPECT_EQ(predictor.predict(cloud_, o).junctions.positions.size(), 32u);
  EXPECT_THROW(predict_junction_candidates(net, cloud_, run_as(1, 3)), std::invalid_argument);
}

// The edge model's views: averaged over a group, a pair's class probabilities do not change when the
// cloud and its junctions turn (one view does).
TEST_F(Inference, EdgeTestTimeViewsMakePairClassesIndependentOfTheTurn) {
  const WireframePredictor predictor(dir_);
  const Vec3 c = NetworkFrame{}.centre_m;
  const std::vector<Vec3>& corners = cloud_.wireframe.junctions;
  ASSERT_GE(corners.size(), 4u);
  for (const auto& [count, which] : {std::pair{2, 1}, std::pair{8, 4}}) {
    const PlaneSymmetry view = test_time_symmetries(8)[static_cast<size_t>(which)];
    auto turn = [&](Vec3 p) {
      Vec3 d = p - c;
      view.apply(d.data());
      return Vec3(c + d);
    };
    std::vector<JunctionPair> pairs, turned_pairs;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        pairs.push_back({corners[i], corners[j], i, j});
        turned_pairs.push_back({turn(corners[i]), turn(corners[j]), i, j});
      }
    const LineCloud other = turned(cloud_, view);
    EdgeNet& net = predictor.edge_net();
    const std::vector<float> a = predict_pair_probabilities(net, cloud_, pairs, count);
    const std::vector<float> b = predict_pair_probabilities(net, other, turned_pairs, count);
    const std::vector<float> a1 = predict_pair_probabilities(net, cloud_, pairs, 1);
    const std::vector<float> b1 = predict_pair_probabilities(net, other, turned_pairs, 1);
    ASSERT_EQ(a.size(), pairs.size() * 5);
    ASSERT_EQ(b.size(), a.size());
    double worst = 0.0, worst_plain = 0.0, total = 0.0;
    for (size_t k = 0; k < a.size(); ++k) {
      worst = std::max(worst, static_cast<double>(std::abs(a[k] - b[k])));
      worst_plain = std::max(worst_plain, static_cast<double>(std::abs(a1[k] - b1[k])));
      total += a[k];
    }
    EXPECT_LT(worst, 1e-5) << count << " views";
    EXPECT_GT(worst_plain, 1e-4) << "one view is already independent of the turn: the test would not see a wrong mean";
    EXPECT_NEAR(total, static_cast<double>(pairs.size()), 1e-4);  // each pair's mean is still a distribution
  }
  PostProcessOptions o = keep_every_junction();
  o.edge_test_time_views = 3;
  EXPECT_THROW(predictor.predict(cloud_, o), std::invalid_argument);
}

// --max-segment-length runs the networks on the cut cloud: the same wireframe as cutting it first.
TEST_F(Inference, MaxSegmentLengthPredictsOnTheCutCloud) {
  const WireframePredictor predictor(dir_);
  PostProcessOptions o = keep_every_junction();
  o.max_segment_length_m = 0.7;
  o.merged_maps_only = false;
  PostProcessOptions as_is = keep_every_junction();
  as_is.max_segment_length_m = 0.0;
  as_is.selection.sampling_passes = o.cut_sampling_passes;  // a cut cloud is sampled in that many passes
  const InferenceResult cut = predictor.predict(cloud_, o);
  const InferenceResult first = predictor.predict(split_long_segments(cloud_, 0.7), as_is);
  const InferenceResult whole = predictor.predict(cloud_, as_is);
  ASSERT_EQ(cut.junctions.positions.size(), 3u * 32u);
  ASSERT_EQ(cut.junctions.positions.size(), first.junctions.positions.size());
  double differs = 0.0;
  for (size_t k = 0; k < cut.junctions.positions.size(); ++k) {
    EXPECT_EQ(cut.junctions.positions[k], first.junctions.positions[k]);
    differs += (cut.junctions.positions[k] - whole.junctions.positions[k]).norm();
  }
  EXPECT_GT(differs, 1e-3) << "the cut changed nothing: the test would not see the option ignored";
  EXPECT_EQ(cut.wireframe.wireframe.edges, first.wireframe.wireframe.edges);
  ASSERT_FALSE(cut.notes.empty());
  EXPECT_THAT(cut.notes.front(), HasSubstr("segments cut at 0.7 m"));
  EXPECT_THAT(cut.notes.front(), HasSubstr("sampled in 3 passes"));
  // More passes asked for than the cut's: the selection's count wins; an uncut cloud keeps the selection's.
  o.selection.sampling_passes = 4;
  EXPECT_EQ(predictor.predict(cloud_, o).junctions.positions.size(), 4u * 32u);
  EXPECT_EQ(whole.junctions.positions.size(), 3u * 32u);
  EXPECT_EQ(predictor.predict(cloud_, keep_every_junction()).junctions.positions.size(), 32u);
  o.selection.sampling_passes = 1;
  o.cut_sampling_passes = 9;
  EXPECT_THROW(predictor.predict(cloud_, o), std::invalid_argument);
  o.cut_sampling_passes = 3;
  o.max_segment_length_m = 0.01;
  EXPECT_THROW(predictor.predict(cloud_, o), std::invalid_argument);
}

// The default (auto) cuts a merged line map read from another program's file and leaves per-view fragment
// clouds, and our own files whatever they hold, as they are.
TEST_F(Inference, MaxSegmentLengthAutoCutsOnlyMergedLineMaps) {
  const WireframePredictor predictor(dir_);
  LineCloud merged = cloud_;  // one line per GT edge: nothing overlaps it
  merged.segments.clear();
  merged.labels.clear();
  merged.support.clear();
  merged.external_line_map = true;
  for (const auto& [j, k] : cloud_.wireframe.edges) merged.segments.push_back({cloud_.wireframe.junctions[j], cloud_.wireframe.junctions[k]});
  LineCloud fragments = merged;  // each edge seen by three views: overlapping pieces
  fragments.segments.clear();
  for (const Segment3& s : merged.segments)
    for (double t0 : {0.0, 0.1, 0.2}) fragments.segments.push_back({s.a + t0 * (s.b - s.a), s.a + (t0 + 0.8) * (s.b - s.a)});
  ASSERT_LT(overlapped_long_fraction(merged, kMergedMapPieceLength), kMergedMapOverlap);
  ASSERT_GE(overlapped_long_fraction(fragments, kMergedMapPieceLength), kMergedMapOverlap);
  PostProcessOptions automatic = keep_every_junction(), off = keep_every_junction();
  off.max_segment_length_m = 0.0;
  const InferenceResult m = predictor.predict(merged, automatic);
  EXPECT_THAT(m.notes.front(), HasSubstr("a merged line map (0 % of its long segments overlapped by another)"));
  EXPECT_TRUE(m.segments_cut);
  PostProcessOptions cut_first = off;
  cut_first.selection.sampling_passes = automatic.cut_sampling_passes;
  EXPECT_EQ(m.junctions.positions,
            predictor.predict(split_long_segments(merged, kMergedMapPieceLength), cut_first).junctions.positions);
  const auto not_cut = [&](const LineCloud& c) {
    const InferenceResult r = predictor.predict(c, automatic);
    EXPECT_FALSE(r.segments_cut);
    for (const std::string& note : r.notes) EXPECT_THAT(note, ::testing::Not(HasSubstr("cut")));
    EXPECT_EQ(r.junctions.positions, predictor.predict(c, off).junctions.positions);
  };
  not_cut(fragments);
  LineCloud ours = merged;  // the same lines from one of our files: ours are per-view fragments by making
  ours.external_line_map = false;
  not_cut(ours);
}

// A line map in a foreign frame (a fifth of a metre per unit, z up) with no scale given: the weights' height
// model reads the building's height and the map comes back in metres; without a model the search runs;
// a given building height wins over both. The report says which, with the model's uncertainty.
TEST_F(Inference, MapFrameTakesTheHeightModelsReading) {
  const WireframePredictor predictor(dir_);
  LineCloud map = cloud_;
  map.external_line_map = true;
  for (Segment3& s : map.segments) s = {5.0 * s.a, 5.0 * s.b};
  MapFrameOptions o;
  o.enabled = true, o.up = "z";
  o.height_model = test::constant_height_model(9.0);
  const FramedInference f = infer_in_metric_frame(predictor, map, keep_every_junction(), o);
  EXPECT_EQ(f.report["scale_source"], "line statistics") << f.report.dump();
  EXPECT_NEAR(f.report["line_statistics"]["height_m"].get<double>(), 9.0, 1e-9);
  EXPECT_EQ(f.report["line_statistics"]["used"], true);
  EXPECT_FALSE(f.report.contains("scale_search"));
  EXPECT_NEAR(f.report["height_m"].get<double>(), 9.0, 0.5);  // the frame's height quantiles, not the top
  EXPECT_THAT(f.summary, HasSubstr("read from the lines"));
  MapFrameOptions given = o;
  given.building_height_m = 12.0;
  EXPECT_EQ(infer_in_metric_frame(predictor, map, keep_every_junction(), given).report["scale_source"], "building height");
  MapFrameOptions none = o;
  none.height_model.reset();
  none.search.coarse_steps = 2, none.search.refine_rounds = 0;  // two runs of the networks are enough here
  const FramedInference s = infer_in_metric_frame(predictor, map, keep_every_junction(), none);
  EXPECT_EQ(s.report["scale_source"], "scale search");
  EXPECT_FALSE(s.report.contains("line_statistics"));
}

// A facade photographed from the street as a photogrammetry tool leaves it (y down, z into the facade, its own
// scale): the lines say the facade's normal is what they are perpendicular to, the height model's clouds of
// street captures say which way is up and which end is the ground; frame.json says so.
TEST_F(Inference, MapFrameFindsUpOfAFacadeFromTheStreet) {
  const WireframePredictor predictor(dir_);
  LineCloud map;
  map.external_line_map = true;
  const Eigen::Matrix3d to_map(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));  // z up -> y down
  for (const Segment3& s : test::street_facade(4, 3.2, 22, 77)) map.segments.push_back({0.4 * (to_map * s.a), 0.4 * (to_map * s.b)});
  MapFrameOptions o;
  o.enabled = true;
  o.height_model = test::street_facade_model();
  const FramedInference f = infer_in_metric_frame(predictor, map, keep_every_junction(), o);
  const Vec3 up(f.report["up_input"][0].get<double>(), f.report["up_input"][1].get<double>(), f.report["up_input"][2].get<double>());
  EXPECT_GT(up.dot(-Vec3::UnitY()), std::cos(3 * M_PI / 180)) << f.report.dump();
  EXPECT_EQ(f.report["up_evidence"]["rule"], "nearest the height model's clouds");
  EXPECT_EQ(f.report["up_evidence"]["ground"], "the end the nearest clouds' ends say");
  EXPECT_LT(f.report["up_evidence"]["statistics_distance"].get<double>(), f.report["up_evidence"]["runner_up_distance"].get<double>());
  // Whether the runner-up came close is said, and only then warned of (also in the wireframe's notes).
  const bool uncertain = f.report["up_evidence"]["uncertain"].get<bool>();
  EXPECT_EQ(uncertain, f.report["up_evidence"]["runner_up_distance"].get<double>() <
                           (1 + kUncertainUpMargin) * f.report["up_evidence"]["statistics_distance"].get<double>());
  EXPECT_EQ(f.warning.empty(), !uncertain);
  EXPECT_EQ(std::count(f.inference.notes.begin(), f.inference.notes.end(), f.warning), uncertain ? 1 : 0);
  // Every direction tried is listed with its statistics distance; the chosen one among them.
  const auto& tried = f.report["up_evidence"]["tried"];
  ASSERT_EQ(tried.size(), f.report["up_evidence"]["candidates"].get<size_t>());
  int chosen = 0;
  for (const auto& t : tried) {
    const Vec3 d(t["direction"][0].get<double>(), t["direction"][1].get<double>(), t["direction"][2].get<double>());
    chosen += std::abs(d.dot(up)) > 0.999 && t["statistics_distance"] == f.report["up_evidence"]["statistics_distance"];
  }
  EXPECT_EQ(chosen, 1);
  MapFrameOptions given = o;  // a direction the user knows (a survey's gravity) wins, made unit length
  given.up = "0.02,-2,0";
  const FramedInference g = infer_in_metric_frame(predictor, map, keep_every_junction(), given);
  EXPECT_NEAR(g.report["up_input"][1].get<double>(), Vec3(0.02, -2, 0).normalized().y(), 1e-12);
  EXPECT_EQ(g.report["up_source"], "given 0.02,-2,0");
  EXPECT_FALSE(g.report.contains("up_evidence"));
  for (const std::string bad : {"0,0,0", "1,nan,0", "1,2", "1,2,3,4", "up"}) {
    given.up = bad;
    EXPECT_THROW(given.Check(), std::invalid_argument) << bad;
  }
  MapFrameOptions plain = o;  // without a model the perpendicular share decides, and says so
  plain.height_model.reset();
  plain.scale = 1.0;
  EXPECT_EQ(infer_in_metric_frame(predictor, map, keep_every_junction(), plain).report["up_evidence"]["rule"], "most line length perpendicular");
}

TEST_F(Inference, RunsBothNetworksOnASyntheticCloud) {
  const WireframePredictor predictor(dir_);
  const InferenceResult r = predictor.predict(cloud_, keep_every_junction());
  EXPECT_EQ(r.junctions.positions.size(), 32u);  // one candidate per sample point
  for (double c : r.junctions.confidence) EXPECT_TRUE(c >= 0.0 && c <= 1.0);
  EXPECT_GE(r.selection.positions.size(), 2u);
  EXPECT_NO_THROW(r.wireframe.check("prediction"));
  EXPECT_NO_THROW(r.candidates.check("candidates"));
  // Deterministic: the same input gives the same output.
  const InferenceResult again = predictor.predict(cloud_, keep_every_junction());
  EXPECT_EQ(again.junctions.confidence, r.junctions.confidence);
  EXPECT_EQ(again.wireframe.edge_scores, r.wireframe.edge_scores);
}

// Each candidate carries how far it was regressed from its sample point, so --max-offset can screen it.
TEST_F(Inference, CandidatesCarryTheirOffsetsForMaxOffset) {
  const WireframePredictor predictor(dir_);
  const InferenceResult all = predictor.predict(cloud_, keep_every_junction());
  ASSERT_EQ(all.junctions.offset_m.size(), all.junctions.positions.size());
  std::vector<double> sorted = all.junctions.offset_m;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_GE(sorted.front(), 0.0);
  PostProcessOptions near = keep_every_junction();
  near.selection.max_offset_m = sorted[sorted.size() / 2];  // the nearer half of the candidates
  const InferenceResult screened = predictor.predict(cloud_, near);
  EXPECT_LT(screened.selection.kept.size(), all.selection.kept.size());
  for (int k : screened.selection.kept) EXPECT_LE(all.junctions.offset_m[static_cast<size_t>(k)], near.selection.max_offset_m);
}

TEST_F(Inference, PairProbabilitiesAreDistributions) {
  const WireframePredictor predictor(dir_);
  std::vector<JunctionPair> pairs(3);
  pairs[0].u = Vec3(0, 0, 4), pairs[0].v = Vec3(5, 0, 4);
  pairs[1].u = Vec3(1, 1, 1), pairs[1].v = Vec3(2, 2, 2);
  pairs[2].u = Vec3(-3, 0, 0), pairs[2].v = Vec3(3, 0, 0);
  const std::vector<float> p = predict_pair_probabilities(predictor.edge_net(), cloud_, pairs);
  ASSERT_EQ(p.size(), 15u);
  for (int k = 0; k < 3; ++k) {
    double total = 0;
    for (int c = 0; c < 5; ++c) total += p[k * 5 + c];
    EXPECT_NEAR(total, 1.0, 1e-5);
  }
}

TEST_F(Inference, DegenerateCloudsGiveEmptyWireframesWithNotes) {
  const WireframePredictor predictor(dir_);
  LineCloud empty;
  empty.name = "empty";
  InferenceResult r = predictor.predict(empty, PostProcessOptions{});
  EXPECT_TRUE(r.wireframe.wireframe.edges.empty());
  EXPECT_TRUE(r.junctions.positions.empty());
  ASSERT_FALSE(r.notes.empty());
  EXPECT_THAT(r.notes.front(), HasSubstr("no segments"));

  LineCloud one;
  one.name = "one";
  one.segments.push_back({Vec3(0, 0, 0), Vec3(1, 0, 0)});
  for (const PostProcessOptions& o : {PostProcessOptions{}, keep_every_junction(), PostProcessOptions::release_quirks()}) {
    r = predictor.predict(one, o);
    EXPECT_NO_THROW(r.wireframe.check("one"));
  }
  // Nothing above a 0.999999 confidence: fewer than 2 junctions, a note, no edge.
  PostProcessOptions strict;
  strict.selection.min_confidence = 0.999999;
  r = predictor.predict(cloud_, strict);
  EXPECT_TRUE(r.wireframe.wireframe.edges.empty());
  EXPECT_FALSE(r.notes.empty());
  // Every pair below the connect threshold: no candidate edge.
  PostProcessOptions no_edges = keep_every_junction();
  no_edges.connect_threshold = 0.999999;
  r = predictor.predict(cloud_, no_edges);
  EXPECT_TRUE(r.wireframe.wireframe.edges.empty());
  EXPECT_FALSE(r.notes.empty());
}

TEST_F(Inference, PairSupportScreensThePairsTheEdgeModelSees) {
  const WireframePredictor predictor(dir_);
  const InferenceResult all = predictor.predict(cloud_, keep_every_junction());
  PostProcessOptions screened = keep_every_junction();
  screened.pair_support.min_support = 0.5;
  const InferenceResult some = predictor.predict(cloud_, screened);
  EXPECT_EQ(some.selection.positions, all.selection.positions);  // the same junctions
  EXPECT_LT(some.pairs.size(), all.pairs.size());
  const SegmentSupport support(cloud_.segments);
  size_t expected = 0;
  for (const JunctionPair& p : all.pairs) {
    const bool keep = (p.v - p.u).norm() < 1.0 || support.support(p.u, p.v, 0.35, 20.0) >= 0.5;
    expected += keep;
  }
  EXPECT_EQ(some.pairs.size(), expected);
  EXPECT_NO_THROW(some.wireframe.check("screened"));
  // No pair passes: an empty wireframe and a note saying why.
  screened.pair_support.min_support = 1.0;
  screened.pair_support.radius_m = 1e-9;
  screened.pair_support.keep_shorter_than_m = 0.0;
  const InferenceResult none = predictor.predict(cloud_, screened);
  EXPECT_TRUE(none.pairs.empty());
  EXPECT_TRUE(none.wireframe.wireframe.edges.empty());
  ASSERT_FALSE(none.notes.empty());
  EXPECT_THAT(none.notes.back(), HasSubstr("line support"));
}

// A cloud with thousands of clutter lines yields hundreds of junctions; the edge model still sees at most
// max_pairs pairs, each junction in at most max_pairs_per_junction of them (counted, not timed).
TEST_F(Inference, ClutteredCloudsRunOnABoundedNumberOfPairs) {
  const WireframePredictor predictor(dir_);
  LineCloud cluttered = cloud_;
  Rng rng(11);
  for (int k = 0; k < 4000; ++k) {
    const Vec3 a(rng.next_uniform(-40, 40), rng.next_uniform(-40, 40), rng.next_uniform(0, 20));
    cluttered.segments.push_back({a, a + Vec3(rng.next_uniform(-2, 2), rng.next_uniform(-2, 2), rng.next_uniform(-2, 2))});
  }
  PostProcessOptions o = keep_every_junction();
  o.selection.sampling_passes = 8;  // 256 sample points of the tiny model's 32
  const InferenceResult r = predictor.predict(cluttered, o);
  const size_t n = r.selection.positions.size();
  ASSERT_GT(n * (n - 1) / 2, 10u * static_cast<size_t>(o.pair_cap.max_pairs));  // the cap must bite
  EXPECT_LE(r.pairs.size(), static_cast<size_t>(o.pair_cap.max_pairs));
  EXPECT_GT(r.pairs.size(), static_cast<size_t>(o.pair_cap.max_pairs) / 2);
  std::vector<int> per_junction(n, 0);
  for (const JunctionPair& p : r.pairs) ++per_junction[p.i], ++per_junction[p.j];
  EXPECT_LE(*std::max_element(per_junction.begin(), per_junction.end()), o.pair_cap.max_pairs_per_junction);
  EXPECT_THAT(testing::PrintToString(r.notes), HasSubstr("capped to the"));
  EXPECT_NO_THROW(r.wireframe.check("cluttered"));
  // The cloud without clutter has fewer pairs than the cap: the same pairs as with no cap at all.
  PostProcessOptions uncapped = keep_every_junction();
  uncapped.pair_cap.max_pairs = 0;
  const InferenceResult plain = predictor.predict(cloud_, keep_every_junction());
  const InferenceResult plain_uncapped = predictor.predict(cloud_, uncapped);
  ASSERT_EQ(plain.pairs.size(), plain_uncapped.pairs.size());
  EXPECT_EQ(plain.wireframe.wireframe.edges, plain_uncapped.wireframe.wireframe.edges);
}

TEST_F(Inference, BatchSkipsACloudWhoseStemCannotNameAnOutput) {
  // "..lcloud" has the stem "." and "...lcloud" the stem "..": the batch used to end on them, naming
  // neither file; now they are skipped by name and the other clouds are written.
  const fs::path in = dir_ / "clouds", out = dir_ / "out";
  for (const char* name : {"..lcloud", "...lcloud", "ok.lcloud"}) write_line_cloud(in / name, cloud_);
  BatchInferenceOptions o;
  o.quiet = true;
  ::testing::internal::CaptureStderr();
  const BatchInferenceSummary s = infer_clouds(WireframePredictor(dir_), {in / "..lcloud", in / "...lcloud", in / "ok.lcloud"}, out, o);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(s.failed, 2);
  EXPECT_EQ(s.buildings, 1);
  EXPECT_NE(err.find((in / "..lcloud").string() + ": its stem '.' cannot name an output file"), std::string::npos) << err;
  EXPECT_NE(err.find((in / "...lcloud").string() + ": its stem '..' cannot name an output file"), std::string::npos) << err;
  EXPECT_TRUE(fs::exists(out / "ok.obj"));
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 2);  // ok.obj, ok.json
}

TEST_F(Inference, BatchRunsInTheAskedPrecisionAndRestoresTheProcessOne) {
  const fs::path in = dir_ / "clouds", wide = dir_ / "wide";
  write_line_cloud(in / "b.lcloud", cloud_);
  test::write_tiny_weights(wide, 32);  // products through the GEMM, where the precision applies
  std::string scores[2];
  for (const MatmulPrecision precision : {MatmulPrecision::kFp32, MatmulPrecision::kBf16}) {
    BatchInferenceOptions o;
    o.quiet = true;
    o.post = keep_every_junction();
    o.post.connect_threshold = 1e-6;  // random weights: keep every pair so that scores are written
    o.precision = precision;
    const fs::path out = dir_ / ("out_" + to_string(precision));
    const BatchInferenceSummary s = infer_clouds(WireframePredictor(wide), {in / "b.lcloud"}, out, o);
    EXPECT_EQ(s.buildings, 1);
    EXPECT_EQ(s.precision, to_string(precision));
    EXPECT_EQ(matmul_precision(), MatmulPrecision::kFp32);  // the batch's choice does not leak
    std::ifstream json(out / "b.json");
    scores[precision == MatmulPrecision::kBf16] = std::string(std::istreambuf_iterator<char>(json), {});
  }
  // bf16 operands move the scores (rounding), so the option reaches the networks.
  EXPECT_FALSE(scores[0].empty());
  EXPECT_NE(scores[0], scores[1]);
  EXPECT_THROW(precision_flag("fp16"), UsageError);
  EXPECT_EQ(precision_flag("bf16"), MatmulPrecision::kBf16);
}

TEST_F(Inference, WrongOrMissingWeightsAreNamed) {
  try {
    WireframePredictor(dir_ / "edge.safetensors", dir_ / "edge.safetensors");
    FAIL() << "a junction model was loaded from an edge checkpoint";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("edge.safetensors")) << e.what();
  }
  EXPECT_ANY_THROW(WireframePredictor(dir_ / "missing"));
}

TEST_F(Inference, PreviewIsAPng) {
  const WireframePredictor predictor(dir_);
  const InferenceResult r = predictor.predict(cloud_, keep_every_junction());
  write_preview(dir_ / "p.png", cloud_, r.wireframe.wireframe, &cloud_.wireframe);
  std::ifstream in(dir_ / "p.png", std::ios::binary);
  std::string head(8, '\0');
  in.read(head.data(), 8);
  EXPECT_EQ(head.substr(1, 3), "PNG");
  EXPECT_THROW(write_preview(dir_ / "q.png", cloud_, r.wireframe.wireframe, nullptr, PreviewOptions{10, 10}),
               std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

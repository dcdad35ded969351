#include "model/inference.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/parallel.h"
#include "core/tensor.h"
#include "dataset/selection/pair_cap.h"
#include "dataset/sampling/sampling.h"
#include "dataset/selection/pair_support.h"
#include "dataset/photo/camera_coverage.h"
#include "model/edge_support.h"
#include "dataset/geometry/segment_split.h"
#include "model/patch_tensors.h"
#include "model/test_time_symmetry.h"

#include "core/util/number_format.h"
#include "core/util/seconds_since.h"

namespace lc2wf {
namespace {

using Clock = std::chrono::steady_clock;

// Puts a module in eval mode for a scope and restores its previous mode.
class EvalScope {
 public:
  explicit EvalScope(Module& m) : module_(m), was_training_(m.is_training()) { module_.eval(); }
  ~EvalScope() { module_.train(was_training_); }

 private:
  Module& module_;
  bool was_training_;
  NoGradGuard no_grad_;
};

// Row-wise softmax of P x C logits, rounded to float as the probabilities are reported.
std::vector<float> softmax_rows(const std::vector<double>& logits, size_t C) {
  std::vector<float> probs(logits.size());
  for (size_t p = 0; p * C < logits.size(); ++p) {
    const double* z = &logits[p * C];
    double zmax = z[0], total = 0.0;
    for (size_t c = 1; c < C; ++c) zmax = std::max(zmax, z[c]);
    for (size_t c = 0; c < C; ++c) total += std::exp(z[c] - zmax);
    for (size_t c = 0; c < C; ++c) probs[p * C + c] = static_cast<float>(std::exp(z[c] - zmax) / total);
  }
  return probs;
}

}  // namespace

JunctionSampleOptions junction_sample_options(const JunctionNetConfig& config) {
  JunctionSampleOptions o;
  o.sampling.num_samples = static_cast<int>(config.lpt.patches);
  o.patch.lines_per_patch = static_cast<int>(config.lpt.lines_per_patch);
  o.patch.negative_noise_count = (o.patch.lines_per_patch + 1) / 2;  // the release's 16 of 32: half the slots
  o.patch.distance = parse_patch_distance(config.patch_distance, "junction_net.patch_distance");
  o.augment_enabled = false;
  return o;
}

PatchOptions pair_patch_options(const EdgeNetConfig& config) {
  PatchOptions o;
  o.lines_per_patch = static_cast<int>(config.lpt.lines_per_patch / 2);
  o.negative_noise_count = (o.lines_per_patch + 1) / 2;  // unused for pairs, kept valid
  return o;
}

PredictedJunctions predict_junction_candidates(JunctionNet& net, const LineCloud& cloud,
                                               const JunctionSelectionOptions& selection) {
  selection.Check();
  if (cloud.segments.empty()) return {};
  // A large cloud gets more sample points: the one rule for inference, validation and the hand-off.
  const int passes = std::max(selection.sampling_passes, passes_for_extent(cloud.segments, selection.metres_per_pass));
  const std::vector<PlaneSymmetry> views = test_time_symmetries(selection.test_time_views);
  JunctionSampleOptions options = junction_sample_options(net.config());
  options.sampling.passes = passes;
  options.sampling.seeds = selection.density_seeds;
  JunctionPatches patches = make_junction_sample(cloud, options, 0);
  // Patches are stored pass after pass, so each pass is one item of a batch the model reads G at a time.
  patches.batch = passes;
  patches.num_patches /= passes;
  // Each view is `passes` more items of the same batch: the same patches, their vectors transformed.
  JunctionPatches viewed = patches;
  viewed.batch = passes * static_cast<int>(views.size());
  for (size_t v = 1; v < views.size(); ++v) {
    std::vector<float> features = patches.features;
    transform_patch_features(features, JunctionPatches::kFeatures, views[v]);
    viewed.features.insert(viewed.features.end(), features.begin(), features.end());
    viewed.padded.insert(viewed.padded.end(), patches.padded.begin(), patches.padded.end());
  }
  const PatchInput in = junction_input(viewed);
  EvalScope scope(net);
  const JunctionOutput y = net.forward(in.x, in.mask);
  std::vector<double> confidence = junction_confidences(y), offsets = y.offsets.to_vector();
  // The mean over views of the probabilities and of the offsets rotated back into the cloud's frame; the
  // offset length that max_offset_m screens is the mean of the views' lengths, since views that disagree
  // on a far vote's direction would shorten their mean vector.
  const size_t n = static_cast<size_t>(patches.batch) * static_cast<size_t>(patches.num_patches);
  std::vector<double> reach(n, 0.0);
  for (size_t v = 0; v < views.size(); ++v)
    for (size_t k = 0; k < n; ++k) {
      double* o = &offsets[3 * (v * n + k)];
      reach[k] += std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
      if (v == 0) continue;
      views[v].apply_inverse(o);
      confidence[k] += confidence[v * n + k];
      for (size_t c = 0; c < 3; ++c) offsets[3 * k + c] += o[c];
    }
  confidence.resize(n), offsets.resize(3 * n);
  const double count = static_cast<double>(views.size());
  for (double& c : confidence) c /= count;
  for (double& o : offsets) o /= count;
  std::vector<PredictedJunctions> per_pass = junction_candidates(confidence, offsets, patches, options.patch.frame);
  if (views.size() > 1)
    for (size_t k = 0; k < n; ++k)
      per_pass[k / patches.num_patches].offset_m[k % patches.num_patches] = reach[k] / count * options.patch.frame.scale_m;
  PredictedJunctions all = std::move(per_pass.at(0));
  for (size_t p = 1; p < per_pass.size(); ++p) {
    const PredictedJunctions& more = per_pass[p];
    all.positions.insert(all.positions.end(), more.positions.begin(), more.positions.end());
    all.confidence.insert(all.confidence.end(), more.confidence.begin(), more.confidence.end());
    all.offset_m.insert(all.offset_m.end(), more.offset_m.begin(), more.offset_m.end());
  }
  return all;
}

Tensor predict_pair_logits(EdgeNet& net, const LineCloud& cloud, const std::vector<JunctionPair>& pairs) {
  const PairPatches patches = build_pair_patches(SegmentSet(cloud.segments), pairs, pair_patch_options(net.config()));
  const PatchInput in = pair_input(patches);
  EvalScope scope(net);
  return net.forward(in.x, in.mask);
}

std::vector<float> predict_pair_probabilities(EdgeNet& net, const LineCloud& cloud, const std::vector<JunctionPair>& pairs,
                                              int views_count) {
  if (pairs.empty()) return {};
  const std::vector<PlaneSymmetry> views = test_time_symmetries(views_count);
  const size_t C = static_cast<size_t>(net.config().num_classes);
  const PairPatches patches = build_pair_patches(SegmentSet(cloud.segments), pairs, pair_patch_options(net.config()));
  EvalScope scope(net);
  std::vector<double> mean;
  // One view at a time: a building's pairs attend to each other, so each view is one forward pass.
  for (const PlaneSymmetry& view : views) {
    PairPatches viewed = patches;
    transform_patch_features(viewed.features, PairPatches::kFeatures, view);
    const PatchInput in = pair_input(viewed);
    const std::vector<float> probs = softmax_rows(net.forward(in.x, in.mask).to_vector(), C);
    mean.resize(probs.size(), 0.0);
    for (size_t k = 0; k < probs.size(); ++k) mean[k] += probs[k];
  }
  std::vector<float> out(mean.size());
  for (size_t k = 0; k < mean.size(); ++k) out[k] = static_cast<float>(mean[k] / static_cast<double>(views.size()));
  return out;
}

InferenceResult predict_wireframe(EdgeNet& edge_net, const LineCloud& cloud, const PredictedJunctions& junctions,
                                  const PostProcessOptions& options, const Wireframe* label_against, Tensor* logits) {
  InferenceResult r;
  r.junctions = junctions;
  auto t0 = Clock::now();
  r.selection = select_junctions(junctions, cloud.segments, options.selection);
  r.notes = r.selection.notes;
  r.pairs = supported_pairs(selection_pairs(r.selection, label_against, PairSamplingOptions{}.fp_distance_m),
                            cloud.segments, options.pair_support);
  if (const size_t before = r.pairs.size(); before > 0) {
    r.pairs = capped_pairs(r.pairs, cloud.segments, options.pair_cap, options.pair_support, num_threads());
    if (r.pairs.size() < before)
      r.notes.push_back(std::to_string(before) + " pairs of " + std::to_string(r.selection.positions.size()) +
                        " junctions capped to the " + std::to_string(r.pairs.size()) + " with the most line support");
  }
  r.post_seconds = seconds_since(t0);
  if (r.pairs.empty() && r.selection.positions.size() >= 2)
    r.notes.push_back("no pair of junctions has line support >= " + format_number("%g", options.pair_support.min_support) +
                      ": empty wireframe");
  if (r.pairs.empty()) return r;  // otherwise select_junctions' note says why

  t0 = Clock::now();
  const size_t C = static_cast<size_t>(edge_net.config().num_classes);
  std::vector<float> probs;
  if (logits) {  // validation's loss needs the logits of the one view it trains on
    *logits = predict_pair_logits(edge_net, cloud, r.pairs);
    probs = softmax_rows(logits->to_vector(), C);
  } else {
    probs = predict_pair_probabilities(edge_net, cloud, r.pairs, options.edge_test_time_views);
  }
  r.edge_seconds = seconds_since(t0);

  t0 = Clock::now();
  PostProcessInput in;
  in.junctions = r.selection.positions;
  in.confidences = r.selection.confidences;
  for (size_t p = 0; p < r.pairs.size(); ++p)
    in.pairs.push_back({r.pairs[p].i, r.pairs[p].j, probs[p * C + kPairIdentical], probs[p * C + kPairConnected]});
  PostProcessResult post = post_process(in, options);
  const EdgeSupportOptions& support = options.edge_support;
  // A partial capture: the cloud's cameras leave a side of the post-processed wireframe unseen.
  const bool ask_partial = (support.partial_captures_only && support.enabled()) || options.flat_parts.enabled();
  const bool partial = ask_partial && !cloud.cameras.empty() && [&] {
    const CameraCoverage c = camera_coverage(cloud.cameras, post.wireframe.wireframe, cloud.segments);
    return std::any_of(c.sides.begin(), c.sides.end(), [](const SideCoverage& s) { return !s.seen; });
  }();
  JudgedEdges judged = JudgedEdges::every_edge;
  if (support.partial_captures_only && support.enabled() && !partial) judged = JudgedEdges::over_connected_only;  // nothing to tell the unseen from
  SupportedEdges seen = keep_supported_edges(post.wireframe, cloud.segments, cloud.cameras, support, judged);
  r.wireframe = std::move(seen.wireframe);
  r.candidates = std::move(post.candidates);
  r.notes.insert(r.notes.end(), post.notes.begin(), post.notes.end());
  const bool cameras_asked = judged == JudgedEdges::every_edge && !cloud.cameras.empty() && support.min_cameras > 0;
  if (seen.dropped_edges > 0)
    r.notes.push_back(std::to_string(seen.dropped_edges) + " edge(s)" +
                      (judged == JudgedEdges::every_edge
                           ? std::string()
                           : " of junctions with > " + std::to_string(support.judge_degree_above) + " edges") +
                      " with line support < " +
                      format_number("%g", judged == JudgedEdges::every_edge ? support.min_support : support.judge_min_support) +
                      " of their length" +
                      (cameras_asked ? " and seen by < " + std::to_string(support.min_cameras) + " cameras"
                                     : std::string()) +
                      " dropped, and " + std::to_string(seen.dropped_junctions) + " junction(s) left without an edge");
  if (options.flat_parts.enabled() && (partial || !options.flat_parts.partial_captures_only)) {
    FlatPartsDropped flat = drop_flat_parts(r.wireframe, options.flat_parts);
    r.wireframe = std::move(flat.wireframe);
    if (flat.dropped_parts > 0)
      r.notes.push_back(std::to_string(flat.dropped_parts) + " flat part(s) of < " + std::to_string(options.flat_parts.max_edges) +
                        " edges apart from the largest dropped (" + std::to_string(flat.dropped_edges) + " edge(s))");
  }
  if (r.wireframe.wireframe.edges.empty()) r.notes.push_back("no edge survived post-processing: empty wireframe");
  r.post_seconds += seconds_since(t0);
  return r;
}

WireframePredictor::WireframePredictor(const std::filesystem::path& dir)
    : WireframePredictor(dir / "junction.safetensors", dir / "edge.safetensors") {}

WireframePredictor::WireframePredictor(const std::filesystem::path& junction_weights,
                                       const std::filesystem::path& edge_weights)
    : junction_(load_junction_net(junction_weights)), edge_(load_edge_net(edge_weights)) {}

InferenceResult WireframePredictor::predict(const LineCloud& input, const PostProcessOptions& options) const {
  options.Check();  // before the cut, so a bad length is reported as the option it is
  const auto t0 = Clock::now();
  const double cut = options.max_segment_length_m;
  const bool ask = cut > 0.0 && (!options.merged_maps_only || input.external_line_map);
  const double overlapped = ask && options.merged_maps_only ? overlapped_long_fraction(input, cut) : 0.0;
  const bool cut_it = ask && overlapped < kMergedMapOverlap;
  LineCloud split;
  if (cut_it) split = split_long_segments(input, cut);
  const LineCloud& cloud = cut_it ? split : input;
  JunctionSelectionOptions sampling = options.selection;
  if (cut_it) sampling.sampling_passes = std::max(sampling.sampling_passes, options.cut_sampling_passes);
  const int by_extent = passes_for_extent(cloud.segments, sampling.metres_per_pass);  // for the note only
  const bool widened = by_extent > sampling.sampling_passes;
  const PredictedJunctions junctions = predict_junction_candidates(*junction_, cloud, sampling);
  const double junction_seconds = seconds_since(t0);
  InferenceResult r = predict_wireframe(*edge_, cloud, junctions, options);
  r.junction_seconds = junction_seconds;
  if (cloud.segments.empty()) r.notes.insert(r.notes.begin(), "line cloud has no segments: no junction candidates");
  r.segments_cut = cut_it;
  if (widened)
    r.notes.insert(r.notes.begin(), "a large cloud: sampled in " + std::to_string(by_extent) + " passes (one per " +
                                        format_number("%g", sampling.metres_per_pass) + " m of its longer side)");
  if (cut_it)
    r.notes.insert(r.notes.begin(),
                   (options.merged_maps_only ? "a merged line map (" + format_number("%.0f", 100 * overlapped) +
                                                   " % of its long segments overlapped by another): "
                                             : std::string()) +
                       std::to_string(input.segments.size()) + " segments cut at " +
                       format_number("%g", cut) + " m into " + std::to_string(cloud.segments.size()) + ", sampled in " +
                       std::to_string(sampling.sampling_passes) + " passes");
  return r;
}

InferenceResult WireframePredictor::predict_from_junctions(const LineCloud& cloud, const PredictedJunctions& junctions,
                                                           const PostProcessOptions& options) const {
  return predict_wireframe(*edge_, cloud, junctions, options);
}

}  // namespace lc2wf

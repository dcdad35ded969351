// Running the two networks on a line cloud, as the release's inference does: junction sampling and
// patches -> JunctionNet -> junction candidates (metres, confidences) -> select_junctions (the rule the
// training pairs use too) -> every pair of the selection -> EdgeNet over every pair of the building at
// once (its patch encoder attends across pairs) -> post_process -> ScoredWireframe. Degenerate clouds (no segments, < 2 junctions, no candidate edge) give
// a valid, possibly empty, wireframe and notes saying why; they never throw.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "dataset/geometry/line_cloud.h"
#include "dataset/sampling/pair_sampling.h"
#include "dataset/sampling/network_input.h"
#include "model/post_process.h"
#include "nn/edge_net.h"
#include "nn/junction_net.h"
#include "nn/model_checkpoint.h"  // load_junction_net, load_edge_net

namespace lc2wf {

// Sampling/patch options matching a junction model (G samples, N lines per patch), no augmentation.
JunctionSampleOptions junction_sample_options(const JunctionNetConfig& config);
// Patch options matching an edge model: each pair takes lines_per_patch / 2 lines around each junction.
PatchOptions pair_patch_options(const EdgeNetConfig& config);

// Every sample point's junction hypothesis: position (sample + offset, metres) and softmax confidence.
// Runs in eval mode without a graph. A cloud without segments gives no candidates. Of `selection`, only
// how the model is run counts: its sample points are seeded by density_seeds; with sampling_passes > 1 the
// sample holds passes x G points, run as passes patch sets of G (the first pass's candidates are the
// one-pass candidates, the others follow); with test_time_views > 1 (test_time_symmetry.h) each candidate is
// the mean of the model's answers on as many views of its patch.
PredictedJunctions predict_junction_candidates(JunctionNet& net, const LineCloud& cloud,
                                               const JunctionSelectionOptions& selection);

// Class logits (1, P, 5) of the given pairs of one building, in eval mode without a graph.
Tensor predict_pair_logits(EdgeNet& net, const LineCloud& cloud, const std::vector<JunctionPair>& pairs);
// Class probabilities (P x 5, row-major) of the given pairs of one building, in eval mode without a graph.
// With `views` > 1 the mean over as many views of the pairs (test_time_symmetry.h).
std::vector<float> predict_pair_probabilities(EdgeNet& net, const LineCloud& cloud, const std::vector<JunctionPair>& pairs,
                                              int views = 1);

struct InferenceResult {
  ScoredWireframe wireframe;       // final, metres
  ScoredWireframe candidates;      // candidate edges before clean-up (post_process "before process")
  PredictedJunctions junctions;    // all junction candidates of the junction model
  JunctionSelection selection;     // the junctions that were paired
  std::vector<JunctionPair> pairs;  // the pairs the edge model classified (labelled when a GT was given)
  std::vector<std::string> notes;  // degenerate cases met on the way
  bool segments_cut = false;       // the cloud's long segments were cut (PostProcessOptions::max_segment_length_m)
  double junction_seconds = 0.0;   // sampling + patches + junction model
  double edge_seconds = 0.0;       // pair patches + edge model
  double post_seconds = 0.0;       // selection + post-processing
};

// A trained model pair: `<dir>/junction.safetensors` and `<dir>/edge.safetensors` (written by lc2wf-train;
// the networks are rebuilt from the configs stored in the files).
class WireframePredictor {
 public:
  explicit WireframePredictor(const std::filesystem::path& weights_dir);
  WireframePredictor(const std::filesystem::path& junction_weights, const std::filesystem::path& edge_weights);

  InferenceResult predict(const LineCloud& cloud, const PostProcessOptions& options) const;
  // The edge half alone, from given junction candidates (used by lc2wf-train's validation).
  InferenceResult predict_from_junctions(const LineCloud& cloud, const PredictedJunctions& junctions,
                                         const PostProcessOptions& options) const;

  JunctionNet& junction_net() const { return *junction_; }
  EdgeNet& edge_net() const { return *edge_; }

 private:
  std::unique_ptr<JunctionNet> junction_;
  std::unique_ptr<EdgeNet> edge_;
};

// The edge half for a caller-owned network (lc2wf-train validates the model it is training). With
// `label_against`, the pairs get class labels and `logits` (if given) the network's (1, P, 5) output, so
// validation computes its loss on exactly the pairs whose wireframe it scores.
InferenceResult predict_wireframe(EdgeNet& edge_net, const LineCloud& cloud, const PredictedJunctions& junctions,
                                  const PostProcessOptions& options, const Wireframe* label_against = nullptr,
                                  Tensor* logits = nullptr);

}  // namespace lc2wf

// Where a trained model loses its score: runs the edge model and the post-processing on junctions that are
// partly or wholly the ground truth's, and scores the result with the paper's metrics. Next to
// `lc2wf-eval --weights` on the same buildings it separates what the junction stage costs (missed, extra
// and misplaced junctions) from what the edge stage and the post-processing cost.
//   lc2wf_oracle_junctions --weights DIR --data CLOUDS --split FILE -o OUT [--precision fp32|bf16|auto]
//                          [--junctions gt|predicted|true-only|snapped|true-snapped] [--min-confidence C]
//                          [--junction-weights FILE] [--keep-wireframes] [post-processing flags of lc2wf-eval]
// --junctions: gt = the GT junctions (confidence 1); predicted = the junction model's selection (the
// pipeline of lc2wf-eval --weights); true-only = that selection without its false positives (farther
// than 0.35 m from every GT junction); snapped = the selection with each true junction moved onto its GT
// junction; true-snapped = both. --junction-weights another junction model than DIR's (e.g. a checkpoint
// of another epoch). The post-processing flags (--nms-radius, --max-pairs, --crossing-distance, ...) set the
// selection and post-processing as for lc2wf-eval (infer/post_process_flags.h; defaults: lc2wf-eval's).
// Writes OUT/metrics.md, metrics.json and per_building.csv (as lc2wf-eval), and the same for the candidate
// edges before post-processing in OUT/candidates/ (what the edge model kept against what the clean-up kept);
// --keep-wireframes also writes both wireframes (OUT/wireframes, OUT/candidates/wireframes: <name>.obj, metres).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <string>

#include "core/matmul_precision.h"
#include "core/util/cli.h"
#include "dataset/formats/cloud_input.h"
#include "dataset/sampling/pair_sampling.h"
#include "dataset/splits/splits.h"
#include "infer/batch_inference.h"
#include "infer/eval_report_io.h"
#include "infer/prediction_io.h"
#include "model/evaluator.h"
#include "model/inference.h"
#include "infer/post_process_flags.h"

namespace fs = std::filesystem;
using namespace lc2wf;

// The junctions the edge model is given in `mode` (see the top of the file).
PredictedJunctions junctions(const WireframePredictor& predictor, const LineCloud& cloud, const std::string& mode,
                             const JunctionSelectionOptions& selection) {
  const std::vector<Vec3>& gt = cloud.wireframe.junctions;
  if (mode == "gt") return {gt, std::vector<double>(gt.size(), 1.0)};
  const PredictedJunctions candidates = predict_junction_candidates(predictor.junction_net(), cloud, selection);
  if (mode == "predicted") return candidates;
  const JunctionSelection selected = select_junctions(candidates, cloud.segments, selection);
  const std::vector<int> label = assign_junction_labels(selected.positions, gt, PairSamplingOptions{}.fp_distance_m);
  PredictedJunctions out;
  for (size_t k = 0; k < selected.positions.size(); ++k) {
    if (label[k] < 0 && mode != "snapped") continue;  // a false positive
    const bool snap = label[k] >= 0 && mode != "true-only";
    out.positions.push_back(snap ? gt[label[k]] : selected.positions[k]);
    out.confidence.push_back(selected.confidences[k]);
  }
  return out;
}

int run(int argc, char** argv) {
  fs::path weights, data, split, out, junction_weights;
  std::string precision = "fp32", mode = "gt";
  bool keep_wireframes = false;
  PostProcessFlags selection_flags;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    if (selection_flags.parse(f, argc, argv, i)) continue;  // every post-processing flag of lc2wf-eval
    if (f == "--keep-wireframes") {
      keep_wireframes = true;
      continue;
    }
    const std::string v = flag_value(argc, argv, i);
    if (f == "--weights") weights = v;
    else if (f == "--data") data = v;
    else if (f == "--split") split = v;
    else if (f == "-o" || f == "--out") out = v;
    else if (f == "--precision") precision = v;
    else if (f == "--junctions") mode = v;
    else if (f == "--junction-weights") junction_weights = v;
    else {
      std::fprintf(stderr, "lc2wf_oracle_junctions: unknown argument '%s'\n", f.c_str());
      return 2;
    }
  }
  const bool known = mode == "gt" || mode == "predicted" || mode == "true-only" || mode == "snapped" || mode == "true-snapped";
  if (weights.empty() || data.empty() || split.empty() || out.empty() || !known) {
    std::fprintf(stderr, "usage: lc2wf_oracle_junctions --weights DIR --data CLOUDS --split FILE -o OUT [--precision P] "
                 "[--junctions gt|predicted|true-only|snapped|true-snapped]\n");
    return 2;
  }
  try {
    const WireframePredictor predictor(junction_weights.empty() ? weights / "junction.safetensors" : junction_weights,
                                       weights / "edge.safetensors");
    const MatmulPrecisionGuard guard(precision_flag(precision));
    const PostProcessOptions pipeline = selection_flags.options();  // lc2wf-eval's, with the asked selection
    PostProcessOptions options = pipeline;  // junctions already selected (or GT): refine nothing again
    options.selection.refine.radius = 0.0;
    options.selection.max_offset_m = std::numeric_limits<double>::infinity();  // no offsets to screen
    Evaluator evaluator{EvalOptions{}};
    Evaluator before_clean_up{EvalOptions{}};  // the candidate edges: what the edge model kept, before post-processing
    InferenceTiming timing;
    timing.record_selection(pipeline);
    for (const std::string& name : read_name_list(split)) {
      const LineCloud cloud = load_line_cloud(find_cloud_file(data, name), CloudFormat::kAuto);
      const InferenceResult r = predict_wireframe(predictor.edge_net(), cloud, junctions(predictor, cloud, mode, pipeline.selection),
                                                  mode == "predicted" ? pipeline : options);
      evaluator.add(name, r.wireframe, cloud.wireframe);
      before_clean_up.add(name, r.candidates, cloud.wireframe);
      if (keep_wireframes) {
        write_prediction(out / "wireframes", name, r.wireframe);
        write_prediction(out / "candidates" / "wireframes", name, r.candidates);
      }
      ++timing.buildings;
      timing.pairs += static_cast<int64_t>(r.pairs.size());
      timing.edge_seconds += r.edge_seconds;
      timing.post_seconds += r.post_seconds;
      timing.total_seconds += r.edge_seconds + r.post_seconds;
    }
    timing.precision = to_string(precision_flag(precision));
    write_eval_outputs(out, evaluator.report(), mode + " junctions + " + weights.filename().string(), nullptr, &timing);
    write_eval_outputs(out / "candidates", before_clean_up.report(),
                       mode + " junctions + " + weights.filename().string() + ", candidate edges", nullptr, &timing);
    std::printf("%s", eval_markdown(evaluator.report(), mode + " junctions").c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf_oracle_junctions: %s\n", e.what());
    return 3;
  }
  return 0;
}

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {  // a bad flag value
    std::fprintf(stderr, "lc2wf_oracle_junctions: %s\n", e.what());
    return 2;
  }
}

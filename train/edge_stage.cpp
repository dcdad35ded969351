#include <cstdio>
#include <vector>

#include "core/tensor.h"
#include "infer/evaluator.h"
#include "infer/inference.h"
#include "infer/patch_tensors.h"
#include "infer/post_process_options.h"
#include "nn/edge_net.h"
#include "nn/losses.h"
#include "train/junction_handoff.h"
#include "train/patch_stream.h"
#include "train/stage_loop.h"
#include "train/stages.h"

namespace lc2wf {

void train_edge_stage(const TrainConfig& config, const BuildingSet& train, const BuildingSet& val,
                      const std::filesystem::path& handoff_dir, RunLog& log, const StageRun& run) {
  const EdgeStageConfig& c = config.edge;
  EdgeNet net(c.net, config.seed);

  PairSampleOptions train_options;
  train_options.pairs.pairs_per_building = static_cast<int>(c.net.lpt.patches);
  train_options.pairs.max_static_pairs = static_cast<int>(c.max_static_pairs);
  train_options.patch = pair_patch_options(c.net);
  train_options.augment_enabled = c.schedule.augment;
  // Training pairs and validation wireframes select junctions as lc2wf-infer does (same NMS, refinement).
  const PostProcessOptions post = c.post_process == "release" ? PostProcessOptions::release_quirks() : PostProcessOptions{};
  JunctionSelectionOptions selection = post.selection;
  selection.top_k = static_cast<int>(c.top_k);

  // Buildings whose GT has fewer than two junctions have no pairs to learn from. The selection is fixed
  // for the stage (the hand-off does not change), so it is made once.
  std::vector<const LineCloud*> clouds;
  std::vector<JunctionSelection> selected;
  for (const LineCloud& cloud : train.clouds) {
    if (cloud.wireframe.junctions.size() < 2) continue;
    clouds.push_back(&cloud);
    selected.push_back(select_junctions(read_predicted_junctions(predicted_junctions_path(handoff_dir, cloud.name)),
                                        cloud.segments, selection, SelectionCut::kTopK));
  }
  if (clouds.size() < train.clouds.size() && !run.quiet)
    std::fprintf(stderr, "edge: %zu training buildings without two GT junctions skipped\n",
                 train.clouds.size() - clouds.size());
  std::vector<PredictedJunctions> val_predicted;
  for (const LineCloud& cloud : val.clouds)
    val_predicted.push_back(read_predicted_junctions(predicted_junctions_path(handoff_dir, cloud.name)));

  PatchStream<PairPatches> stream(
      clouds.size(), [&](size_t b, uint64_t seed) { return make_pair_training_sample(*clouds[b], selected[b], train_options, seed); },
      PatchStreamOptions::of_stage(c.schedule, config.loader_workers, config.seed + 2));

  StageCallbacks cb;
  cb.batches_per_epoch = stream.batches_per_epoch();
  cb.start_epoch = [&](int64_t epoch, int64_t first) { stream.start(epoch, first); };
  cb.train_step = [&]() -> std::optional<StageStep> {
    std::optional<PairPatches> p = stream.next();
    if (!p) return std::nullopt;
    const auto ranges = micro_batch_ranges(p->batch, c.schedule.micro_batch);
    if (ranges.size() == 1) {
      const PatchInput in = pair_input(*p);
      const Tensor loss = edge_loss(net.forward(in.x, in.mask), pair_labels(*p), c.loss);
      loss.backward();
      return StageStep{loss.item(), nlohmann::json::object(), p->batch};
    }
    // Each micro-batch divides by the whole batch's class-weight sum: the parts add up to the batch loss.
    const double weight_total = edge_loss_weight(pair_labels(*p), c.loss);
    double total = 0.0;
    for (const auto& [first, count] : ranges) {
      const PairPatches part = slice(*p, first, count);
      const PatchInput in = pair_input(part);
      const Tensor loss = edge_loss(net.forward(in.x, in.mask), pair_labels(part), c.loss, weight_total);
      loss.backward();
      total += loss.item();
    }
    return StageStep{total, nlohmann::json::object(), p->batch};
  };
  cb.validate = [&]() {
    // One pass per building: the loss is computed on exactly the pairs whose wireframe is scored.
    Evaluator evaluator{EvalOptions{}};
    double loss_sum = 0.0;
    int64_t loss_buildings = 0;
    for (size_t k = 0; k < val.clouds.size(); ++k) {
      const LineCloud& cloud = val.clouds[k];
      Tensor logits;
      const InferenceResult r = predict_wireframe(net, cloud, val_predicted[k], post, &cloud.wireframe, &logits);
      if (!r.pairs.empty() && cloud.wireframe.junctions.size() >= 2) {
        std::vector<int64_t> labels;
        for (const JunctionPair& p : r.pairs) labels.push_back(p.label);
        NoGradGuard no_grad;
        loss_sum += edge_loss(logits, Tensor::from_vector(labels, {1, static_cast<int64_t>(labels.size())}), c.loss).item();
        ++loss_buildings;
      }
      evaluator.add(cloud.name, r.wireframe, cloud.wireframe);
    }
    const EvalReport report = evaluator.report();
    StageValidation v;
    v.score = report.edge_ap_mean;
    v.loss = loss_buildings ? loss_sum / static_cast<double>(loss_buildings) : 0.0;
    nlohmann::json sap = nlohmann::json::array(), srec = nlohmann::json::array();
    for (const ApSummary& s : report.edge) sap.push_back(s.ap), srec.push_back(s.recall);
    v.metrics = {{"sAP", sap},
                 {"sRecall", srec},
                 {"sAP_mean", report.edge_ap_mean},
                 {"vAP_mean", report.vertex_ap_mean},
                 {"wed_total", report.wed.total_dist},
                 {"buildings", val.clouds.size()}};
    return v;
  };

  run_stage(stage_loop_options("edge", c, config.seed, run), net, net.dropout_rng(), log, cb);
}

}  // namespace lc2wf

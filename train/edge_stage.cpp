#include <cstdio>
#include <vector>

#include "core/tensor.h"
#include "infer/evaluator.h"
#include "infer/inference.h"
#include "infer/patch_tensors.h"
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
  train_options.pairs.top_k = static_cast<int>(c.top_k);
  train_options.patch = pair_patch_options(c.net);
  train_options.augment_enabled = c.schedule.augment;
  PairSampleOptions val_options = train_options;
  val_options.augment_enabled = false;

  // Buildings whose GT has fewer than two junctions have no pairs to learn from.
  std::vector<const LineCloud*> clouds;
  std::vector<PredictedJunctions> predicted;
  for (const LineCloud& cloud : train.clouds) {
    if (cloud.wireframe.junctions.size() < 2) continue;
    clouds.push_back(&cloud);
    predicted.push_back(read_predicted_junctions(predicted_junctions_path(handoff_dir, cloud.name)));
  }
  if (clouds.size() < train.clouds.size() && !run.quiet)
    std::fprintf(stderr, "edge: %zu training buildings without two GT junctions skipped\n",
                 train.clouds.size() - clouds.size());
  std::vector<PredictedJunctions> val_predicted;
  for (const LineCloud& cloud : val.clouds)
    val_predicted.push_back(read_predicted_junctions(predicted_junctions_path(handoff_dir, cloud.name)));

  PatchStreamOptions so;
  so.batch_size = c.schedule.batch_size;
  so.drop_last = c.schedule.drop_last;
  so.workers = config.loader_workers;
  so.seed = config.seed + 2;
  so.max_batches = c.schedule.max_steps_per_epoch;
  PatchStream<PairPatches> stream(
      clouds.size(),
      [&](size_t b, uint64_t seed) { return make_pair_training_sample(*clouds[b], predicted[b], train_options, seed); }, so);

  StageCallbacks cb;
  cb.batches_per_epoch = stream.batches_per_epoch();
  cb.start_epoch = [&](int64_t epoch, int64_t first) { stream.start(epoch, first); };
  cb.train_step = [&]() -> std::optional<StageStep> {
    std::optional<PairPatches> p = stream.next();
    if (!p) return std::nullopt;
    const PatchInput in = pair_input(*p);
    const Tensor loss = edge_loss(net.forward(in.x, in.mask), pair_labels(*p), c.loss);
    loss.backward();
    return StageStep{loss.item(), nlohmann::json::object(), p->batch};
  };
  cb.validate = [&]() {
    Evaluator evaluator{EvalOptions{}};
    double loss_sum = 0.0;
    int64_t loss_buildings = 0;
    PostProcessOptions post;
    post.junction_refine.radius = 0.0;  // the hand-off positions are already refined (once is enough)
    for (size_t k = 0; k < val.clouds.size(); ++k) {
      const LineCloud& cloud = val.clouds[k];
      if (cloud.wireframe.junctions.size() >= 2) {
        const PairPatches p = make_pair_test_sample(cloud, val_predicted[k], val_options);
        if (p.num_pairs > 0) {
          net.eval();
          NoGradGuard no_grad;
          const PatchInput in = pair_input(p);
          loss_sum += edge_loss(net.forward(in.x, in.mask), pair_labels(p), c.loss).item();
          ++loss_buildings;
        }
      }
      const InferenceResult r = predict_wireframe(net, cloud, val_predicted[k], post);
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

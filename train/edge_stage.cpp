#include <cstdio>
#include <vector>

#include "core/tensor.h"
#include "model/evaluator.h"
#include "model/inference.h"
#include "model/patch_tensors.h"
#include "model/post_process_options.h"
#include "nn/edge_net.h"
#include "nn/losses.h"
#include "train/data_parallel.h"
#include "train/edge_step.h"
#include "train/junction_handoff.h"
#include "train/patch_stream.h"
#include "train/stage_loop.h"
#include "train/stages.h"

namespace lc2wf {

namespace {

// A validation wireframe as doubles (coordinates, scores and indices are exact in double), so the
// ranks can pool their buildings' predictions.
void append_wireframe(const ScoredWireframe& w, std::vector<double>& out) {
  out.push_back(static_cast<double>(w.wireframe.junctions.size()));
  for (size_t i = 0; i < w.wireframe.junctions.size(); ++i) {
    const Vec3& p = w.wireframe.junctions[i];
    out.insert(out.end(), {p.x(), p.y(), p.z(), w.junction_scores.at(i)});
  }
  out.push_back(static_cast<double>(w.wireframe.edges.size()));
  for (size_t i = 0; i < w.wireframe.edges.size(); ++i) {
    const auto& e = w.wireframe.edges[i];
    out.insert(out.end(), {static_cast<double>(e[0]), static_cast<double>(e[1]), w.edge_scores.at(i)});
  }
}

ScoredWireframe read_wireframe(const std::vector<double>& in, size_t& at) {
  ScoredWireframe w;
  const size_t junctions = static_cast<size_t>(in.at(at++));
  for (size_t i = 0; i < junctions; ++i, at += 4) {
    w.wireframe.junctions.emplace_back(in.at(at), in.at(at + 1), in.at(at + 2));
    w.junction_scores.push_back(in.at(at + 3));
  }
  const size_t edges = static_cast<size_t>(in.at(at++));
  for (size_t i = 0; i < edges; ++i, at += 3) {
    w.wireframe.edges.push_back({static_cast<int>(in.at(at)), static_cast<int>(in.at(at + 1))});
    w.edge_scores.push_back(in.at(at + 2));
  }
  return w;
}

}  // namespace

void train_edge_stage(const TrainConfig& config, const BuildingSet& train, const BuildingSet& val,
                      const std::filesystem::path& handoff_dir, RunLog& log, const StageRun& run) {
  const EdgeStageConfig& c = config.edge;
  EdgeNet net(c.net, config.seed);
  net.set_recompute_mlp(c.schedule.recompute_mlp);
  Communicator& comm = run.communicator();
  DataParallel dp(comm, net, net.dropout_rng(), c.schedule.batch_norm == "sync");

  const PairSampleOptions train_options = edge_training_sample_options(c);
  // Training pairs and validation wireframes select junctions as lc2wf-infer does (same NMS, refinement).
  const PostProcessOptions post = edge_post_process_options(c);
  const JunctionSelectionOptions selection = edge_training_selection(c);

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
      PatchStreamOptions::of_stage(c.schedule, config.loader_workers, config.seed + 2, comm.rank(), comm.size()));

  StageCallbacks cb;
  cb.batches_per_epoch = stream.batches_per_epoch();
  cb.training_buildings = clouds.size();
  cb.start_epoch = [&](int64_t epoch, int64_t first) { stream.start(epoch, first); };
  cb.train_step = [&]() -> std::optional<StageStep> {
    std::optional<StreamBatch<PairPatches>> p = stream.next();
    if (!p) return std::nullopt;
    const EdgeStepPasses step = edge_step_passes(net, dp, *p, c.schedule.micro_batch, c.loss);
    return StageStep{step.loss, nlohmann::json::object(), p->batch, step.comm_seconds};
  };
  cb.validate = [&]() {
    // One pass per building: the loss is computed on exactly the pairs whose wireframe is scored.
    // This rank's share of the buildings is predicted here; every rank then scores all of them in order.
    const BatchShare share = batch_share(static_cast<int64_t>(val.clouds.size()), comm.rank(), comm.size());
    std::vector<double> mine;
    for (int64_t k = share.first; k < share.first + share.count; ++k) {
      const LineCloud& cloud = val.clouds[static_cast<size_t>(k)];
      Tensor logits;
      const InferenceResult r = predict_wireframe(net, cloud, val_predicted[static_cast<size_t>(k)], post, &cloud.wireframe, &logits);
      double loss = 0.0;
      const bool has_loss = !r.pairs.empty() && cloud.wireframe.junctions.size() >= 2;
      if (has_loss) {
        std::vector<int64_t> labels;
        for (const JunctionPair& p : r.pairs) labels.push_back(p.label);
        NoGradGuard no_grad;
        loss = edge_loss(logits, Tensor::from_vector(labels, {1, static_cast<int64_t>(labels.size())}), c.loss).item();
      }
      mine.insert(mine.end(), {has_loss ? 1.0 : 0.0, loss});
      append_wireframe(r.wireframe, mine);
    }
    Evaluator evaluator{EvalOptions{}};
    double loss_sum = 0.0;
    int64_t loss_buildings = 0;
    size_t k = 0;
    for (const std::vector<double>& theirs : gather_doubles(comm, mine, "validation results"))
      for (size_t at = 0; at < theirs.size(); ++k) {
        const LineCloud& cloud = val.clouds.at(k);
        if (theirs.at(at) != 0.0) {
          loss_sum += theirs.at(at + 1);
          ++loss_buildings;
        }
        at += 2;
        evaluator.add(cloud.name, read_wireframe(theirs, at), cloud.wireframe);
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

  StageLoopOptions loop = stage_loop_options("edge", c, config.seed, run);
  loop.model_config["inputs"] = handoff_identity(handoff_dir);
  run_stage(loop, net, net.dropout_rng(), log, cb);
}

}  // namespace lc2wf

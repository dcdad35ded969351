#include <vector>

#include "core/ops.h"
#include "core/tensor.h"
#include "infer/ap_metric.h"
#include "infer/inference.h"
#include "infer/patch_tensors.h"
#include "dataset/point_nms.h"
#include "nn/junction_net.h"
#include "nn/losses.h"
#include "train/patch_stream.h"
#include "train/stage_loop.h"
#include "train/stages.h"

namespace lc2wf {
namespace {

// Validation: the junction metric the release logs while training, in metres: every candidate,
// point NMS at 0.15 m (3 raw), pooled vAP at the paper's three thresholds.
constexpr double kValNmsRadius = 0.15;
const std::vector<double> kVertexThresholds{0.15, 0.25, 0.35};

JunctionSampleOptions training_sample_options(const JunctionStageConfig& c, bool augment) {
  JunctionSampleOptions o = junction_sample_options(c.net);
  o.augment_enabled = augment;
  o.sampling.near_gt_samples = augment ? static_cast<int>(c.near_gt_samples) : 0;
  if (c.endpoint_label_max_distance_m > 0) o.endpoint_label_max_distance_m = c.endpoint_label_max_distance_m;
  return o;
}

}  // namespace

void train_junction_stage(const TrainConfig& config, const BuildingSet& train, const BuildingSet& val, RunLog& log,
                          const StageRun& run) {
  const JunctionStageConfig& c = config.junction;
  JunctionNet net(c.net, config.seed);
  const JunctionSampleOptions train_options = training_sample_options(c, c.schedule.augment);
  const JunctionSampleOptions val_options = training_sample_options(c, false);

  PatchStream<JunctionPatches> stream(
      train.clouds.size(), [&](size_t b, uint64_t seed) { return make_junction_sample(train.clouds[b], train_options, seed); },
      PatchStreamOptions::of_stage(c.schedule, config.loader_workers, config.seed + 1));

  // Validation patches do not change between epochs: build them once.
  std::vector<JunctionPatches> val_batches;
  for (size_t first = 0; first < val.clouds.size(); first += c.schedule.batch_size) {
    std::vector<JunctionPatches> parts;
    for (size_t k = first; k < std::min(val.clouds.size(), first + static_cast<size_t>(c.schedule.batch_size)); ++k)
      parts.push_back(make_junction_sample(val.clouds[k], val_options, 0));
    val_batches.push_back(stack(parts));
  }

  StageCallbacks cb;
  cb.batches_per_epoch = stream.batches_per_epoch();
  cb.start_epoch = [&](int64_t epoch, int64_t first) { stream.start(epoch, first); };
  cb.train_step = [&]() -> std::optional<StageStep> {
    std::optional<JunctionPatches> p = stream.next();
    if (!p) return std::nullopt;
    // The loss is a mean over buildings, so a micro-batch's share of it is its share of the buildings.
    double total = 0.0, cls = 0.0, reg = 0.0;
    for (const auto& [first, count] : micro_batch_ranges(p->batch, c.schedule.micro_batch)) {
      const bool whole = count == p->batch;
      const JunctionPatches part = whole ? JunctionPatches{} : slice(*p, first, count);
      const JunctionPatches& q = whole ? *p : part;
      const PatchInput in = junction_input(q);
      const LossTerms loss = junction_loss(net.forward(in.x, in.mask), junction_targets(q), c.loss);
      const double share = static_cast<double>(count) / p->batch;
      (whole ? loss.total : loss.total * share).backward();
      total += share * loss.total.item();
      cls += share * loss.classification.item();
      reg += share * loss.regression.item();
    }
    return StageStep{total, {{"cls_loss", cls}, {"reg_loss", reg}}, p->batch};
  };
  cb.validate = [&]() {
    net.eval();
    NoGradGuard no_grad;
    std::vector<std::vector<RankedHit>> hits(kVertexThresholds.size());
    int64_t num_gt = 0;
    double loss_sum = 0.0;
    size_t building = 0;
    for (const JunctionPatches& p : val_batches) {
      const PatchInput in = junction_input(p);
      const JunctionOutput y = net.forward(in.x, in.mask);
      loss_sum += junction_loss(y, junction_targets(p), c.loss).total.item() * p.batch;
      for (const PredictedJunctions& candidates : junction_candidates(y, p, val_options.patch.frame)) {
        std::vector<Vec3> kept_pos;
        std::vector<double> kept_conf;
        for (int i : point_nms(candidates.positions, candidates.confidence, kValNmsRadius, PointNmsRule::kGreedy)) {
          kept_pos.push_back(candidates.positions[i]);
          kept_conf.push_back(candidates.confidence[i]);
        }
        const std::vector<Vec3>& gt = val.clouds[building].wireframe.junctions;
        num_gt += static_cast<int64_t>(gt.size());
        for (size_t t = 0; t < kVertexThresholds.size(); ++t) {
          const auto h = match_junctions(kept_pos, kept_conf, gt, kVertexThresholds[t]);
          hits[t].insert(hits[t].end(), h.begin(), h.end());
        }
        ++building;
      }
    }
    StageValidation v;
    v.loss = building ? loss_sum / static_cast<double>(building) : 0.0;
    nlohmann::json vap = nlohmann::json::array(), vrec = nlohmann::json::array();
    for (size_t t = 0; t < kVertexThresholds.size(); ++t) {
      const ApSummary s = summarize_hits(hits[t], num_gt, kVertexThresholds[t], ApTieRule::kGroupTies);
      v.score += s.ap / static_cast<double>(kVertexThresholds.size());
      vap.push_back(s.ap);
      vrec.push_back(s.recall);
    }
    v.metrics = {{"vAP", vap}, {"vRecall", vrec}, {"vAP_mean", v.score}, {"buildings", building}};
    return v;
  };

  run_stage(stage_loop_options("junction", c, config.seed, run), net, net.dropout_rng(), log, cb);
}

}  // namespace lc2wf

#include <vector>

#include "core/ops.h"
#include "core/tensor.h"
#include "model/ap_metric.h"
#include "model/inference.h"
#include "model/patch_tensors.h"
#include "dataset/selection/point_nms.h"
#include "nn/junction_net.h"
#include "nn/losses.h"
#include "train/data_parallel.h"
#include "train/patch_stream.h"
#include "train/stage_loop.h"
#include "train/stages.h"

namespace lc2wf {
namespace {

// Validation: the junction metric the release logs while training, in metres: every candidate,
// point NMS at 0.15 m (3 raw), pooled vAP at the paper's three thresholds.
constexpr double kValNmsRadius = 0.15;
const std::vector<double> kVertexThresholds{0.15, 0.25, 0.35};

// Training batches get the schedule's augmentations and near-GT samples; validation gets none.
JunctionSampleOptions stage_sample_options(const JunctionStageConfig& c, bool training) {
  JunctionSampleOptions o = junction_sample_options(c.net);
  o.augment_enabled = training && c.schedule.augment;
  o.augment.rotate_z = c.schedule.augment_rotate_z;
  o.cloud_augment_enabled = training && c.schedule.cloud_augment.enabled;
  o.cloud_augment = c.schedule.cloud_augment.options;
  o.sampling.near_gt_samples = o.augment_enabled ? static_cast<int>(c.near_gt_samples) : 0;
  if (c.endpoint_label_max_distance_m > 0) o.endpoint_label_max_distance_m = c.endpoint_label_max_distance_m;
  if (c.positive_radius_m > 0) o.patch.positive_radius_m = c.positive_radius_m;
  o.sampling.seeds = DensitySeedRule::parse(c.density_seeds);
  return o;
}

}  // namespace

void train_junction_stage(const TrainConfig& config, const BuildingSet& train, const BuildingSet& val, RunLog& log,
                          const StageRun& run) {
  const JunctionStageConfig& c = config.junction;
  JunctionNet net(c.net, config.seed);
  net.set_recompute_mlp(c.schedule.recompute_mlp);
  const JunctionSampleOptions train_options = stage_sample_options(c, true);
  const JunctionSampleOptions val_options = stage_sample_options(c, false);
  Communicator& comm = run.communicator();
  DataParallel dp(comm, net, net.dropout_rng(), c.schedule.batch_norm == "sync");

  PatchStream<JunctionPatches> stream(
      train.clouds.size(), [&](size_t b, uint64_t seed) { return make_junction_sample(train.clouds[b], train_options, seed); },
      PatchStreamOptions::of_stage(c.schedule, config.loader_workers, config.seed + 1, comm.rank(), comm.size()));

  // Validation patches do not change between epochs: build them once. The batches are one process's
  // (the loss is a mean per batch); a data-parallel rank takes its share of the batches.
  const size_t val_batch = static_cast<size_t>(c.schedule.batch_size);
  const BatchShare val_share =
      batch_share(static_cast<int64_t>((val.clouds.size() + val_batch - 1) / val_batch), comm.rank(), comm.size());
  const size_t val_begin = std::min(val.clouds.size(), static_cast<size_t>(val_share.first) * val_batch);
  const size_t val_end = std::min(val.clouds.size(), static_cast<size_t>(val_share.first + val_share.count) * val_batch);
  std::vector<JunctionPatches> val_batches;
  for (size_t first = val_begin; first < val_end; first += val_batch) {
    std::vector<JunctionPatches> parts;
    for (size_t k = first; k < std::min(val_end, first + val_batch); ++k)
      parts.push_back(make_junction_sample(val.clouds[k], val_options, 0));
    val_batches.push_back(stack(parts));
  }

  StageCallbacks cb;
  cb.batches_per_epoch = stream.batches_per_epoch();
  cb.training_buildings = train.clouds.size();
  cb.start_epoch = [&](int64_t epoch, int64_t first) { stream.start(epoch, first); };
  cb.train_step = [&]() -> std::optional<StageStep> {
    std::optional<StreamBatch<JunctionPatches>> p = stream.next();
    if (!p) return std::nullopt;
    // The loss is a mean over buildings, so a pass's share of it is its share of the batch's buildings.
    std::vector<double> terms{0.0, 0.0, 0.0};  // total, classification, regression
    const double comm_seconds = dp.run_step(p->batch, c.schedule.micro_batch, [&](int64_t first, int64_t count) {
      const bool all_local = count == p->share.count;
      const JunctionPatches part =
          all_local ? JunctionPatches{} : slice(p->patches, static_cast<int>(first - p->share.first), static_cast<int>(count));
      const JunctionPatches& q = all_local ? p->patches : part;
      const PatchInput in = junction_input(q);
      const LossTerms loss = junction_loss(net.forward(in.x, in.mask), junction_targets(q), c.loss);
      const double share = static_cast<double>(count) / static_cast<double>(p->batch);
      (count == p->batch ? loss.total : loss.total * share).backward();
      terms[0] += share * loss.total.item();
      terms[1] += share * loss.classification.item();
      terms[2] += share * loss.regression.item();
    });
    dp.sum(terms, "loss terms");
    return StageStep{terms[0], {{"cls_loss", terms[1]}, {"reg_loss", terms[2]}}, p->batch, comm_seconds};
  };
  cb.validate = [&]() {
    net.eval();
    NoGradGuard no_grad;
    // This rank's buildings; the hits are pooled in building order (rank order) below.
    std::vector<std::vector<RankedHit>> hits(kVertexThresholds.size());
    int64_t num_gt = 0;
    double loss_sum = 0.0;
    size_t building = val_begin;
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
    // Every rank's [loss sum, GT junctions, then per threshold: hit count, (score, true positive) pairs].
    std::vector<double> mine{loss_sum, static_cast<double>(num_gt)};
    for (const auto& h : hits) {
      mine.push_back(static_cast<double>(h.size()));
      for (const RankedHit& r : h) mine.insert(mine.end(), {r.score, r.true_positive ? 1.0 : 0.0});
    }
    loss_sum = 0.0;
    num_gt = 0;
    for (auto& h : hits) h.clear();
    for (const std::vector<double>& theirs : gather_doubles(comm, mine, "validation results")) {
      loss_sum += theirs.at(0);
      num_gt += static_cast<int64_t>(theirs.at(1));
      size_t at = 2;
      for (auto& h : hits) {
        const size_t n = static_cast<size_t>(theirs.at(at++));
        for (size_t k = 0; k < n; ++k, at += 2) h.push_back({theirs.at(at), theirs.at(at + 1) != 0.0});
      }
    }
    building = val.clouds.size();
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

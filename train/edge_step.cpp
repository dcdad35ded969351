#include "train/edge_step.h"

#include <vector>

#include "model/inference.h"
#include "model/patch_tensors.h"
#include "nn/losses.h"
#include "train/stage_loop.h"

namespace lc2wf {

PairSampleOptions edge_training_sample_options(const EdgeStageConfig& c) {
  PairSampleOptions o;
  o.pairs.pairs_per_building = static_cast<int>(c.net.lpt.patches);
  o.pairs.max_static_pairs = static_cast<int>(c.max_static_pairs);
  o.patch = pair_patch_options(c.net);
  o.augment_enabled = c.schedule.augment;
  o.augment.rotate_z = c.schedule.augment_rotate_z;
  o.cloud_augment_enabled = c.schedule.cloud_augment.enabled;
  o.cloud_augment = c.schedule.cloud_augment.options;
  return o;
}

PostProcessOptions edge_post_process_options(const EdgeStageConfig& c) {
  PostProcessOptions o = c.post_process == "release" ? PostProcessOptions::release_quirks() : PostProcessOptions{};
  o.selection.min_confidence = c.min_confidence;
  o.pair_support.min_support = c.pair_support;
  o.selection.nms_radius_m = c.nms_radius_m;
  // The config decides either way, so a later default of the options never leaks into a run.
  o.selection.max_offset_m = JunctionSelectionOptions::offset_limit(c.max_offset_m);
  o.selection.corner.radius_m = c.corner_radius_m;
  o.selection.footing.radius_m = c.footing_radius_m;
  o.selection.sampling_passes = static_cast<int>(c.sampling_passes);
  o.selection.test_time_views = static_cast<int>(c.test_time_views);
  o.selection.density_seeds = DensitySeedRule::parse(c.density_seeds);
  return o;
}

JunctionSelectionOptions edge_training_selection(const EdgeStageConfig& c) {
  JunctionSelectionOptions selection = edge_post_process_options(c).selection;
  selection.top_k = static_cast<int>(c.top_k);
  return selection;
}

EdgeStepPasses edge_step_passes(EdgeNet& net, DataParallel& dp, const StreamBatch<PairPatches>& p,
                                int64_t micro, const EdgeLossConfig& loss_config) {
  EdgeStepPasses out;
  if (dp.ranks() == 1 && micro_batch_ranges(static_cast<int>(p.batch), micro).size() == 1) {
    dp.run_step(p.batch, micro, [&](int64_t, int64_t) {
      const PatchInput in = pair_input(p.patches);
      const Tensor loss = edge_loss(net.forward(in.x, in.mask), pair_labels(p.patches), loss_config);
      loss.backward();
      out.loss = loss.item();
    });
    return out;
  }
  // Each pass divides by the whole batch's class-weight sum: the parts add up to the batch loss.
  std::vector<double> weight_total{p.share.count > 0 ? edge_loss_weight(pair_labels(p.patches), loss_config) : 0.0};
  dp.sum(weight_total, "edge loss weight");
  std::vector<double> total{0.0};
  out.comm_seconds = dp.run_step(p.batch, micro, [&](int64_t first, int64_t count) {
    const bool all_local = count == p.share.count;
    const PairPatches part =
        all_local ? PairPatches{} : slice(p.patches, static_cast<int>(first - p.share.first), static_cast<int>(count));
    const PairPatches& q = all_local ? p.patches : part;
    const PatchInput in = pair_input(q);
    const Tensor loss = edge_loss(net.forward(in.x, in.mask), pair_labels(q), loss_config, weight_total[0]);
    loss.backward();
    total[0] += loss.item();
  });
  dp.sum(total, "loss terms");
  out.loss = total[0];
  return out;
}

}  // namespace lc2wf

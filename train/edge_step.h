// The edge stage's pieces that the training loop and the micro-batch study (bench/train) must share:
// how training pairs are sampled and junctions selected from the config, and one step's forward and
// backward passes over a batch, cut into micro-batches whose losses add up to the batch's loss.
#pragma once

#include <cstdint>

#include "dataset/selection/junction_selection.h"
#include "dataset/sampling/patches.h"
#include "dataset/sampling/network_input.h"
#include "model/post_process_options.h"
#include "nn/edge_net.h"
#include "train/data_parallel.h"
#include "train/patch_stream.h"
#include "train/train_config.h"

namespace lc2wf {

// Pair sampling of the training buildings: pairs per building, static pairs, patch size, augmentation.
PairSampleOptions edge_training_sample_options(const EdgeStageConfig& c);
// Post-processing of validation (and junction selection of training pairs), as lc2wf-infer with the
// config's post_process ("sound" or "release").
PostProcessOptions edge_post_process_options(const EdgeStageConfig& c);
// Junction selection of the training buildings: inference's rule with the config's top_k.
JunctionSelectionOptions edge_training_selection(const EdgeStageConfig& c);

struct EdgeStepPasses {
  double loss = 0.0;          // the batch's loss (summed over its passes and the ranks)
  double comm_seconds = 0.0;  // waiting for the gradient sum
};

// Forward and backward passes of one batch; gradients accumulate in `net`'s parameters (the caller
// steps the optimiser). micro_batch <= 0: the whole batch in one pass.
EdgeStepPasses edge_step_passes(EdgeNet& net, DataParallel& dp, const StreamBatch<PairPatches>& batch,
                                int64_t micro_batch, const EdgeLossConfig& loss);

}  // namespace lc2wf

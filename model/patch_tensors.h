// Where patch arrays (dataset/sampling/patches.h) meet the networks, for training and inference alike: input tensors
// (features F32 (B, G, L, F), padding mask Bool (B, G, L)), the training targets of each stage, and the
// junction model's output decoded into candidates.
#pragma once

#include "core/tensor.h"
#include "dataset/selection/junction_selection.h"
#include "dataset/geometry/network_frame.h"
#include "dataset/sampling/patches.h"
#include "nn/junction_net.h"
#include "nn/losses.h"

namespace lc2wf {

struct PatchInput {
  Tensor x;
  Tensor mask;
};

PatchInput junction_input(const JunctionPatches& patches);
PatchInput pair_input(const PairPatches& patches);

// labels I64 (B, G): 1 where the patch holds a GT junction; offsets F32 (B, G, 3).
JunctionTargets junction_targets(const JunctionPatches& patches);
// I64 (B, P) pair classes; throws std::invalid_argument when a pair has no label.
Tensor pair_labels(const PairPatches& patches);

// The junction model's output on `patches`, one entry per building: each sample point's hypothesis,
// position = sample point + predicted offset (metres, through `frame`), confidence = softmax(logits)[1].
std::vector<PredictedJunctions> junction_candidates(const JunctionOutput& y, const JunctionPatches& patches,
                                                    const NetworkFrame& frame);
// The same from per-patch confidences (B G) and offsets (B G 3, network units), e.g. averaged over views.
std::vector<PredictedJunctions> junction_candidates(const std::vector<double>& confidence,
                                                    const std::vector<double>& offsets, const JunctionPatches& patches,
                                                    const NetworkFrame& frame);
// softmax(logits)[1] of every patch, in patch order.
std::vector<double> junction_confidences(const JunctionOutput& y);

}  // namespace lc2wf

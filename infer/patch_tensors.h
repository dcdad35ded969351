// Patch arrays (dataset/patches.h) as network input tensors: features F32 (B, G, L, F) and the padding
// mask Bool (B, G, L), plus the training targets of each stage.
#pragma once

#include "core/tensor.h"
#include "dataset/patches.h"
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

}  // namespace lc2wf

// One building's network input, from a line cloud: sampling, optional augmentation, patches.
#pragma once

#include <cstdint>
#include <limits>

#include "dataset/sampling/augmentation.h"
#include "dataset/sampling/cloud_augmentation.h"
#include "dataset/geometry/line_cloud.h"
#include "dataset/sampling/pair_sampling.h"
#include "dataset/sampling/patches.h"
#include "dataset/sampling/sampling.h"

namespace lc2wf {

struct JunctionSampleOptions {
  SamplingOptions sampling;
  PatchOptions patch;
  AugmentOptions augment;
  bool augment_enabled = false;  // training only, as the release
  CloudAugmentOptions cloud_augment;
  bool cloud_augment_enabled = false;  // training only; the release has no such augmentation
  // Endpoint labels farther than this from their junction count as noise (see endpoint_labels()); the
  // default keeps the plain (f, i1, i2) derivation.
  double endpoint_label_max_distance_m = std::numeric_limits<double>::infinity();
  void Check() const;
};

// With cloud_augment_enabled the cloud's statistics are augmented first (augment_cloud_statistics, its
// own seed stream), and everything below sees the augmented cloud.
// Sample points are chosen on the un-augmented cloud (the release computes density seeds before
// augmentation; FPS is invariant to the similarity transform), then segments and GT are augmented and
// patched. Deterministic for a seed. Throws DataError naming the cloud when it has no segments.
JunctionPatches make_junction_sample(const LineCloud& cloud, const JunctionSampleOptions& options, uint64_t seed);

struct PairSampleOptions {
  PairSamplingOptions pairs;
  PatchOptions patch;
  AugmentOptions augment;
  bool augment_enabled = false;
  CloudAugmentOptions cloud_augment;
  bool cloud_augment_enabled = false;
  void Check() const;
};

// Training: GT + predicted pairs (release 3.3) of the junctions `selected` for this cloud (select_junctions
// with SelectionCut::kTopK, metres), augmentation applied jointly to segments, GT and predictions.
PairPatches make_pair_training_sample(const LineCloud& cloud, const JunctionSelection& selected,
                                      const PairSampleOptions& options, uint64_t seed);

}  // namespace lc2wf

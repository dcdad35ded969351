#include "dataset/sampling/network_input.h"

#include <stdexcept>

#include "dataset/formats/errors.h"
#include "dataset/sampling/rng.h"

namespace lc2wf {
namespace {

void require_segments(const LineCloud& c) {
  if (c.segments.empty()) throw DataError(c.name.empty() ? "line cloud" : c.name, "empty line cloud (no segments)");
}

// The cloud's statistics augmentation draws from its own stream, so enabling it leaves the other draws alone.
constexpr uint64_t kCloudAugmentStream = 0xC10DA06ull;

}  // namespace

void JunctionSampleOptions::Check() const {
  if (!(endpoint_label_max_distance_m > 0)) throw std::invalid_argument("JunctionSampleOptions.endpoint_label_max_distance_m must be > 0");
  sampling.Check();
  patch.Check();
  augment.Check();
  cloud_augment.Check();
}

void PairSampleOptions::Check() const {
  pairs.Check();
  patch.Check();
  augment.Check();
  cloud_augment.Check();
}

JunctionPatches make_junction_sample(const LineCloud& original, const JunctionSampleOptions& o, uint64_t seed) {
  o.Check();
  require_segments(original);
  const LineCloud augmented = o.cloud_augment_enabled
                                  ? augment_cloud_statistics(original, o.cloud_augment, mix_seed(seed, kCloudAugmentStream))
                                  : LineCloud{};
  const LineCloud& cloud = o.cloud_augment_enabled ? augmented : original;
  DataRng rng(seed);
  const Augmentation aug = o.augment_enabled ? draw_augmentation(rng, o.augment, o.patch.frame) : Augmentation{};
  const std::vector<Vec3> endpoints = segment_endpoints(cloud.segments);
  const std::vector<int> samples = sample_endpoints(endpoints, o.sampling, &cloud.wireframe.junctions, &rng);
  std::vector<Segment3> segs = cloud.segments;
  std::vector<Vec3> gt = cloud.wireframe.junctions;
  aug.apply(segs);
  aug.apply(gt);
  return build_junction_patches(SegmentSet(segs), endpoint_labels(cloud, o.endpoint_label_max_distance_m), gt, samples, o.patch);
}

PairPatches make_pair_training_sample(const LineCloud& cloud, const JunctionSelection& selected,
                                      const PairSampleOptions& o, uint64_t seed) {
  o.Check();
  require_segments(cloud);
  if (cloud.wireframe.junctions.size() < 2) throw DataError(cloud.name, "fewer than 2 GT junctions: no training pairs");
  DataRng rng(seed);
  const Augmentation aug = o.augment_enabled ? draw_augmentation(rng, o.augment, o.patch.frame) : Augmentation{};
  std::vector<JunctionPair> pairs = sample_training_pairs(cloud.wireframe, selected, o.pairs);
  for (auto& p : pairs) {
    p.u = aug.apply(p.u);
    p.v = aug.apply(p.v);
  }
  std::vector<Segment3> segs =
      o.cloud_augment_enabled ? augment_cloud_statistics(cloud, o.cloud_augment, mix_seed(seed, kCloudAugmentStream)).segments
                              : cloud.segments;
  aug.apply(segs);
  return build_pair_patches(SegmentSet(segs), pairs, o.patch);
}

}  // namespace lc2wf

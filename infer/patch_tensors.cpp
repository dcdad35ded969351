#include "infer/patch_tensors.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace lc2wf {

PatchInput junction_input(const JunctionPatches& p) {
  const Shape s{p.batch, p.num_patches, p.lines};
  return {Tensor::from_vector(p.features, {p.batch, p.num_patches, p.lines, JunctionPatches::kFeatures}),
          Tensor::from_mask(p.padded, s)};
}

PatchInput pair_input(const PairPatches& p) {
  const Shape s{p.batch, p.num_pairs, p.lines};
  return {Tensor::from_vector(p.features, {p.batch, p.num_pairs, p.lines, PairPatches::kFeatures}),
          Tensor::from_mask(p.padded, s)};
}

JunctionTargets junction_targets(const JunctionPatches& p) {
  std::vector<int64_t> labels(p.label.size());
  for (size_t k = 0; k < labels.size(); ++k) labels[k] = p.label[k] >= 0 ? 1 : 0;
  return {Tensor::from_vector(labels, {p.batch, p.num_patches}),
          Tensor::from_vector(p.offset, {p.batch, p.num_patches, 3})};
}

Tensor pair_labels(const PairPatches& p) {
  std::vector<int64_t> labels(p.label.size());
  for (size_t k = 0; k < labels.size(); ++k) {
    if (p.label[k] < 0) throw std::invalid_argument("pair_labels: pair " + std::to_string(k) + " has no class label");
    labels[k] = p.label[k];
  }
  return Tensor::from_vector(labels, {p.batch, p.num_pairs});
}

}  // namespace lc2wf

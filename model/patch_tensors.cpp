#include "model/patch_tensors.h"

#include <cmath>
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

std::vector<double> junction_confidences(const JunctionOutput& y) {
  const std::vector<double> logits = y.logits.to_vector();
  std::vector<double> confidence(logits.size() / 2);
  for (size_t k = 0; k < confidence.size(); ++k)
    confidence[k] = 1.0 / (1.0 + std::exp(logits[2 * k] - logits[2 * k + 1]));  // softmax[1]
  return confidence;
}

std::vector<PredictedJunctions> junction_candidates(const JunctionOutput& y, const JunctionPatches& p, const NetworkFrame& frame) {
  return junction_candidates(junction_confidences(y), y.offsets.to_vector(), p, frame);
}

std::vector<PredictedJunctions> junction_candidates(const std::vector<double>& confidence,
                                                    const std::vector<double>& offsets, const JunctionPatches& p,
                                                    const NetworkFrame& frame) {
  const size_t patches = static_cast<size_t>(p.batch) * static_cast<size_t>(p.num_patches);
  if (confidence.size() != patches || offsets.size() != 3 * patches)
    throw std::invalid_argument("junction_candidates: " + std::to_string(confidence.size()) + " confidences and " +
                                std::to_string(offsets.size()) + " offset values for " + std::to_string(patches) +
                                " patches");
  std::vector<PredictedJunctions> out(static_cast<size_t>(p.batch));
  for (int b = 0; b < p.batch; ++b) {
    for (int g = 0; g < p.num_patches; ++g) {
      const size_t k = static_cast<size_t>(b) * p.num_patches + g;
      out[b].confidence.push_back(confidence[k]);
      const Vec3 point(p.points[3 * k], p.points[3 * k + 1], p.points[3 * k + 2]);
      const Vec3 offset(offsets[3 * k], offsets[3 * k + 1], offsets[3 * k + 2]);
      out[b].positions.push_back(frame.to_metres(point + offset));
      out[b].offset_m.push_back(offset.norm() * frame.scale_m);
    }
  }
  return out;
}

}  // namespace lc2wf

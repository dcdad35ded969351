#include "nn/losses.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "core/ops.h"

namespace lc2wf {

namespace {
void check_targets(const JunctionOutput& out, const JunctionTargets& t) {
  const Shape& ls = out.logits.shape();
  if (ls.size() != 3 || ls[2] != 2 || out.offsets.shape() != Shape{ls[0], ls[1], 3})
    throw std::invalid_argument("junction_loss: expected logits (B, G, 2) and offsets (B, G, 3), got " +
                                shape_str(ls) + " and " + shape_str(out.offsets.shape()));
  if (!t.labels.defined() || t.labels.dtype() != DType::I64 || t.labels.shape() != Shape{ls[0], ls[1]})
    throw std::invalid_argument("junction_loss: labels must be I64 " + shape_str({ls[0], ls[1]}));
  if (!t.offsets.defined() || t.offsets.shape() != out.offsets.shape() || t.offsets.dtype() != out.offsets.dtype())
    throw std::invalid_argument("junction_loss: target offsets must match the predicted offsets " +
                                shape_str(out.offsets.shape()));
}

// Per-patch regression weights cls / (sum_g cls + 1e-8) / B, shape (B, G, 1): turns the release's
// per-building mean over positive patches followed by the batch mean into one weighted sum.
Tensor regression_weights(const Tensor& labels, DType dtype) {
  const int64_t B = labels.size(0), G = labels.size(1);
  const std::vector<double> cls = labels.to_vector();
  std::vector<double> w(static_cast<size_t>(B * G), 0.0);
  for (int64_t b = 0; b < B; ++b) {
    double positives = 0.0;
    for (int64_t g = 0; g < G; ++g) {
      const double c = cls[b * G + g];
      if (c != 0.0 && c != 1.0)
        throw std::invalid_argument("junction_loss: labels must be 0 or 1, got " + std::to_string(c));
      positives += c;
    }
    for (int64_t g = 0; g < G; ++g) w[b * G + g] = cls[b * G + g] / (positives + 1e-8) / static_cast<double>(B);
  }
  return Tensor::from_vector(w, {B, G, 1}).to(dtype);
}
}  // namespace

LossTerms junction_loss(const JunctionOutput& out, const JunctionTargets& t, const JunctionLossConfig& config) {
  config.Check();
  check_targets(out, t);
  const int64_t B = out.logits.size(0), G = out.logits.size(1);
  const DType dtype = out.offsets.dtype();
  const Tensor weights = regression_weights(t.labels, dtype);
  // Negative patches may carry arbitrary targets; zero them so a NaN there cannot leak through 0 * NaN.
  std::vector<uint8_t> negative(static_cast<size_t>(B * G));
  const std::vector<double> labels = t.labels.to_vector();
  for (size_t i = 0; i < negative.size(); ++i) negative[i] = labels[i] == 0.0;
  const Tensor target = masked_fill(t.offsets, Tensor::from_mask(negative, {B, G, 1}), 0.0);
  const Tensor diff = out.offsets - target;
  LossTerms terms;
  if (config.kind == "release") {
    terms.classification = cross_entropy(out.logits.reshape({B * G, 2}), t.labels.reshape({B * G}));
    terms.regression = sum(abs(diff) * weights) * config.reg_weight;
  } else {
    const Tensor positive_logit = slice(out.logits, 2, 1, 2) - slice(out.logits, 2, 0, 1);
    terms.classification = bce_with_logits(positive_logit.reshape({B, G}), t.labels.to(dtype));
    terms.regression = sum(diff * diff * weights) * config.reg_weight;
  }
  terms.total = terms.classification + terms.regression;
  return terms;
}

Tensor edge_loss(const Tensor& logits, const Tensor& labels, const EdgeLossConfig& config, double weight_total) {
  config.Check();
  const int64_t C = static_cast<int64_t>(config.class_weights.size());
  if (logits.dim() != 3 || logits.size(2) != C)
    throw std::invalid_argument("edge_loss: expected logits (B, P, " + std::to_string(C) + "), got " +
                                shape_str(logits.shape()));
  if (!labels.defined() || labels.dtype() != DType::I64 || labels.shape() != Shape{logits.size(0), logits.size(1)})
    throw std::invalid_argument("edge_loss: labels must be I64 " + shape_str({logits.size(0), logits.size(1)}));
  const int64_t R = logits.size(0) * logits.size(1);
  const Tensor weight = Tensor::from_vector(config.class_weights, {C}).to(logits.dtype());
  if (!(weight_total > 0)) return cross_entropy(logits.reshape({R, C}), labels.reshape({R}), weight);
  return cross_entropy(logits.reshape({R, C}), labels.reshape({R}), weight, -100, Reduction::Sum) * (1.0 / weight_total);
}

double edge_loss_weight(const Tensor& labels, const EdgeLossConfig& config) {
  config.Check();
  if (!labels.defined() || labels.dtype() != DType::I64) throw std::invalid_argument("edge_loss_weight: labels must be I64");
  const int64_t* t = labels.data<int64_t>();
  double total = 0.0;
  for (int64_t k = 0; k < labels.numel(); ++k) {
    if (t[k] < 0 || t[k] >= static_cast<int64_t>(config.class_weights.size()))
      throw std::invalid_argument("edge_loss_weight: label " + std::to_string(t[k]) + " is not a class");
    total += config.class_weights[t[k]];
  }
  return total;
}

}  // namespace lc2wf

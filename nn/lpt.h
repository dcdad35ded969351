// Line-Patch Transformer (LC2WF paper, as in the release): per-line MLP with BatchNorm over every line slot, an encoder
// over the N lines of each patch (padding-masked), pooling over the N slots, and an encoder over the G
// patches of each building.
#pragma once

#include <memory>
#include <vector>

#include "core/rng.h"
#include "core/tensor.h"
#include "nn/config.h"
#include "nn/layers.h"
#include "nn/module.h"
#include "nn/transformer.h"

namespace lc2wf {

// One MLP stage: Linear + BatchNorm + ReLU (the release's 1x1 Conv2d + BatchNorm2d + ReLU).
class LinearBnRelu : public Module {
 public:
  LinearBnRelu(int64_t in, int64_t out, Rng& init_rng);
  Tensor forward(const Tensor& x);  // (M, in) -> (M, out)
  const Linear& fc() const { return fc_; }
  const BatchNorm& bn() const { return bn_; }

 private:
  Linear fc_;
  BatchNorm bn_;
};

class LinePatchTransformer : public Module {
 public:
  // Line slots per chunk when patches are encoded without gradients in eval mode (about 16 MB per
  // activation at width 256): the edge model meets thousands of pairs per building at inference.
  static constexpr int64_t kInferenceTokensPerChunk = 16384;
  LinePatchTransformer(const LptConfig& config, Rng& init_rng);
  // x (B, G, N, F) F32; mask Bool (B, G, N), true = padded slot. Returns (B, G, hidden_dim).
  Tensor forward(const Tensor& x, const Tensor& mask, Rng& rng);
  const LptConfig& config() const { return config_; }
  // Training only: rebuild the line MLP's activations (M x 640 floats twice at the paper's sizes) in the
  // backward pass instead of keeping them. Same values and gradients; less memory, slower steps.
  void set_recompute_mlp(bool on) { recompute_mlp_ = on; }

 private:
  // Line MLP, line encoder and pooling of R patches: rows (R, N, F), mask (R, N) -> (R, E).
  Tensor encode_patches(const Tensor& rows, const Tensor& mask, Rng& rng);
  Tensor line_mlp(const Tensor& rows) const;
  Tensor pool(const Tensor& lines, const Tensor& mask) const;

  LptConfig config_;
  bool recompute_mlp_ = false;
  std::vector<std::unique_ptr<LinearBnRelu>> mlp_;
  TransformerEncoder enc1_, enc2_;
};

// Validates x (B, G, N, F) and mask (B, G, N) against the config, naming `who` in the error.
void check_patch_input(const Tensor& x, const Tensor& mask, const LptConfig& config, const char* who);

}  // namespace lc2wf

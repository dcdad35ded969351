#include "nn/lpt.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/ops.h"

namespace lc2wf {

namespace {
EncoderSizes encoder_sizes(const LptConfig& c) {
  return {c.hidden_dim, c.num_heads, c.ffn_dim, c.dropout, c.attn_dropout};
}
const LptConfig& checked(const LptConfig& c) {
  c.Check();
  return c;
}
}  // namespace

LinearBnRelu::LinearBnRelu(int64_t in, int64_t out, Rng& init_rng) : fc_(in, out, init_rng), bn_(out) {
  register_module("fc", fc_);
  register_module("bn", bn_);
}

Tensor LinearBnRelu::forward(const Tensor& x) { return relu(bn_.forward(fc_.forward(x))); }

LinePatchTransformer::LinePatchTransformer(const LptConfig& config, Rng& init_rng)
    : config_(checked(config)),
      enc1_(encoder_sizes(config), config.line_layers, init_rng),
      enc2_(encoder_sizes(config), config.patch_layers, init_rng) {
  // Members are built in declaration order, so the MLP draws its weights after the encoders.
  int64_t in = config.input_dim;
  for (size_t i = 0; i < config.mlp_dims.size(); ++i) {
    mlp_.push_back(std::make_unique<LinearBnRelu>(in, config.mlp_dims[i], init_rng));
    register_module("mlp." + std::to_string(i), *mlp_.back());
    in = config.mlp_dims[i];
  }
  register_module("enc1", enc1_);
  register_module("enc2", enc2_);
}

void check_patch_input(const Tensor& x, const Tensor& mask, const LptConfig& c, const char* who) {
  const std::string name(who);
  if (!x.defined() || x.dim() != 4 || x.size(2) != c.lines_per_patch || x.size(3) != c.input_dim)
    throw std::invalid_argument(name + ": expected input (B, G, " + std::to_string(c.lines_per_patch) + ", " +
                                std::to_string(c.input_dim) + "), got " +
                                (x.defined() ? shape_str(x.shape()) : std::string("undefined")));
  if (x.dtype() != DType::F32 && x.dtype() != DType::F64)
    throw std::invalid_argument(name + ": input must be F32 or F64, got " + dtype_name(x.dtype()));
  const Shape mask_shape{x.size(0), x.size(1), x.size(2)};
  if (!mask.defined() || mask.dtype() != DType::Bool || mask.shape() != mask_shape)
    throw std::invalid_argument(name + ": expected a Bool mask " + shape_str(mask_shape) + ", got " +
                                (mask.defined() ? std::string(dtype_name(mask.dtype())) + " " + shape_str(mask.shape())
                                                : std::string("undefined")));
}

Tensor LinePatchTransformer::forward(const Tensor& x, const Tensor& mask, Rng& rng) {
  check_patch_input(x, mask, config_, "LinePatchTransformer");
  const int64_t B = x.size(0), G = x.size(1), N = x.size(2), E = config_.hidden_dim;
  const Tensor rows = x.reshape({B * G, N, config_.input_dim});
  const Tensor row_mask = mask.reshape({B * G, N});
  // Inference: each patch's lines are encoded independently of every other patch (BatchNorm uses its
  // running statistics, no dropout), so a building's thousands of pair patches go through in chunks that
  // stay in cache instead of as activations of gigabytes. Training needs the whole batch (statistics, graph).
  const int64_t chunk = std::max<int64_t>(1, kInferenceTokensPerChunk / N);
  Tensor patches;
  if (is_training() || grad_enabled() || B * G <= chunk) {
    patches = encode_patches(rows, row_mask, rng);
  } else {
    std::vector<Tensor> parts;
    for (int64_t first = 0; first < B * G; first += chunk) {
      const int64_t last = std::min(B * G, first + chunk);
      parts.push_back(encode_patches(slice(rows, 0, first, last), slice(row_mask, 0, first, last), rng));
    }
    patches = concat(parts, 0);
  }
  return enc2_.forward(patches.reshape({B, G, E}), Tensor(), rng);
}

Tensor LinePatchTransformer::encode_patches(const Tensor& rows, const Tensor& mask, Rng& rng) {
  const int64_t R = rows.size(0), N = rows.size(1), E = config_.hidden_dim;
  const Tensor h = line_mlp(rows.reshape({R * N, config_.input_dim}));
  return pool(enc1_.forward(h.reshape({R, N, E}), mask, rng), mask);
}

// The MLP runs on every line slot: checkpointed (set_recompute_mlp), its Linear outputs and ReLU
// activations are rebuilt from the (M x F) input in the backward pass instead of being kept through the
// whole step. Forward values and gradients are the same ops on the same data either way.
Tensor LinePatchTransformer::line_mlp(const Tensor& rows) const {
  struct Running {
    Tensor mean, var;
    double momentum, eps;
    bool training;
  };
  std::vector<Tensor> inputs{rows};
  std::vector<Running> running;
  for (const auto& stage : mlp_) {
    const BatchNorm& bn = stage->bn();
    inputs.insert(inputs.end(), {stage->fc().weight(), stage->fc().bias(), bn.weight(), bn.bias()});
    running.push_back({bn.running_mean(), bn.running_var(), bn.momentum(), bn.eps(), bn.is_training()});
  }
  auto stages = [running](const std::vector<Tensor>& in, bool recompute) {
    Tensor h = in[0];
    for (size_t i = 0; i < running.size(); ++i) {
      const Running& r = running[i];
      // The recomputation uses the batch statistics again but must not update the running ones twice.
      Tensor mean = recompute && r.training ? Tensor() : r.mean;
      Tensor var = recompute && r.training ? Tensor() : r.var;
      const Tensor* p = &in[1 + 4 * i];
      h = relu(batch_norm(linear(h, p[0], p[1]), p[2], p[3], mean, var, r.training, r.momentum, r.eps));
    }
    return h;
  };
  return recompute_mlp_ ? checkpoint(inputs, stages) : stages(inputs, false);
}

Tensor LinePatchTransformer::pool(const Tensor& lines, const Tensor& mask) const {
  if (config_.pool == "mean_all") return mean(lines, {1});
  // mean_valid: weights 1/#valid on valid slots, 0 elsewhere; a fully padded patch pools to zero.
  const int64_t R = lines.size(0), N = lines.size(1);
  const std::vector<double> padded = mask.to_vector();
  std::vector<float> w(static_cast<size_t>(R * N), 0.0f);
  for (int64_t r = 0; r < R; ++r) {
    int64_t valid = 0;
    for (int64_t n = 0; n < N; ++n) valid += padded[r * N + n] == 0.0;
    for (int64_t n = 0; n < N; ++n)
      if (padded[r * N + n] == 0.0) w[r * N + n] = 1.0f / static_cast<float>(valid);
  }
  Tensor weights = Tensor::from_vector(w, {R, N, 1});
  if (lines.dtype() != DType::F32) weights = weights.to(lines.dtype());
  return sum(lines * weights, {1});
}

}  // namespace lc2wf

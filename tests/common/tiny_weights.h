// A junction + edge model pair with tiny random networks, saved as lc2wf-train would: the weights folder
// the inference and reconstruction tests run on.
#pragma once

#include <filesystem>
#include <stdexcept>

#include "nn/checkpoint.h"
#include "nn/edge_net.h"
#include "nn/junction_net.h"

namespace lc2wf::test {

inline LptConfig tiny_lpt(int64_t patches, int64_t lines, int64_t features, int64_t width = 16) {
  LptConfig c;
  c.input_dim = features;
  c.patches = patches;
  c.lines_per_patch = lines;
  c.mlp_dims = {8, width};
  c.hidden_dim = width;
  c.num_heads = 2;
  c.ffn_dim = width;
  return c;
}

// <dir>/junction.safetensors (32 samples of 8 lines) and <dir>/edge.safetensors (pairs of 2 x 8 lines).
// A width above 16 sends the products through the GEMM (narrower ones take the small-K loop).
// connect_pairs: the edge model calls nearly every pair connected (class 1's bias raised), so a test that
// scores wireframes gets non-empty ones from untrained networks.
inline void write_tiny_weights(const std::filesystem::path& dir, int64_t width = 16, bool connect_pairs = false) {
  std::filesystem::create_directories(dir);
  JunctionNetConfig jc;
  jc.lpt = tiny_lpt(32, 8, 7, width);
  jc.head.dims = {8};
  EdgeNetConfig ec;
  ec.lpt = tiny_lpt(16, 16, 6, width);
  ec.head.dims = {8};
  JunctionNet j(jc, 3);
  EdgeNet e(ec, 4);
  if (connect_pairs) {
    Tensor bias = e.named_parameters().back().second;  // the head's last layer: one logit per class
    if (bias.numel() != 5) throw std::logic_error("write_tiny_weights: the edge head's last parameter is not its class bias");
    bias.data<float>()[1] += 10.0f;
  }
  save_checkpoint(dir / "junction.safetensors", j, {{"stage", "junction"}, {"net", jc.to_json()}}, j.dropout_rng(), nullptr, {});
  save_checkpoint(dir / "edge.safetensors", e, {{"stage", "edge"}, {"net", ec.to_json()}}, e.dropout_rng(), nullptr, {});
}

}  // namespace lc2wf::test

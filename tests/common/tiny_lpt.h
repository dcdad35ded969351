// The tiny LPT sizes the training tests share (seconds per run on 2 cores), as config JSON.
#pragma once

#include <nlohmann/json.hpp>

namespace lc2wf::testing {

struct TinyLpt {
  nlohmann::json junction;  // 24 patches of 8 lines
  nlohmann::json edge;      // 32 pairs of 16 lines
};

inline TinyLpt tiny_lpt() {
  const nlohmann::json lpt = {{"mlp_dims", {16, 16, 24}}, {"hidden_dim", 24}, {"num_heads", 2}, {"ffn_dim", 24},
                              {"dropout", 0.1},           {"attn_dropout", 0.1}};
  TinyLpt t{lpt, lpt};
  t.junction["patches"] = 24;
  t.junction["lines_per_patch"] = 8;
  t.edge["patches"] = 32;
  t.edge["lines_per_patch"] = 16;
  return t;
}

}  // namespace lc2wf::testing

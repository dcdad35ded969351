#include "nn/edge_net.h"

namespace lc2wf {

namespace {
const EdgeNetConfig& checked(const EdgeNetConfig& c) {
  c.Check();
  return c;
}
constexpr uint64_t kDropoutStream = 0xD1B54A32D192ED03ull;
}  // namespace

EdgeNet::EdgeNet(const EdgeNetConfig& config, uint64_t seed)
    : config_(checked(config)),
      init_rng_(seed),
      lpt_(config.lpt, init_rng_),
      cls_head_(config.lpt.hidden_dim, config.head, config.num_classes, init_rng_),
      dropout_rng_(seed ^ kDropoutStream) {
  register_module("lpt", lpt_);
  register_module("cls_head", cls_head_);
}

Tensor EdgeNet::forward(const Tensor& x, const Tensor& mask) {
  const Tensor features = lpt_.forward(x, mask, dropout_rng_);
  const int64_t B = features.size(0), P = features.size(1);
  return cls_head_.forward(features.reshape({B * P, config_.lpt.hidden_dim}), dropout_rng_)
      .reshape({B, P, config_.num_classes});
}

}  // namespace lc2wf

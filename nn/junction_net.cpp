#include "nn/junction_net.h"

namespace lc2wf {

namespace {
const JunctionNetConfig& checked(const JunctionNetConfig& c) {
  c.Check();
  return c;
}
// A fixed odd offset keeps the dropout stream disjoint from the init stream of the same seed.
constexpr uint64_t kDropoutStream = 0xD1B54A32D192ED03ull;
}  // namespace

JunctionNet::JunctionNet(const JunctionNetConfig& config, uint64_t seed)
    : config_(checked(config)),
      init_rng_(seed),
      lpt_(config.lpt, init_rng_),
      cls_head_(config.lpt.hidden_dim, config.head, 2, init_rng_),
      reg_head_(config.lpt.hidden_dim, config.head, 3, init_rng_),
      dropout_rng_(seed ^ kDropoutStream) {
  register_module("lpt", lpt_);
  register_module("cls_head", cls_head_);
  register_module("reg_head", reg_head_);
}

JunctionOutput JunctionNet::forward(const Tensor& x, const Tensor& mask) {
  const Tensor features = lpt_.forward(x, mask, dropout_rng_);
  const int64_t B = features.size(0), G = features.size(1);
  const Tensor rows = features.reshape({B * G, config_.lpt.hidden_dim});
  return {cls_head_.forward(rows, dropout_rng_).reshape({B, G, 2}),
          reg_head_.forward(rows, dropout_rng_).reshape({B, G, 3})};
}

}  // namespace lc2wf

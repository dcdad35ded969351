#include "nn/head.h"

#include <string>

namespace lc2wf {

Head::Head(int64_t in, const HeadConfig& config, int64_t out, Rng& init_rng)
    : dropout_(config.dropout), out_(config.dims.back(), out, init_rng) {
  int64_t width = in;
  for (size_t i = 0; i < config.dims.size(); ++i) {
    blocks_.push_back(std::make_unique<LinearBnRelu>(width, config.dims[i], init_rng));
    register_module(std::to_string(i), *blocks_.back());
    width = config.dims[i];
  }
  register_module("dropout", dropout_);
  register_module("out", out_);
}

Tensor Head::forward(const Tensor& x, Rng& rng) {
  Tensor h = x;
  for (auto& block : blocks_) h = dropout_.forward(block->forward(h), rng);
  return out_.forward(h);
}

}  // namespace lc2wf

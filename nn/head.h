// Prediction head (release `Head` branch): [Linear + BatchNorm + ReLU + Dropout] per hidden width, then
// a final Linear. BatchNorm statistics run over all B*G rows, like the release's BatchNorm1d.
#pragma once

#include <memory>
#include <vector>

#include "core/rng.h"
#include "core/tensor.h"
#include "nn/config.h"
#include "nn/layers.h"
#include "nn/lpt.h"
#include "nn/module.h"

namespace lc2wf {

class Head : public Module {
 public:
  Head(int64_t in, const HeadConfig& config, int64_t out, Rng& init_rng);
  Tensor forward(const Tensor& x, Rng& rng);  // (R, in) -> (R, out)

 private:
  std::vector<std::unique_ptr<LinearBnRelu>> blocks_;
  Dropout dropout_;
  Linear out_;
};

}  // namespace lc2wf

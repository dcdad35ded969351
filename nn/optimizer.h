// Optimisers with PyTorch's update rules: AdamW (decoupled weight decay) and SGD with momentum.
// Weight decay applies to every parameter whose name does not contain "bias" (the release's grouping;
// BatchNorm/LayerNorm scales are decayed). State is exposed as named tensors for checkpoints.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/tensor.h"
#include "nn/config.h"
#include "nn/module.h"

namespace lc2wf {

class Optimizer {
 public:
  Optimizer(NamedTensors params, double lr, double weight_decay);
  virtual ~Optimizer() = default;
  Optimizer(const Optimizer&) = delete;
  Optimizer& operator=(const Optimizer&) = delete;

  void step();  // parameters without a gradient are skipped
  void zero_grad();
  double lr() const { return lr_; }
  void set_lr(double lr) { lr_ = lr; }
  int64_t step_count() const { return step_count_; }

  // Per-parameter state tensors, named "<slot>.<parameter name>".
  NamedTensors state() const;
  // Restores state() output; any missing, unexpected or misshaped tensor throws naming it.
  void load_state(const std::map<std::string, Tensor>& tensors, int64_t step_count, const std::string& source);

 protected:
  struct Param {
    std::string name;
    Tensor value;
    double weight_decay;
    std::vector<Tensor> slots;  // optimiser state, same shape and dtype as value
  };
  virtual std::vector<std::string> slot_names() const = 0;
  virtual void update(Param& p, const Tensor& grad) = 0;
  void init_slots();

  std::vector<Param> params_;
  double lr_;
  int64_t step_count_ = 0;
};

class AdamW : public Optimizer {
 public:
  AdamW(NamedTensors params, const OptimConfig& config);

 private:
  std::vector<std::string> slot_names() const override { return {"exp_avg", "exp_avg_sq"}; }
  void update(Param& p, const Tensor& grad) override;
  double beta1_, beta2_, eps_;
};

class Sgd : public Optimizer {
 public:
  Sgd(NamedTensors params, const OptimConfig& config);

 private:
  std::vector<std::string> slot_names() const override { return {"momentum_buffer"}; }
  void update(Param& p, const Tensor& grad) override;
  double momentum_;
};

// Builds the optimiser named by config.optimizer over every parameter of `module`.
std::unique_ptr<Optimizer> make_optimizer(const Module& module, const OptimConfig& config);

// Scales all gradients so their global L2 norm is at most max_norm (PyTorch's clip_grad_norm_:
// coefficient max_norm / (norm + 1e-6)). Returns the norm before clipping.
double clip_grad_norm(const std::vector<Tensor>& params, double max_norm);

// MultiStepLR: lr = base_lr * gamma^(number of milestones <= epoch), epoch counted from 0 like
// PyTorch's scheduler after `epoch` calls of step().
class MultiStepLR {
 public:
  MultiStepLR(double base_lr, std::vector<int64_t> milestones, double gamma);
  double lr_at(int64_t epoch) const;

 private:
  double base_lr_;
  std::vector<int64_t> milestones_;
  double gamma_;
};

}  // namespace lc2wf

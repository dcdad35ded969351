// Module: a tree of named parameters and buffers with PyTorch-style hierarchical names
// ("lpt.enc1.layers.0.self_attn.in_proj_weight"), so weights map 1:1 onto state dicts and checkpoints.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/tensor.h"

namespace lc2wf {

using NamedTensors = std::vector<std::pair<std::string, Tensor>>;

class Module {
 public:
  Module() = default;
  virtual ~Module() = default;
  // Children are registered by address, so a module never moves once built.
  Module(const Module&) = delete;
  Module& operator=(const Module&) = delete;

  void train(bool on = true);
  void eval() { train(false); }
  bool is_training() const { return training_; }

  void zero_grad();
  int64_t num_parameters() const;  // number of scalar parameters

  // Registration order, depth first; names are prefix-joined with '.'.
  NamedTensors named_parameters() const;
  NamedTensors named_buffers() const;
  NamedTensors state_dict() const;  // parameters then buffers
  std::vector<Tensor> parameters() const;

  // Copies every tensor of `tensors` into this module. Strict: a missing, unexpected or misshaped
  // tensor throws std::invalid_argument naming it (`source` names the file for the message).
  void load_state_dict(const std::map<std::string, Tensor>& tensors, const std::string& source = "state dict");

 protected:
  // Returns the handle to keep as a member; it aliases the registered tensor.
  Tensor register_parameter(const std::string& name, Tensor value);
  Tensor register_buffer(const std::string& name, Tensor value);
  void register_module(const std::string& name, Module& child);

 private:
  void collect(const std::string& prefix, bool params, bool buffers, NamedTensors& out) const;

  std::vector<std::pair<std::string, Tensor>> params_;
  std::vector<std::pair<std::string, Tensor>> buffers_;
  std::vector<std::pair<std::string, Module*>> children_;
  bool training_ = true;
};

}  // namespace lc2wf

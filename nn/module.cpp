#include "nn/module.h"

#include <set>
#include <stdexcept>

namespace lc2wf {

void Module::train(bool on) {
  training_ = on;
  for (auto& [name, child] : children_) child->train(on);
}

void Module::zero_grad() {
  for (auto& [name, p] : named_parameters()) p.zero_grad();
}

int64_t Module::num_parameters() const {
  int64_t n = 0;
  for (const auto& [name, p] : named_parameters()) n += p.numel();
  return n;
}

void Module::collect(const std::string& prefix, bool params, bool buffers, NamedTensors& out) const {
  if (params)
    for (const auto& [name, t] : params_) out.emplace_back(prefix + name, t);
  if (buffers)
    for (const auto& [name, t] : buffers_) out.emplace_back(prefix + name, t);
  for (const auto& [name, child] : children_) child->collect(prefix + name + ".", params, buffers, out);
}

NamedTensors Module::named_parameters() const {
  NamedTensors out;
  collect("", true, false, out);
  return out;
}

NamedTensors Module::named_buffers() const {
  NamedTensors out;
  collect("", false, true, out);
  return out;
}

NamedTensors Module::state_dict() const {
  NamedTensors out = named_parameters();
  NamedTensors bufs = named_buffers();
  out.insert(out.end(), bufs.begin(), bufs.end());
  return out;
}

std::vector<Tensor> Module::parameters() const {
  std::vector<Tensor> out;
  for (auto& [name, p] : named_parameters()) out.push_back(p);
  return out;
}

void Module::load_state_dict(const std::map<std::string, Tensor>& tensors, const std::string& source) {
  const NamedTensors own = state_dict();
  std::set<std::string> expected;
  for (const auto& [name, t] : own) {
    expected.insert(name);
    auto it = tensors.find(name);
    if (it == tensors.end()) throw std::invalid_argument(source + ": missing tensor '" + name + "'");
    const Tensor& src = it->second;
    if (src.shape() != t.shape())
      throw std::invalid_argument(source + ": tensor '" + name + "' has shape " + shape_str(src.shape()) +
                                  ", expected " + shape_str(t.shape()));
    if (src.dtype() != t.dtype())
      throw std::invalid_argument(source + ": tensor '" + name + "' has dtype " + dtype_name(src.dtype()) +
                                  ", expected " + dtype_name(t.dtype()));
  }
  for (const auto& [name, t] : tensors)
    if (!expected.count(name)) throw std::invalid_argument(source + ": unexpected tensor '" + name + "'");
  // Copy only after every check passed, so a failed load leaves the module untouched.
  for (const auto& [name, t] : own) {
    Tensor dst = t;
    dst.copy_(tensors.at(name));
  }
}

Tensor Module::register_parameter(const std::string& name, Tensor value) {
  value.set_requires_grad(true);
  params_.emplace_back(name, value);
  return value;
}

Tensor Module::register_buffer(const std::string& name, Tensor value) {
  buffers_.emplace_back(name, value);
  return value;
}

void Module::register_module(const std::string& name, Module& child) {
  child.training_ = training_;
  children_.emplace_back(name, &child);
}

}  // namespace lc2wf

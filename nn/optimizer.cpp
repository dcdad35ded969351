#include "nn/optimizer.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "core/parallel.h"

namespace lc2wf {

namespace {
constexpr int64_t kGrain = 1 << 15;

template <class F>
void for_float(const Tensor& t, F&& f) {
  if (t.dtype() == DType::F32) f(float{});
  else if (t.dtype() == DType::F64) f(double{});
  else throw std::invalid_argument(std::string("optimizer: parameters must be F32 or F64, got ") + dtype_name(t.dtype()));
}
}  // namespace

Optimizer::Optimizer(NamedTensors params, double lr, double weight_decay) : lr_(lr) {
  for (auto& [name, value] : params) {
    const double wd = name.find("bias") == std::string::npos ? weight_decay : 0.0;
    params_.push_back({name, value, wd, {}});
  }
}

void Optimizer::init_slots() {
  const size_t n = slot_names().size();
  for (auto& p : params_) {
    p.slots.clear();
    for (size_t i = 0; i < n; ++i) p.slots.push_back(Tensor::zeros(p.value.shape(), p.value.dtype()));
  }
}

void Optimizer::step() {
  ++step_count_;
  for (auto& p : params_) {
    const Tensor grad = p.value.grad();
    if (!grad.defined()) continue;
    if (grad.shape() != p.value.shape() || grad.dtype() != p.value.dtype())
      throw std::invalid_argument("optimizer: gradient of '" + p.name + "' does not match the parameter");
    update(p, grad);
  }
}

void Optimizer::zero_grad() {
  for (auto& p : params_) p.value.zero_grad();
}

NamedTensors Optimizer::state() const {
  NamedTensors out;
  const std::vector<std::string> slots = slot_names();
  for (size_t s = 0; s < slots.size(); ++s)
    for (const auto& p : params_) out.emplace_back(slots[s] + "." + p.name, p.slots[s]);
  return out;
}

void Optimizer::load_state(const std::map<std::string, Tensor>& tensors, int64_t step_count, const std::string& source) {
  const NamedTensors own = state();
  std::set<std::string> expected;
  for (const auto& [name, t] : own) {
    expected.insert(name);
    auto it = tensors.find(name);
    if (it == tensors.end()) throw std::invalid_argument(source + ": missing optimizer tensor '" + name + "'");
    if (it->second.shape() != t.shape() || it->second.dtype() != t.dtype())
      throw std::invalid_argument(source + ": optimizer tensor '" + name + "' is " + dtype_name(it->second.dtype()) +
                                  " " + shape_str(it->second.shape()) + ", expected " + dtype_name(t.dtype()) + " " +
                                  shape_str(t.shape()));
  }
  for (const auto& [name, t] : tensors)
    if (!expected.count(name)) throw std::invalid_argument(source + ": unexpected optimizer tensor '" + name + "'");
  if (step_count < 0) throw std::invalid_argument(source + ": negative optimizer step count");
  for (const auto& [name, t] : own) {
    Tensor dst = t;
    dst.copy_(tensors.at(name));
  }
  step_count_ = step_count;
}

AdamW::AdamW(NamedTensors params, const OptimConfig& c)
    : Optimizer(std::move(params), c.lr, c.weight_decay), beta1_(c.beta1), beta2_(c.beta2), eps_(c.eps) {
  c.Check();
  init_slots();
}

void AdamW::update(Param& p, const Tensor& grad) {
  const double bc1 = 1.0 - std::pow(beta1_, static_cast<double>(step_count_));
  const double bc2_sqrt = std::sqrt(1.0 - std::pow(beta2_, static_cast<double>(step_count_)));
  const double step_size = lr_ / bc1;
  const double decay = 1.0 - lr_ * p.weight_decay;
  for_float(p.value, [&](auto zero) {
    using T = decltype(zero);
    T* w = p.value.data<T>();
    const T* g = grad.data<T>();
    T* m = p.slots[0].data<T>();
    T* v = p.slots[1].data<T>();
    const T b1 = static_cast<T>(beta1_), b2 = static_cast<T>(beta2_);
    parallel_for(p.value.numel(), kGrain, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        w[i] = static_cast<T>(w[i] * decay);
        m[i] = b1 * m[i] + (1 - b1) * g[i];
        v[i] = b2 * v[i] + (1 - b2) * g[i] * g[i];
        const T denom = static_cast<T>(std::sqrt(v[i]) / bc2_sqrt + eps_);
        w[i] = static_cast<T>(w[i] - step_size * m[i] / denom);
      }
    });
  });
}

Sgd::Sgd(NamedTensors params, const OptimConfig& c)
    : Optimizer(std::move(params), c.lr, c.weight_decay), momentum_(c.momentum) {
  c.Check();
  init_slots();
}

void Sgd::update(Param& p, const Tensor& grad) {
  const bool first = step_count_ == 1;
  for_float(p.value, [&](auto zero) {
    using T = decltype(zero);
    T* w = p.value.data<T>();
    const T* g = grad.data<T>();
    T* buf = p.slots[0].data<T>();
    const T wd = static_cast<T>(p.weight_decay), mom = static_cast<T>(momentum_), lr = static_cast<T>(lr_);
    parallel_for(p.value.numel(), kGrain, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        T d = g[i] + wd * w[i];
        if (mom != 0) {
          buf[i] = first ? d : mom * buf[i] + d;
          d = buf[i];
        }
        w[i] -= lr * d;
      }
    });
  });
}

std::unique_ptr<Optimizer> make_optimizer(const Module& module, const OptimConfig& config) {
  config.Check();
  if (config.optimizer == "adamw") return std::make_unique<AdamW>(module.named_parameters(), config);
  return std::make_unique<Sgd>(module.named_parameters(), config);
}

double clip_grad_norm(const std::vector<Tensor>& params, double max_norm) {
  double total_sq = 0.0;
  for (const Tensor& p : params) {
    const Tensor g = p.grad();
    if (!g.defined()) continue;
    for_float(g, [&](auto zero) {
      using T = decltype(zero);
      const T* d = g.data<T>();
      for (int64_t i = 0; i < g.numel(); ++i) total_sq += static_cast<double>(d[i]) * d[i];
    });
  }
  const double norm = std::sqrt(total_sq);
  const double coef = max_norm / (norm + 1e-6);
  if (coef >= 1.0) return norm;
  for (const Tensor& p : params) {
    Tensor g = p.grad();
    if (!g.defined()) continue;
    for_float(g, [&](auto zero) {
      using T = decltype(zero);
      T* d = g.data<T>();
      for (int64_t i = 0; i < g.numel(); ++i) d[i] = static_cast<T>(d[i] * coef);
    });
  }
  return norm;
}

MultiStepLR::MultiStepLR(double base_lr, std::vector<int64_t> milestones, double gamma)
    : base_lr_(base_lr), milestones_(std::move(milestones)), gamma_(gamma) {
  if (!std::is_sorted(milestones_.begin(), milestones_.end()))
    throw std::invalid_argument("MultiStepLR: milestones must be increasing");
}

double MultiStepLR::lr_at(int64_t epoch) const {
  const auto passed = std::upper_bound(milestones_.begin(), milestones_.end(), epoch) - milestones_.begin();
  return base_lr_ * std::pow(gamma_, static_cast<double>(passed));
}

}  // namespace lc2wf

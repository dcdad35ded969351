#include "train/gradient_reducer.h"

#include <chrono>
#include <cstring>
#include <stdexcept>

namespace lc2wf {

GradientReducer::GradientReducer(Communicator& comm, std::vector<Tensor> params, int64_t bucket_bytes)
    : comm_(comm), params_(std::move(params)) {
  if (bucket_bytes < 1) throw std::invalid_argument("GradientReducer: bucket_bytes must be >= 1");
  for (size_t k = params_.size(); k-- > 0;) {
    const Tensor& p = params_[k];
    if (p.dtype() != DType::F32) throw std::invalid_argument("GradientReducer: parameters must be F32");
    if (buckets_.empty() || buckets_.back().floats * 4 >= bucket_bytes) buckets_.emplace_back();
    Bucket& b = buckets_.back();
    b.params.push_back(k);
    b.floats += p.numel();
    bucket_of_[p.impl()] = buckets_.size() - 1;
  }
  for (Bucket& b : buckets_) b.buffer.resize(static_cast<size_t>(b.floats) + b.params.size());
}

GradientReducer::~GradientReducer() = default;

std::unique_ptr<LeafGradReadyHook> GradientReducer::overlap_next_backward() {
  if (comm_.size() == 1) return nullptr;
  return std::make_unique<LeafGradReadyHook>([this](const TensorImpl* leaf) { on_ready(leaf); });
}

void GradientReducer::on_ready(const TensorImpl* leaf) {
  const auto it = bucket_of_.find(leaf);
  if (it != bucket_of_.end()) ++buckets_[it->second].ready;
  start_in_order();
  // MPI moves a started sum along only inside MPI calls.
  for (size_t k = 0; k < next_; ++k)
    if (buckets_[k].pending) buckets_[k].pending->test();
}

void GradientReducer::start_in_order() {
  while (next_ < buckets_.size() && buckets_[next_].ready >= buckets_[next_].params.size()) start(buckets_[next_++]);
}

void GradientReducer::start(Bucket& b) {
  float* out = b.buffer.data();
  float* flags = out + b.floats;
  for (size_t i = 0; i < b.params.size(); ++i) {
    const Tensor& p = params_[b.params[i]];
    const Tensor g = p.grad();
    const size_t n = static_cast<size_t>(p.numel());
    if (g.defined()) std::memcpy(out, g.data<float>(), n * sizeof(float));
    else std::memset(out, 0, n * sizeof(float));
    flags[i] = g.defined() ? 1.0f : 0.0f;
    out += n;
  }
  b.pending = comm_.start_sum(b.buffer.data(), static_cast<int64_t>(b.buffer.size()), "gradient sum");
}

double GradientReducer::finish() {
  if (comm_.size() == 1) return 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  while (next_ < buckets_.size()) start(buckets_[next_++]);
  for (Bucket& b : buckets_) {
    b.pending->wait();
    b.pending.reset();
    const float* in = b.buffer.data();
    const float* flags = in + b.floats;
    for (size_t i = 0; i < b.params.size(); ++i) {
      Tensor& p = params_[b.params[i]];
      const size_t n = static_cast<size_t>(p.numel());
      if (flags[i] > 0.0f) {
        Tensor g = p.grad();
        if (!g.defined()) {
          g = Tensor::empty(p.shape(), DType::F32);
          p.set_grad(g);
        }
        std::memcpy(g.data<float>(), in, n * sizeof(float));
      }
      in += n;
    }
    b.ready = 0;
  }
  next_ = 0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace lc2wf

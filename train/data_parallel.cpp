#include "train/data_parallel.h"

#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/ops.h"
#include "nn/optimizer.h"

namespace lc2wf {

namespace {

std::vector<Tensor> f32_tensors(const NamedTensors& named, const char* what) {
  std::vector<Tensor> out;
  for (const auto& [name, t] : named) {
    if (t.dtype() != DType::F32)
      throw std::invalid_argument(std::string(what) + " '" + name + "' is not F32: data-parallel training sums F32 only");
    out.push_back(t);
  }
  return out;
}

}  // namespace

DataParallel::DataParallel(Communicator& comm, Module& model, Rng& dropout_rng, bool synchronised_batch_norm)
    : comm_(comm), model_(model), dropout_rng_(dropout_rng), synchronised_(synchronised_batch_norm) {
  if (comm_.size() > 1)
    reducer_ = std::make_unique<GradientReducer>(comm_, f32_tensors(model.named_parameters(), "parameter"), kGradientBucketBytes);
}

DataParallel::~DataParallel() = default;

double DataParallel::run_step(int64_t batch, int64_t micro_batch,
                              const std::function<void(int64_t first, int64_t count)>& pass) {
  const int ranks = comm_.size();
  // A batch too small to give every rank a building in every synchronised pass (the last one of an epoch
  // without drop_last) uses per-rank statistics; every rank comes to the same decision.
  const bool synchronised = synchronised_ && ranks > 1 && synchronised_batch_problem(batch, ranks, micro_batch).empty();
  const auto passes = share_passes(batch, comm_.rank(), ranks, micro_batch, synchronised);
  std::unique_ptr<BatchNormSyncGuard> sync;
  if (synchronised)
    sync = std::make_unique<BatchNormSyncGuard>(
        [this](double* values, int64_t n) { comm_.sum(values, n, "synchronised BatchNorm statistics"); });
  // Every pass draws from the step's first stream position: the batch's masks, sliced.
  const uint64_t seed = dropout_rng_.seed(), start = dropout_rng_.counter();
  uint64_t end = start;
  for (size_t k = 0; k < passes.size(); ++k) {
    const auto [first, count] = passes[k];
    dropout_rng_.set_state(seed, start);
    dropout_rng_.set_batch_slice(static_cast<uint64_t>(first), static_cast<uint64_t>(count), static_cast<uint64_t>(batch));
    std::unique_ptr<LeafGradReadyHook> overlap = k + 1 == passes.size() && reducer_ ? reducer_->overlap_next_backward() : nullptr;
    pass(first, count);
    end = dropout_rng_.counter();
  }
  dropout_rng_.clear_batch_slice();
  sync.reset();
  if (ranks == 1) {
    dropout_rng_.set_state(seed, end);
    return 0.0;
  }
  const double seconds = reducer_->finish();
  if (!synchronised) average_running_statistics(!passes.empty());
  // A rank without buildings in this batch drew nothing; the others agree on where the stream is.
  dropout_rng_.set_state(seed, comm_.max(end, "dropout stream position"));
  return seconds;
}

void DataParallel::average_running_statistics(bool ran) {
  const std::vector<Tensor> buffers = f32_tensors(model_.named_buffers(), "buffer");
  std::vector<double> values;
  for (const Tensor& b : buffers)
    for (int64_t i = 0; i < b.numel(); ++i) values.push_back(ran ? static_cast<double>(b.data<float>()[i]) : 0.0);
  values.push_back(ran ? 1.0 : 0.0);  // ranks that saw buildings in this step
  comm_.sum(values.data(), static_cast<int64_t>(values.size()), "BatchNorm running statistics");
  const double contributors = values.back();
  size_t at = 0;
  for (const Tensor& b : buffers) {
    float* out = const_cast<Tensor&>(b).data<float>();
    for (int64_t i = 0; i < b.numel(); ++i) out[i] = static_cast<float>(values[at++] / contributors);
  }
}

uint64_t state_fingerprint(const Module& model) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const auto& [name, t] : model.state_dict()) {
    const auto* bytes = static_cast<const unsigned char*>(t.dtype() == DType::F32 ? static_cast<const void*>(t.data<float>())
                                                                                 : static_cast<const void*>(t.data<double>()));
    const size_t n = static_cast<size_t>(t.numel()) * (t.dtype() == DType::F32 ? 4 : 8);
    // 8 bytes at a time through a multiply-xorshift: fast enough to run after every step.
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
      uint64_t w;
      std::memcpy(&w, bytes + i, 8);
      h = (h ^ w) * 0x100000001b3ull;
      h ^= h >> 29;
    }
    for (; i < n; ++i) h = (h ^ bytes[i]) * 0x100000001b3ull;
  }
  return h;
}

void broadcast_training_state(Communicator& comm, Module& model, Optimizer* optimizer, Rng& dropout_rng) {
  if (comm.size() == 1) return;
  for (Tensor& t : f32_tensors(model.state_dict(), "tensor")) comm.broadcast(t.data<float>(), t.numel(), "start-up state");
  std::ostringstream meta;
  meta << dropout_rng.seed() << ' ' << dropout_rng.counter() << ' ' << (optimizer ? optimizer->step_count() : 0);
  std::string text = meta.str();
  comm.broadcast(text, "start-up state");
  uint64_t seed = 0, counter = 0;
  int64_t steps = 0;
  std::istringstream(text) >> seed >> counter >> steps;
  dropout_rng.set_state(seed, counter);
  if (!optimizer) return;
  std::map<std::string, Tensor> slots;
  for (auto& [name, t] : optimizer->state()) {
    if (t.dtype() != DType::F32) throw std::invalid_argument("optimiser state '" + name + "' is not F32");
    comm.broadcast(t.data<float>(), t.numel(), "start-up state");
    slots.emplace(name, t.detach().clone());  // load_state copies them back into the slots
  }
  optimizer->load_state(slots, steps, "rank 0");
}

}  // namespace lc2wf

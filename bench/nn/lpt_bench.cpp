// Line-Patch Transformer speed at the paper's shapes: one training step (forward, release loss,
// backward, AdamW) of each model and one inference pass per building. Reports seconds per iteration
// and the process's peak RSS; run one workload per process (--benchmark_filter) for a per-workload peak.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cstdlib>
#include <vector>

#include "core/matmul_precision.h"
#include "core/ops.h"
#include "core/parallel.h"
#include "core/storage_cache.h"
#include "nn/edge_net.h"
#include "nn/junction_net.h"
#include "nn/losses.h"
#include "nn/optimizer.h"

namespace lc2wf {
namespace {

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

struct Batch {
  Tensor x, mask, labels, offsets;
};

// Random patches like the real data: ~40% padded slots, slot 0 always valid.
Batch make_batch(int64_t B, int64_t G, int64_t N, int64_t F, int64_t classes, uint64_t seed) {
  Rng rng(seed);
  std::vector<float> x(static_cast<size_t>(B * G * N * F));
  for (auto& v : x) v = static_cast<float>(rng.next_uniform(-0.5, 0.5));
  std::vector<uint8_t> mask(static_cast<size_t>(B * G * N));
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = (i % N != 0) && rng.next_uniform() < 0.4;
  std::vector<int64_t> labels(static_cast<size_t>(B * G));
  for (auto& l : labels) l = static_cast<int64_t>(rng.next_below(classes));
  std::vector<float> offsets(static_cast<size_t>(B * G * 3));
  for (auto& v : offsets) v = static_cast<float>(rng.next_uniform(-0.1, 0.1));
  return {Tensor::from_vector(x, {B, G, N, F}), Tensor::from_mask(mask, {B, G, N}),
          Tensor::from_vector(labels, {B, G}), Tensor::from_vector(offsets, {B, G, 3})};
}

void finish(benchmark::State& state) { state.counters["peak_rss_MB"] = peak_rss_mb(); }

// CPU time and page faults of the measured steps only (the warm-up's first-touch faults excluded): the
// system share is what the storage cache exists to remove (issue target: <= 5% of a step).
class StepCost {
 public:
  StepCost() : cache_(storage_cache_stats()) { getrusage(RUSAGE_SELF, &start_); }
  void report(benchmark::State& state) const {
    rusage end{};
    getrusage(RUSAGE_SELF, &end);
    const double steps = static_cast<double>(state.iterations());
    auto seconds = [](const timeval& a, const timeval& b) {
      return static_cast<double>(b.tv_sec - a.tv_sec) + 1e-6 * static_cast<double>(b.tv_usec - a.tv_usec);
    };
    const double user = seconds(start_.ru_utime, end.ru_utime), sys = seconds(start_.ru_stime, end.ru_stime);
    state.counters["user_s_per_step"] = user / steps;
    state.counters["sys_s_per_step"] = sys / steps;
    state.counters["sys_share"] = sys / (user + sys);
    state.counters["faults_per_step"] = static_cast<double>(end.ru_minflt - start_.ru_minflt) / steps;
    const StorageCacheStats cache = storage_cache_stats();
    state.counters["cache_misses_per_step"] = static_cast<double>(cache.misses - cache_.misses) / steps;
    state.counters["cache_hits_per_step"] = static_cast<double>(cache.hits - cache_.hits) / steps;
    state.counters["fresh_MB_per_step"] = static_cast<double>(cache.fresh_bytes - cache_.fresh_bytes) / (1 << 20) / steps;
  }

 private:
  StorageCacheStats cache_;
  rusage start_{};
};

// Arg "fused" 0 runs attention on the reference kernel (the one before core/attention_fused.cpp), for a
// before/after of the training step from one build; run one variant per process for its peak RSS.
// Arg "bf16" 1 runs the matrix products with bf16 operands (core/matmul_precision.h; the AVX512-BF16 kernel
// where the CPU has it, else its emulation). Arg "recompute" 1 rebuilds the line MLP's activations in the
// backward pass (<stage>.recompute_mlp: less memory, more time).
struct AttentionKernel {
  explicit AttentionKernel(const benchmark::State& state)
      : before(fused_attention_enabled()),
        precision(state.range(1) != 0 ? MatmulPrecision::kBf16 : MatmulPrecision::kFp32) {
    set_fused_attention(state.range(0) != 0);
  }
  ~AttentionKernel() { set_fused_attention(before); }
  bool before;
  MatmulPrecisionGuard precision;
};

void BM_JunctionTrainStep(benchmark::State& state) {
  AttentionKernel kernel(state);
  JunctionNet net{JunctionNetConfig{}};
  net.set_recompute_mlp(state.range(2) != 0);
  AdamW opt(net.named_parameters(), OptimConfig{});
  const Batch b = make_batch(16, 256, 32, 7, 2, 1);
  JunctionLossConfig loss_config;
  loss_config.kind = "release";
  auto step = [&] {
    opt.zero_grad();
    const LossTerms loss = junction_loss(net.forward(b.x, b.mask), {b.labels, b.offsets}, loss_config);
    loss.total.backward();
    opt.step();
  };
  step();  // warm-up: first-touch allocations
  const StepCost cost;
  for (auto _ : state) step();
  cost.report(state);
  finish(state);
}

void BM_EdgeTrainStep(benchmark::State& state) {
  AttentionKernel kernel(state);
  EdgeNet net{EdgeNetConfig{}};
  net.set_recompute_mlp(state.range(2) != 0);
  AdamW opt(net.named_parameters(), OptimConfig{});
  const Batch b = make_batch(4, 512, 64, 6, 5, 2);
  auto step = [&] {
    opt.zero_grad();
    const Tensor loss = edge_loss(net.forward(b.x, b.mask), b.labels, EdgeLossConfig{});
    loss.backward();
    opt.step();
  };
  step();
  const StepCost cost;
  for (auto _ : state) step();
  cost.report(state);
  finish(state);
}

void BM_JunctionInference(benchmark::State& state) {
  const MatmulPrecisionGuard precision(state.range(0) ? MatmulPrecision::kBf16 : MatmulPrecision::kFp32);
  JunctionNet net{JunctionNetConfig{}};
  net.eval();
  const Batch b = make_batch(1, 256, 32, 7, 2, 3);
  NoGradGuard no_grad;
  net.forward(b.x, b.mask);
  for (auto _ : state) benchmark::DoNotOptimize(net.forward(b.x, b.mask).logits.data<float>());
  finish(state);
}

void BM_EdgeInference(benchmark::State& state) {
  const MatmulPrecisionGuard precision(state.range(0) ? MatmulPrecision::kBf16 : MatmulPrecision::kFp32);
  EdgeNet net{EdgeNetConfig{}};
  net.eval();
  const Batch b = make_batch(1, 435, 64, 6, 5, 4);
  NoGradGuard no_grad;
  net.forward(b.x, b.mask);
  for (auto _ : state) benchmark::DoNotOptimize(net.forward(b.x, b.mask).data<float>());
  finish(state);
}

BENCHMARK(BM_JunctionTrainStep)->ArgNames({"fused", "bf16", "recompute"})->Args({1, 0, 0})->Args({0, 0, 0})->Args({1, 1, 0})->Args({1, 1, 1})->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_EdgeTrainStep)->ArgNames({"fused", "bf16", "recompute"})->Args({1, 0, 0})->Args({0, 0, 0})->Args({1, 1, 0})->Args({1, 1, 1})->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_JunctionInference)->ArgName("bf16")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);
BENCHMARK(BM_EdgeInference)->ArgName("bf16")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);

}  // namespace
}  // namespace lc2wf

BENCHMARK_MAIN();

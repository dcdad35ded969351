// Core engine benchmarks at the LPT's hot shapes. Every case reports its arithmetic rate (GFLOP/s)
// or bandwidth (GB/s) and the fraction of the GEMM peak / memcpy bandwidth measured in the same run.
//   build-core/bench/core/lc2wf-core-bench [--benchmark_filter=...]   (threads: LC2WF_THREADS, default all)
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>

#include "core/gemm.h"
#include "core/matmul_precision.h"
#include "core/ops.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/storage_cache.h"

namespace {

using namespace lc2wf;

double g_peak_gflops = 0;  // sgemm 1024^3 through our GEMM path, median of 5
double g_memcpy_gbs = 0;   // threaded memcpy of 256 MiB (read + write bytes)

Tensor rand32(const Shape& s, uint64_t seed, bool grad = false) {
  Rng rng(seed);
  std::vector<float> v(static_cast<size_t>(shape_numel(s)));
  for (float& x : v) x = static_cast<float>(rng.next_uniform(-1, 1));
  Tensor t = Tensor::from_vector(v, s);
  if (grad) t.set_requires_grad();
  return t;
}

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

template <class F>
double median_seconds(int reps, F f) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

void sgemm_1024(const std::vector<float>& a, const std::vector<float>& b, std::vector<float>& c) {
  gemm<float>(false, false, 1024, 1024, 1024, a.data(), 1024, b.data(), 1024, c.data(), 1024, false);
}

void threaded_copy(const char* src, char* dst, int64_t bytes) {
  constexpr int64_t kChunk = 1 << 22;
  parallel_for(bytes, kChunk, [&](int64_t b, int64_t e) { std::memcpy(dst + b, src + b, e - b); });
}

void measure_anchors() {
  std::vector<float> a(1 << 20, 1.0f), b(1 << 20, 0.5f), c(1 << 20);
  sgemm_1024(a, b, c);
  g_peak_gflops = 2.0 * 1024 * 1024 * 1024 / median_seconds(5, [&] { sgemm_1024(a, b, c); }) / 1e9;
  int64_t bytes = int64_t{256} << 20;
  std::vector<char> src(bytes, 1), dst(bytes, 0);
  threaded_copy(src.data(), dst.data(), bytes);
  g_memcpy_gbs = 2.0 * bytes / median_seconds(5, [&] { threaded_copy(src.data(), dst.data(), bytes); }) / 1e9;
}

void report_flops(benchmark::State& state, double flops_per_iter) {
  double it = static_cast<double>(state.iterations());
  state.counters["GFLOP/s"] = benchmark::Counter(flops_per_iter * it / 1e9, benchmark::Counter::kIsRate);
  state.counters["frac_peak"] = benchmark::Counter(flops_per_iter * it / 1e9 / g_peak_gflops, benchmark::Counter::kIsRate);
}

void report_bytes(benchmark::State& state, double bytes_per_iter) {
  double it = static_cast<double>(state.iterations());
  state.counters["GB/s"] = benchmark::Counter(bytes_per_iter * it / 1e9, benchmark::Counter::kIsRate);
  state.counters["frac_memcpy"] = benchmark::Counter(bytes_per_iter * it / 1e9 / g_memcpy_gbs, benchmark::Counter::kIsRate);
}

// ---------------------------------------------------------------- anchors
void BM_GemmPeak_1024(benchmark::State& state) {
  std::vector<float> a(1 << 20, 1.0f), b(1 << 20, 0.5f), c(1 << 20);
  for (auto _ : state) {
    sgemm_1024(a, b, c);
    benchmark::DoNotOptimize(c.data());
  }
  report_flops(state, 2.0 * 1024 * 1024 * 1024);
}
BENCHMARK(BM_GemmPeak_1024)->UseRealTime()->Unit(benchmark::kMillisecond);

// The same product with bf16 operands (the AVX512-BF16 kernel where the CPU has it): frac_peak above 1 is
// its gain over the fp32 anchor.
void BM_GemmPeak_1024_Bf16(benchmark::State& state) {
  const MatmulPrecisionGuard bf16(MatmulPrecision::kBf16);
  std::vector<float> a(1 << 20, 1.0f), b(1 << 20, 0.5f), c(1 << 20);
  for (auto _ : state) {
    sgemm_1024(a, b, c);
    benchmark::DoNotOptimize(c.data());
  }
  report_flops(state, 2.0 * 1024 * 1024 * 1024);
  state.counters["bf16_instruction"] = cpu_has_bf16_dot_product();
}
BENCHMARK(BM_GemmPeak_1024_Bf16)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_Memcpy_256MiB(benchmark::State& state) {
  int64_t bytes = int64_t{256} << 20;
  std::vector<char> src(bytes, 1), dst(bytes, 0);
  for (auto _ : state) {
    threaded_copy(src.data(), dst.data(), bytes);
    benchmark::DoNotOptimize(dst.data());
  }
  report_bytes(state, 2.0 * bytes);
}
BENCHMARK(BM_Memcpy_256MiB)->UseRealTime()->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- linear 8192x256 -> 256
constexpr int64_t kTokens = 8192, kWidth = 256;

// Arg "bf16" 1: bf16 GEMM operands (the AVX512-BF16 kernel where the CPU has it).
void BM_LinearForward(benchmark::State& state) {
  const MatmulPrecisionGuard precision(state.range(0) ? MatmulPrecision::kBf16 : MatmulPrecision::kFp32);
  Tensor x = rand32({kTokens, kWidth}, 1), w = rand32({kWidth, kWidth}, 2), b = rand32({kWidth}, 3);
  NoGradGuard no_grad;
  for (auto _ : state) benchmark::DoNotOptimize(linear(x, w, b).impl());
  report_flops(state, 2.0 * kTokens * kWidth * kWidth);
}
BENCHMARK(BM_LinearForward)->ArgName("bf16")->Arg(0)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_LinearForwardBackward(benchmark::State& state) {
  const MatmulPrecisionGuard precision(state.range(0) ? MatmulPrecision::kBf16 : MatmulPrecision::kFp32);
  Tensor x = rand32({kTokens, kWidth}, 1, true), w = rand32({kWidth, kWidth}, 2, true), b = rand32({kWidth}, 3, true);
  Tensor seed = rand32({kTokens, kWidth}, 4);
  for (auto _ : state) {
    linear(x, w, b).backward(seed);
    x.zero_grad();
    w.zero_grad();
    b.zero_grad();
  }
  report_flops(state, 3 * 2.0 * kTokens * kWidth * kWidth);
}
BENCHMARK(BM_LinearForwardBackward)->ArgName("bf16")->Arg(0)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);

// The LPT's first MLP layer: 7 line features -> 64 over B*G*N = 16384 lines (tiny K).
void BM_LinearSmallKForward(benchmark::State& state) {
  Tensor x = rand32({16384, 7}, 1), w = rand32({64, 7}, 2), b = rand32({64}, 3);
  NoGradGuard no_grad;
  for (auto _ : state) benchmark::DoNotOptimize(linear(x, w, b).impl());
  report_flops(state, 2.0 * 16384 * 7 * 64);
}
BENCHMARK(BM_LinearSmallKForward)->UseRealTime()->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- attention: 8192 tokens, patches of L
// FLOPs: Q.K^T and P.V, 2 * L * L * Dh multiply-adds each per (patch, head); backward does 4 such products.
double attention_flops(int64_t patches, int64_t L) { return 4.0 * patches * L * L * kWidth; }

void BM_AttentionForward(benchmark::State& state) {
  int64_t L = state.range(0), B = kTokens / L;
  Tensor qkv = rand32({B, L, 3 * kWidth}, 5);
  Rng rng(1);
  NoGradGuard no_grad;
  for (auto _ : state) benchmark::DoNotOptimize(packed_attention(qkv, 8, Tensor(), 0.1, true, rng).impl());
  report_flops(state, attention_flops(B, L));
}
BENCHMARK(BM_AttentionForward)->Arg(32)->Arg(64)->UseRealTime()->Unit(benchmark::kMillisecond);

// Inference of the edge model's patch encoder: one building's pair patches attend to each other, L = the
// pairs scored (2,545 on average in base.json's validation), no mask, no dropout.
void BM_AttentionOverPairs(benchmark::State& state) {
  const int64_t L = state.range(0);
  Tensor qkv = rand32({1, L, 3 * kWidth}, 5);
  Rng rng(1);
  NoGradGuard no_grad;
  for (auto _ : state) benchmark::DoNotOptimize(packed_attention(qkv, 8, Tensor(), 0.0, false, rng).impl());
  report_flops(state, attention_flops(1, L));
}
BENCHMARK(BM_AttentionOverPairs)->Arg(435)->Arg(2545)->ArgName("pairs")->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_AttentionForwardBackward(benchmark::State& state) {
  int64_t L = state.range(0), B = kTokens / L;
  Tensor qkv = rand32({B, L, 3 * kWidth}, 5, true);
  Tensor seed = rand32({B, L, kWidth}, 6);
  Rng rng(1);
  for (auto _ : state) {
    packed_attention(qkv, 8, Tensor(), 0.1, true, rng).backward(seed);
    qkv.zero_grad();
  }
  report_flops(state, 3 * attention_flops(B, L));
}
BENCHMARK(BM_AttentionForwardBackward)->Arg(32)->Arg(64)->UseRealTime()->Unit(benchmark::kMillisecond);

// Attention fwd+bwd against the Linear fwd+bwd above, alternated within every iteration, so both see the
// same load: ratio = attention GFLOP/s / linear GFLOP/s, the ratio_cpu counter the same in thread CPU time
// (meaningful with LC2WF_THREADS=1). fused = 0 runs the reference kernel (the one before the fused
// kernel) for a before/after in one process. Dropout 0.5 and a key mask of a quarter of the keys in
// every other patch, as in training. tokens = 1024 keeps qkv (3 MiB) in the caches, 8192 streams it.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void BM_AttentionOverLinear(benchmark::State& state) {
  const int64_t L = state.range(0), B = state.range(2) / L;
  const bool was_fused = fused_attention_enabled();
  set_fused_attention(state.range(1) != 0);
  Tensor qkv = rand32({B, L, 3 * kWidth}, 5, true), seed = rand32({B, L, kWidth}, 6);
  std::vector<uint8_t> m(static_cast<size_t>(B * L), 0);
  for (int64_t b = 0; b < B; b += 2)
    for (int64_t j = L - L / 4; j < L; ++j) m[static_cast<size_t>(b * L + j)] = 1;
  Tensor mask = Tensor::from_mask(m, {B, L});
  Tensor x = rand32({kTokens, kWidth}, 1, true), w = rand32({kWidth, kWidth}, 2, true), bias = rand32({kWidth}, 3, true);
  Tensor lseed = rand32({kTokens, kWidth}, 4);
  Rng rng(1);
  double attn_wall = 0, lin_wall = 0, attn_cpu = 0, lin_cpu = 0;
  const StorageCacheStats cache_before = storage_cache_stats();
  const long faults_before = minor_faults();
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    double c0 = thread_cpu_seconds();
    packed_attention(qkv, 8, mask, 0.5, true, rng).backward(seed);
    qkv.zero_grad();
    auto t1 = std::chrono::steady_clock::now();
    double c1 = thread_cpu_seconds();
    linear(x, w, bias).backward(lseed);
    x.zero_grad();
    w.zero_grad();
    bias.zero_grad();
    auto t2 = std::chrono::steady_clock::now();
    double c2 = thread_cpu_seconds();
    attn_wall += std::chrono::duration<double>(t1 - t0).count();
    lin_wall += std::chrono::duration<double>(t2 - t1).count();
    attn_cpu += c1 - c0;
    lin_cpu += c2 - c1;
  }
  set_fused_attention(was_fused);
  const double n = static_cast<double>(state.iterations());
  const double attn_flops = 3 * attention_flops(B, L), lin_flops = 3 * 2.0 * kTokens * kWidth * kWidth;
  state.counters["attn_ms"] = 1e3 * attn_wall / n;
  state.counters["attn_GFLOP/s"] = attn_flops * n / attn_wall / 1e9;
  state.counters["linear_GFLOP/s"] = lin_flops * n / lin_wall / 1e9;
  state.counters["ratio"] = (attn_flops / attn_wall) / (lin_flops / lin_wall);
  state.counters["ratio_cpu"] = (attn_flops / attn_cpu) / (lin_flops / lin_cpu);
  // Fresh pages are the allocator's cost, not the kernels': a training step in steady state maps none.
  const StorageCacheStats cache_after = storage_cache_stats();
  state.counters["misses_per_iter"] = static_cast<double>(cache_after.misses - cache_before.misses) / n;
  state.counters["fresh_MB_per_iter"] = static_cast<double>(cache_after.fresh_bytes - cache_before.fresh_bytes) / n / 1e6;
  state.counters["faults_per_iter"] = static_cast<double>(minor_faults() - faults_before) / n;
}
BENCHMARK(BM_AttentionOverLinear)
    ->ArgsProduct({{32, 64}, {0, 1}, {kTokens, 1024}})
    ->ArgNames({"L", "fused", "tokens"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- normalisation over 8192x256
// Bytes: the minimal traffic (forward reads x, writes y; backward reads x and g, writes dx).
constexpr double kActBytes = 4.0 * kTokens * kWidth;

void BM_BatchNormForward(benchmark::State& state) {
  Tensor x = rand32({kTokens, kWidth}, 7), w = rand32({kWidth}, 8), b = rand32({kWidth}, 9);
  Tensor rm = Tensor::zeros({kWidth}), rv = Tensor::ones({kWidth});
  NoGradGuard no_grad;
  for (auto _ : state) benchmark::DoNotOptimize(batch_norm(x, w, b, rm, rv, true).impl());
  report_bytes(state, 2 * kActBytes);
}
BENCHMARK(BM_BatchNormForward)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_BatchNormForwardBackward(benchmark::State& state) {
  Tensor x = rand32({kTokens, kWidth}, 7, true), w = rand32({kWidth}, 8, true), b = rand32({kWidth}, 9, true);
  Tensor rm = Tensor::zeros({kWidth}), rv = Tensor::ones({kWidth}), seed = rand32({kTokens, kWidth}, 10);
  for (auto _ : state) {
    batch_norm(x, w, b, rm, rv, true).backward(seed);
    x.zero_grad();
    w.zero_grad();
    b.zero_grad();
  }
  report_bytes(state, 5 * kActBytes);
}
BENCHMARK(BM_BatchNormForwardBackward)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_LayerNormForward(benchmark::State& state) {
  Tensor x = rand32({kTokens, kWidth}, 7), w = rand32({kWidth}, 8), b = rand32({kWidth}, 9);
  NoGradGuard no_grad;
  for (auto _ : state) benchmark::DoNotOptimize(layer_norm(x, w, b).impl());
  report_bytes(state, 2 * kActBytes);
}
BENCHMARK(BM_LayerNormForward)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_LayerNormForwardBackward(benchmark::State& state) {
  Tensor x = rand32({kTokens, kWidth}, 7, true), w = rand32({kWidth}, 8, true), b = rand32({kWidth}, 9, true);
  Tensor seed = rand32({kTokens, kWidth}, 10);
  for (auto _ : state) {
    layer_norm(x, w, b).backward(seed);
    x.zero_grad();
    w.zero_grad();
    b.zero_grad();
  }
  report_bytes(state, 5 * kActBytes);
}
BENCHMARK(BM_LayerNormForwardBackward)->UseRealTime()->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- softmax over (256*8, 32, 32)
void BM_SoftmaxForward(benchmark::State& state) {
  Tensor s = rand32({256 * 8, 32, 32}, 11);
  NoGradGuard no_grad;
  for (auto _ : state) benchmark::DoNotOptimize(softmax(s, -1).impl());
  report_bytes(state, 2.0 * 4 * s.numel());
}
BENCHMARK(BM_SoftmaxForward)->UseRealTime()->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- elementwise reference points
void BM_ReluForward(benchmark::State& state) {
  Tensor x = rand32({kTokens, kWidth}, 12);
  NoGradGuard no_grad;
  for (auto _ : state) benchmark::DoNotOptimize(relu(x).impl());
  report_bytes(state, 2 * kActBytes);
}
BENCHMARK(BM_ReluForward)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_DropoutForward(benchmark::State& state) {
  Tensor x = rand32({kTokens, kWidth}, 13);
  Rng rng(2);
  NoGradGuard no_grad;
  for (auto _ : state) benchmark::DoNotOptimize(dropout(x, 0.1, true, rng).impl());
  report_bytes(state, 2 * kActBytes);
}
BENCHMARK(BM_DropoutForward)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  if (const char* t = std::getenv("LC2WF_THREADS")) set_num_threads(std::atoi(t));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  measure_anchors();
  benchmark::AddCustomContext("threads", std::to_string(num_threads()));
  benchmark::AddCustomContext("gemm_peak_gflops", std::to_string(g_peak_gflops));
  benchmark::AddCustomContext("memcpy_gbs", std::to_string(g_memcpy_gbs));
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

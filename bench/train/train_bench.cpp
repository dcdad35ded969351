// Training throughput per stage and inference time per building at the paper's network sizes
// (configs/base.json: width 256, G 256 x N 32 junction patches, 512 x 64 pair patches), on synthetic
// buildings, through the same code lc2wf-train and lc2wf-infer run (sampling, patches, forward,
// backward, AdamW step; inference incl. post-processing). Counters: buildings/s for training, seconds
// per building for inference. Threads: LC2WF_THREADS (default 2).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <vector>

#include "core/parallel.h"
#include "dataset/sampling/network_input.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "model/inference.h"
#include "model/patch_tensors.h"
#include "nn/losses.h"
#include "nn/optimizer.h"

namespace lc2wf {
namespace {

void init_threads() {
  const char* t = std::getenv("LC2WF_THREADS");
  set_num_threads(t ? std::atoi(t) : 2);
}

const std::vector<LineCloud>& clouds() {
  static const std::vector<LineCloud> c = [] {
    std::vector<LineCloud> out;
    for (int i = 0; i < 32; ++i) {
      LineCloud cloud = make_synthetic_line_cloud(make_random_building(100 + i, "b" + std::to_string(i)), 200 + i);
      out.push_back(std::move(cloud));
    }
    return out;
  }();
  return c;
}

// A plausible hand-off: GT junctions jittered by 5 cm, plus false candidates on random endpoints.
PredictedJunctions fake_predictions(const LineCloud& cloud, uint64_t seed) {
  PredictedJunctions p;
  Rng rng(seed);
  for (const Vec3& j : cloud.wireframe.junctions) {
    p.positions.push_back(j + 0.05 * Vec3(rng.next_normal(), rng.next_normal(), rng.next_normal()));
    p.confidence.push_back(0.9 + 0.09 * rng.next_uniform());
  }
  for (int k = 0; k < 40; ++k) {
    const Segment3& s = cloud.segments[rng.next_below(cloud.segments.size())];
    p.positions.push_back(s.a);
    p.confidence.push_back(0.5 * rng.next_uniform());
  }
  p.offset_m.assign(p.positions.size(), 0.0);  // every candidate passes the offset screen, as before it existed
  return p;
}

void BM_JunctionTrainStep(benchmark::State& state) {
  init_threads();
  const int B = static_cast<int>(state.range(0));
  JunctionNetConfig config;
  JunctionNet net(config, 1555);
  auto opt = make_optimizer(net, OptimConfig{});
  JunctionSampleOptions so = junction_sample_options(config);
  so.augment_enabled = true;
  JunctionLossConfig loss_config;
  loss_config.kind = "release";
  uint64_t step = 0;
  for (auto _ : state) {
    std::vector<JunctionPatches> parts;
    for (int b = 0; b < B; ++b) parts.push_back(make_junction_sample(clouds()[(step * B + b) % clouds().size()], so, step * 100 + b));
    const JunctionPatches p = stack(parts);
    const PatchInput in = junction_input(p);
    const LossTerms loss = junction_loss(net.forward(in.x, in.mask), junction_targets(p), loss_config);
    loss.total.backward();
    opt->step();
    opt->zero_grad();
    ++step;
  }
  state.counters["buildings_per_s"] = benchmark::Counter(static_cast<double>(B), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_JunctionTrainStep)->Arg(4)->Arg(16)->Unit(benchmark::kSecond)->Iterations(3)->UseRealTime();

void BM_EdgeTrainStep(benchmark::State& state) {
  init_threads();
  const int B = static_cast<int>(state.range(0));
  EdgeNetConfig config;
  EdgeNet net(config, 1555);
  auto opt = make_optimizer(net, OptimConfig{});
  PairSampleOptions so;
  so.patch = pair_patch_options(config);
  so.augment_enabled = true;
  std::vector<JunctionSelection> selected;
  for (size_t k = 0; k < clouds().size(); ++k)
    selected.push_back(select_junctions(fake_predictions(clouds()[k], k), clouds()[k].segments, {}, SelectionCut::kTopK));
  uint64_t step = 0;
  for (auto _ : state) {
    std::vector<PairPatches> parts;
    for (int b = 0; b < B; ++b) {
      const size_t k = (step * B + b) % clouds().size();
      parts.push_back(make_pair_training_sample(clouds()[k], selected[k], so, step * 100 + b));
    }
    const PairPatches p = stack(parts);
    const PatchInput in = pair_input(p);
    edge_loss(net.forward(in.x, in.mask), pair_labels(p), EdgeLossConfig{}).backward();
    opt->step();
    opt->zero_grad();
    ++step;
  }
  state.counters["buildings_per_s"] = benchmark::Counter(static_cast<double>(B), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_EdgeTrainStep)->Arg(2)->Arg(4)->Unit(benchmark::kSecond)->Iterations(3)->UseRealTime();

// Whole inference of one building: sampling + junction model, then (with the hand-off stand-in above, so
// the pair count is realistic for random weights) selection, C(n,2) pairs through the edge model and
// post-processing. Reports the mean number of pairs.
void BM_InferBuilding(benchmark::State& state) {
  init_threads();
  JunctionNet junction(JunctionNetConfig{}, 1555);
  EdgeNet edge(EdgeNetConfig{}, 1555);
  const PostProcessOptions post;
  size_t k = 0;
  double pairs = 0;
  for (auto _ : state) {
    const LineCloud& cloud = clouds()[k % clouds().size()];
    benchmark::DoNotOptimize(predict_junction_candidates(junction, cloud, post.selection));
    const InferenceResult r = predict_wireframe(edge, cloud, fake_predictions(cloud, k), post);
    const double n = static_cast<double>(r.selection.positions.size());
    pairs += n * (n - 1) / 2;
    ++k;
  }
  state.counters["pairs"] = pairs / static_cast<double>(k);
  state.counters["s_per_building"] = benchmark::Counter(static_cast<double>(k), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_InferBuilding)->Unit(benchmark::kMillisecond)->Iterations(16)->UseRealTime();

}  // namespace
}  // namespace lc2wf

BENCHMARK_MAIN();

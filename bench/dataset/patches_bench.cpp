// Patch building for one building: 1,500 segments, 256 junction patches and 512 pair patches, one core.
#include <benchmark/benchmark.h>

#include "dataset/sampling/pair_sampling.h"
#include "dataset/sampling/patches.h"
#include "dataset/sampling/network_input.h"
#include "dataset/sampling/sampling.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"

namespace lc2wf {
namespace {

constexpr size_t kSegments = 1500;

// An L-shaped building with a paper-sized cloud (cut to exactly kSegments, the paper's ~1.4K average).
const LineCloud& cloud() {
  static const LineCloud c = [] {
    const Building b = make_l_building("bench", LBuildingSpec{});
    SyntheticCloudOptions o;
    o.edge_pieces_per_metre = 4.0;
    o.texture_per_roof_m2 = 4.0;
    o.max_support_views = 0;
    const LineCloud full = make_synthetic_line_cloud(b, 1, o);  // ~1.8K segments
    if (full.segments.size() < kSegments) std::abort();
    // Evenly spaced subset keeps the mix of edge pieces, texture and clutter.
    LineCloud lc = full;
    lc.segments.clear();
    lc.labels.clear();
    lc.support.clear();
    for (size_t k = 0; k < kSegments; ++k) {
      const size_t i = k * full.segments.size() / kSegments;
      lc.segments.push_back(full.segments[i]);
      lc.labels.push_back(full.labels[i]);
    }
    return lc;
  }();
  return c;
}

PredictedJunctions predictions() {
  PredictedJunctions p;
  const auto& J = cloud().wireframe.junctions;
  for (int k = 0; k < 40; ++k) {
    p.positions.push_back(J[k % J.size()] + Vec3(0.03 * (k / J.size()), 0.01 * k, 0));
    p.confidence.push_back(1.0 - 0.01 * k);
  }
  p.offset_m.assign(p.positions.size(), 0.0);  // every candidate passes the offset screen
  return p;
}

void BM_Sampling(benchmark::State& state) {
  const auto ends = segment_endpoints(cloud().segments);
  for (auto _ : state) benchmark::DoNotOptimize(sample_endpoints(ends, SamplingOptions{}));
}
BENCHMARK(BM_Sampling)->Unit(benchmark::kMillisecond);

void BM_DensitySeeds(benchmark::State& state) {
  const auto ends = segment_endpoints(cloud().segments);
  for (auto _ : state) benchmark::DoNotOptimize(density_seeds(ends, SamplingOptions{}));
  state.counters["seeds"] = static_cast<double>(density_seeds(ends, SamplingOptions{}).size());
}
BENCHMARK(BM_DensitySeeds)->Unit(benchmark::kMillisecond);

void BM_JunctionPatches256(benchmark::State& state) {
  const auto ends = segment_endpoints(cloud().segments);
  const auto samples = sample_endpoints(ends, SamplingOptions{});
  const auto labels = endpoint_labels(cloud());
  for (auto _ : state) {
    const SegmentSet set(cloud().segments);
    benchmark::DoNotOptimize(build_junction_patches(set, labels, cloud().wireframe.junctions, samples, PatchOptions{}));
  }
}
BENCHMARK(BM_JunctionPatches256)->Unit(benchmark::kMillisecond);

void BM_JunctionSampleWithAugmentation(benchmark::State& state) {
  JunctionSampleOptions o;
  o.augment_enabled = true;
  uint64_t seed = 0;
  for (auto _ : state) benchmark::DoNotOptimize(make_junction_sample(cloud(), o, ++seed));
}
BENCHMARK(BM_JunctionSampleWithAugmentation)->Unit(benchmark::kMillisecond);

void BM_PairPatches512(benchmark::State& state) {
  const auto selected = select_junctions(predictions(), cloud().segments, {}, SelectionCut::kTopK);
  const auto pairs = sample_training_pairs(cloud().wireframe, selected, PairSamplingOptions{});
  for (auto _ : state) {
    const SegmentSet set(cloud().segments);
    benchmark::DoNotOptimize(build_pair_patches(set, pairs, PatchOptions{}));
  }
  state.counters["pairs"] = static_cast<double>(pairs.size());
}
BENCHMARK(BM_PairPatches512)->Unit(benchmark::kMillisecond);

void BM_PairTrainingSampleWithAugmentation(benchmark::State& state) {
  PairSampleOptions o;
  o.augment_enabled = true;
  const auto selected = select_junctions(predictions(), cloud().segments, {}, SelectionCut::kTopK);
  uint64_t seed = 0;
  for (auto _ : state) benchmark::DoNotOptimize(make_pair_training_sample(cloud(), selected, o, ++seed));
}
BENCHMARK(BM_PairTrainingSampleWithAugmentation)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lc2wf

BENCHMARK_MAIN();

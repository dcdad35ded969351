// Post-processing and metrics on one building of 40 junctions (C(40,2) = 780 classified pairs), the
// per-building work that follows the two networks at inference time.
#include <benchmark/benchmark.h>

#include <random>

#include "model/evaluator.h"
#include "model/post_process.h"

namespace lc2wf {
namespace {

// A 5 x 4 x 2 lattice (3 m spacing, 40 junctions) with edges between lattice neighbours (82 edges).
Wireframe lattice() {
  Wireframe w;
  auto id = [](int x, int y, int z) { return (z * 4 + y) * 5 + x; };
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x) w.junctions.push_back({3.0 * x, 3.0 * y, 3.75 * z});
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x) {
        if (x + 1 < 5) w.edges.push_back({id(x, y, z), id(x + 1, y, z)});
        if (y + 1 < 4) w.edges.push_back({id(x, y, z), id(x, y + 1, z)});
        if (z == 0) w.edges.push_back({id(x, y, 0), id(x, y, 1)});
      }
  return w;
}

// 256 junction candidates (the junction model's patches): noisy copies of the GT junctions plus clutter.
void candidates(const Wireframe& gt, std::vector<Vec3>& pts, std::vector<double>& conf) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 256; ++k) {
    const bool clutter = k >= 200;
    const Vec3 base = clutter ? Vec3(12 * u(rng), 9 * u(rng), 3.75 * u(rng)) : gt.junctions[k % gt.junctions.size()];
    pts.push_back(base + Vec3(noise(rng), noise(rng), noise(rng)));
    conf.push_back(clutter ? 0.5 * u(rng) : 0.86 + 0.14 * u(rng));
  }
}

// Edge-model output for every pair of the 40 GT junctions: high P(connected) on GT edges, a few
// near-identical pairs, low probabilities elsewhere.
PostProcessInput edge_stage_output(const Wireframe& gt) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PostProcessInput in;
  std::normal_distribution<double> noise(0.0, 0.05);
  for (const Vec3& p : gt.junctions) in.junctions.push_back(p + Vec3(noise(rng), noise(rng), noise(rng)));
  for (size_t k = 0; k < gt.junctions.size(); ++k) in.confidences.push_back(0.86 + 0.14 * u(rng));
  std::vector<std::vector<char>> adj(gt.junctions.size(), std::vector<char>(gt.junctions.size(), 0));
  for (const auto& [a, b] : gt.edges) adj[a][b] = adj[b][a] = 1;
  for (const auto& [i, j] : all_pairs(static_cast<int>(gt.junctions.size()))) {
    const double connect = adj[i][j] ? 0.6 + 0.4 * u(rng) : 0.31 * u(rng);  // ~3 % false candidates
    in.pairs.push_back({i, j, u(rng) < 0.01 ? 0.5 : 0.05 * u(rng), connect});
  }
  return in;
}

void BM_SelectJunctions(benchmark::State& state) {
  const Wireframe gt = lattice();
  PredictedJunctions c;
  candidates(gt, c.positions, c.confidence);
  c.offset_m.assign(c.positions.size(), 0.0);  // every candidate passes the offset screen
  PostProcessOptions o = state.range(0) ? PostProcessOptions::release_quirks() : PostProcessOptions{};
  for (auto _ : state) benchmark::DoNotOptimize(select_junctions(c, {}, o.selection));
}
BENCHMARK(BM_SelectJunctions)->Arg(0)->Arg(1)->ArgName("release");

void BM_PostProcess40(benchmark::State& state) {
  const PostProcessInput in = edge_stage_output(lattice());
  PostProcessOptions o = state.range(0) ? PostProcessOptions::release_quirks() : PostProcessOptions{};
  size_t edges = 0;
  for (auto _ : state) {
    const PostProcessResult r = post_process(in, o);
    edges = r.wireframe.wireframe.edges.size();
    benchmark::DoNotOptimize(edges);
  }
  state.counters["final_edges"] = static_cast<double>(edges);
  state.counters["pairs"] = static_cast<double>(in.pairs.size());
}
BENCHMARK(BM_PostProcess40)->Arg(0)->Arg(1)->ArgName("release");

void BM_EvaluateBuilding(benchmark::State& state) {
  const Wireframe gt = lattice();
  const PostProcessResult r = post_process(edge_stage_output(gt), PostProcessOptions{});
  EvalOptions o;
  o.strict_wed = true;
  for (auto _ : state) {
    Evaluator ev(o);
    ev.add("b", r.wireframe, gt);
    benchmark::DoNotOptimize(ev.report());
  }
}
BENCHMARK(BM_EvaluateBuilding);

// Report over a 757-building split (the paper's test set size) once the per-building matching is done.
void BM_Report757(benchmark::State& state) {
  const Wireframe gt = lattice();
  const PostProcessResult r = post_process(edge_stage_output(gt), PostProcessOptions{});
  Evaluator ev(EvalOptions{});
  for (int b = 0; b < 757; ++b) ev.add("b" + std::to_string(b), r.wireframe, gt);
  for (auto _ : state) benchmark::DoNotOptimize(ev.report());
}
BENCHMARK(BM_Report757);

}  // namespace
}  // namespace lc2wf

BENCHMARK_MAIN();

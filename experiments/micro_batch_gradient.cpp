// How far the edge stage's micro-batches move a step's gradient from the whole batch's, next to the
// noise training already has. At the paper's shapes (configs/base.json), on real buildings of the train
// split, with junctions predicted by a junction model and selected as the edge stage does, it trains
// the edge model with the config's micro-batches and, at the chosen steps, takes one batch's gradient
// four ways from the same weights: micro-batched and whole (same dropout masks: only BatchNorm's
// statistics differ), whole with other dropout masks (dropout noise) and whole on the next batch
// (sampling noise). With --bf16 it also takes the micro-batched gradient with bf16 GEMM operands
// (core/matmul_precision.h) next to other dropout masks at the same passes; --no-whole skips the three
// whole-batch passes (≈ 14 GB at the paper's batch). Writes a JSON report; train/README.md ("How far
// micro-batches move the gradient") has runs.
//   micro_batch_gradient CONFIG --junction-weights FILE [--buildings 96] [--measure-at 0,8] [--bf16] [--no-whole] [-o OUT.json]
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/matmul_precision.h"
#include "core/parallel.h"
#include "core/util/atomic_file.h"
#include "dataset/splits/splits.h"
#include "model/inference.h"
#include "nn/optimizer.h"
#include "train/building_set.h"
#include "train/communicator.h"
#include "train/edge_step.h"
#include "train/train_config.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

struct Options {
  fs::path config, junction_weights, out = "micro_batch_gradient.json";
  int64_t buildings = 96;
  std::set<int64_t> measure_at{0, 8};
  bool bf16 = false, whole = true;
};

std::set<int64_t> parse_steps(const std::string& text) {
  std::set<int64_t> steps;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) steps.insert(std::stoll(item));
  return steps;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(f + " needs a value");
      return argv[++i];
    };
    if (f == "--junction-weights") o.junction_weights = value();
    else if (f == "--buildings") o.buildings = std::stoll(value());
    else if (f == "--measure-at") o.measure_at = parse_steps(value());
    else if (f == "--bf16") o.bf16 = true;
    else if (f == "--no-whole") o.whole = false;
    else if (f == "-o" || f == "--out") o.out = value();
    else if (!f.empty() && f[0] != '-' && o.config.empty()) o.config = f;
    else throw std::invalid_argument("unknown argument '" + f + "'");
  }
  if (o.config.empty() || o.junction_weights.empty())
    throw std::invalid_argument("usage: micro_batch_gradient CONFIG --junction-weights FILE [--buildings N] [--measure-at 0,8] [--bf16] [--no-whole] [-o OUT.json]");
  return o;
}

// The parameters' gradients, concatenated (a parameter no pass reached counts as zeros).
std::vector<double> gradient(const Module& net) {
  std::vector<double> g;
  for (const auto& [name, p] : net.named_parameters()) {
    const Tensor d = p.grad();
    if (!d.defined()) {
      g.insert(g.end(), static_cast<size_t>(p.numel()), 0.0);
      continue;
    }
    const std::vector<double> v = d.to_vector();
    g.insert(g.end(), v.begin(), v.end());
  }
  return g;
}

struct Comparison {
  double cosine = 0.0, relative_difference = 0.0;
};

// cos(a, b) and |a - b| / |b|.
Comparison compare(const std::vector<double>& a, const std::vector<double>& b) {
  double ab = 0.0, aa = 0.0, bb = 0.0, dd = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    ab += a[i] * b[i], aa += a[i] * a[i], bb += b[i] * b[i];
    dd += (a[i] - b[i]) * (a[i] - b[i]);
  }
  return {ab / std::sqrt(aa * bb), std::sqrt(dd / bb)};
}

// Another dropout stream for the noise reference.
constexpr uint64_t kOtherMasks = 0x9e3779b97f4a7c15ull;

nlohmann::json to_json(const Comparison& c) { return {{"cosine", c.cosine}, {"relative_difference", c.relative_difference}}; }

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

int run(const Options& o) {
  const TrainConfig config = TrainConfig::from_file(o.config);
  const EdgeStageConfig& c = config.edge;
  set_num_threads(static_cast<int>(config.threads));

  // The first N buildings of the train split.
  const std::vector<std::string> names = read_name_list(config.data.train_split);
  if (static_cast<int64_t>(names.size()) < o.buildings) throw std::invalid_argument("--buildings exceeds the train split");
  const fs::path split = o.out.string() + ".split.txt";
  {
    std::ofstream f(split);
    for (int64_t k = 0; k < o.buildings; ++k) f << names[static_cast<size_t>(k)] << '\n';
  }
  const BuildingSet train = load_building_set(config.data, split, "data.train_split", true);
  fs::remove(split);

  // The hand-off and the edge stage's junction selection, as lc2wf-train makes them.
  const auto junction_net = load_junction_net(o.junction_weights);
  std::vector<const LineCloud*> clouds;
  std::vector<JunctionSelection> selected;
  for (const LineCloud& cloud : train.clouds) {
    if (cloud.wireframe.junctions.size() < 2) continue;
    clouds.push_back(&cloud);
    selected.push_back(select_junctions(predict_junction_candidates(*junction_net, cloud, edge_training_selection(c)), cloud.segments,
                                        edge_training_selection(c), SelectionCut::kTopK));
  }
  const PairSampleOptions sampling = edge_training_sample_options(c);
  PatchStream<PairPatches> stream(
      clouds.size(), [&](size_t b, uint64_t seed) { return make_pair_training_sample(*clouds[b], selected[b], sampling, seed); },
      PatchStreamOptions::of_stage(c.schedule, config.loader_workers, config.seed + 2));

  EdgeNet net(c.net, config.seed);
  auto optimizer = make_optimizer(net, c.optim);
  LocalCommunicator comm;
  DataParallel dp(comm, net, net.dropout_rng(), false);
  Rng& dropout = net.dropout_rng();
  const int64_t micro = c.schedule.micro_batch;
  // One batch's gradient from the current weights, starting the dropout stream at (seed, counter).
  auto batch_gradient = [&](const StreamBatch<PairPatches>& b, int64_t passes_micro, uint64_t seed, uint64_t counter,
                            double& loss) {
    optimizer->zero_grad();
    dropout.set_state(seed, counter);
    loss = edge_step_passes(net, dp, b, passes_micro, c.loss).loss;
    return gradient(net);
  };

  nlohmann::json report = {{"config", o.config.string()},
                           {"junction_weights", o.junction_weights.string()},
                           {"buildings", clouds.size()},
                           {"batch", c.schedule.batch_size},
                           {"micro_batch", micro},
                           {"threads", config.threads},
                           {"bf16_dot_product_instruction", cpu_has_bf16_dot_product()},
                           {"measurements", nlohmann::json::array()}};
  const int64_t last = *o.measure_at.rbegin();
  stream.start(0);
  std::optional<StreamBatch<PairPatches>> batch = stream.next();
  for (int64_t step = 0; step <= last && batch; ++step) {
    std::optional<StreamBatch<PairPatches>> next = stream.next();
    const uint64_t seed = dropout.seed(), counter = dropout.counter();
    if (o.measure_at.count(step)) {
      if (!next) throw std::invalid_argument("--buildings too small: a measurement needs the step's batch and the next");
      const auto t0 = std::chrono::steady_clock::now();
      double loss_micro = 0;
      const std::vector<double> g_micro = batch_gradient(*batch, micro, seed, counter, loss_micro);
      nlohmann::json m = {{"step", step}, {"loss", {{"micro", loss_micro}}}};
      if (o.whole) {
        double loss_whole = 0, loss_other_masks = 0, loss_next = 0;
        const std::vector<double> g_whole = batch_gradient(*batch, 0, seed, counter, loss_whole);
        const std::vector<double> g_masks = batch_gradient(*batch, 0, seed ^ kOtherMasks, counter, loss_other_masks);
        const std::vector<double> g_next = batch_gradient(*next, 0, seed, counter, loss_next);
        m["loss"].update({{"whole", loss_whole}, {"whole_other_masks", loss_other_masks}, {"next_batch", loss_next}});
        m["micro_vs_whole"] = to_json(compare(g_micro, g_whole));
        m["other_masks_vs_whole"] = to_json(compare(g_masks, g_whole));
        m["next_batch_vs_whole"] = to_json(compare(g_next, g_whole));
      }
      if (o.bf16) {
        double loss_bf16 = 0, loss_micro_masks = 0;
        std::vector<double> g_bf16;
        {
          MatmulPrecisionGuard bf16(MatmulPrecision::kBf16);
          g_bf16 = batch_gradient(*batch, micro, seed, counter, loss_bf16);
        }
        const std::vector<double> g_micro_masks = batch_gradient(*batch, micro, seed ^ kOtherMasks, counter, loss_micro_masks);
        m["loss"].update({{"micro_bf16", loss_bf16}, {"micro_other_masks", loss_micro_masks}});
        m["bf16_vs_fp32"] = to_json(compare(g_bf16, g_micro));
        m["other_masks_vs_micro"] = to_json(compare(g_micro_masks, g_micro));
      }
      m["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      report["measurements"].push_back(m);
      std::cerr << m.dump() << '\n';
    }
    // Train on with the config's passes, as lc2wf-train does.
    double loss = 0.0;
    batch_gradient(*batch, micro, seed, counter, loss);
    optimizer->step();
    batch = std::move(next);
  }
  report["peak_rss_mb"] = peak_rss_mb();
  write_text_atomically(o.out, report.dump(2) + "\n");
  std::cout << report.dump(2) << '\n';
  return 0;
}

}  // namespace
}  // namespace lc2wf

int main(int argc, char** argv) {
  try {
    return lc2wf::run(lc2wf::parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "micro_batch_gradient: %s\n", e.what());
    return 2;
  }
}

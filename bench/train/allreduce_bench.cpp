// Time of one step's gradient sum for the paper's networks (configs/base.json) over the ranks of an MPI
// job, through the trainer's GradientReducer (1 MiB buckets, and one bucket for comparison), and of a
// one-number sum (the per-message latency that the loss and BatchNorm sums pay). Run under mpirun:
//   mpirun -np 2 build/bench/train/allreduce_bench [configs/base.json] [--repeats 30]
// Rank 0 prints one JSON line per measurement (median seconds over the repeats).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nn/edge_net.h"
#include "nn/junction_net.h"
#include "train/communicator.h"
#include "train/data_parallel.h"
#include "train/gradient_reducer.h"
#include "train/train_config.h"

namespace {

using namespace lc2wf;
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double time_gradient_sum(Communicator& comm, const Module& net, int64_t bucket_bytes, int repeats) {
  std::vector<Tensor> params = net.parameters();
  for (Tensor& p : params) p.set_grad(Tensor::ones(p.shape()));
  GradientReducer reducer(comm, params, bucket_bytes);
  std::vector<double> seconds;
  for (int k = 0; k < repeats + 3; ++k) {
    comm.barrier("bench");
    const auto t0 = Clock::now();
    reducer.finish();
    if (k >= 3) seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return median(seconds);
}

}  // namespace

int main(int argc, char** argv) {
  std::string config_path = "configs/base.json";
  int repeats = 30;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeats") == 0 && i + 1 < argc) repeats = std::max(1, std::atoi(argv[++i]));
    else config_path = argv[i];
  }
  const TrainConfig config = TrainConfig::from_file(config_path);
  const std::unique_ptr<Communicator> comm = open_communicator(&argc, &argv, CommunicatorOptions{});
  JunctionNet junction(config.junction.net, config.seed);
  EdgeNet edge(config.edge.net, config.seed);
  auto report = [&](const char* what, int64_t parameters, int64_t bucket_bytes, double seconds) {
    if (comm->rank() != 0) return;
    std::printf("%s\n", nlohmann::json{{"what", what}, {"ranks", comm->size()}, {"parameters", parameters},
                                       {"bytes", parameters * 4}, {"bucket_bytes", bucket_bytes}, {"seconds", seconds}}
                            .dump().c_str());
  };
  for (const auto& [name, net] : {std::pair<const char*, const Module*>{"junction gradient sum", &junction},
                                  std::pair<const char*, const Module*>{"edge gradient sum", &edge}}) {
    const int64_t n = net->num_parameters();
    report(name, n, kGradientBucketBytes, time_gradient_sum(*comm, *net, kGradientBucketBytes, repeats));
    report(name, n, n * 4 + 4096, time_gradient_sum(*comm, *net, n * 4 + 4096, repeats));
  }
  std::vector<double> seconds;
  for (int k = 0; k < 20 * repeats; ++k) {
    double x = 1.0;
    const auto t0 = Clock::now();
    comm->sum(&x, 1, "bench");
    seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  report("one-number sum", 0, 8, median(seconds));
  return 0;
}

// lc2wf-train: trains the junction model, writes the hand-off, trains the edge model (train/README.md).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "core/blas_backend.h"
#include "core/matmul_precision.h"
#include "core/parallel.h"
#include "core/util/cli.h"
#include "core/util/atomic_file.h"
#include "train/building_set.h"
#include "train/communicator.h"
#include "train/edge_step.h"
#include "train/model_card.h"
#include "train/run_log.h"
#include "train/stages.h"
#include "train/train_config.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-train CONFIG.json [-o OUT] [--stage junction|edge|all] [--resume] [options]
       mpirun -np RANKS lc2wf-train CONFIG.json ...      (data-parallel, one process per rank)

Trains LC2WF's two networks as the paper's release does, one after the other:
  1. junction  the junction model (best weights: OUT/junction.safetensors)
  2. handoff   predicted junctions of every train and validation building from the frozen best junction
               model (OUT/predicted_junctions/<name>.json)
  3. edge      the edge model on GT + predicted pairs (best weights: OUT/edge.safetensors)
Validation runs on the config's validation split only. OUT/log.jsonl logs losses, metrics, learning
rate and throughput; OUT/checkpoints/ holds the last state of each stage for --resume; OUT/README.md is
the model card (lc2wf version and commit, data, kept epochs and their validation scores).

  -o, --out OUT      output folder (default: the config's "out"); created once the config and the
                     line clouds have been read
  --stage S          junction (step 1), edge (steps 2-3, needs OUT/junction.safetensors) or all (default)
  --resume           continue from OUT/checkpoints/ exactly where the last run stopped (same losses as an
                     uninterrupted run); completed stages are skipped
  -j, --threads N    compute threads (default: the config's "threads"; 0 = all cores)
  -q, --quiet        no progress output
  --comm-timeout S   MPI jobs: a rank that waits S seconds for the others ends the job with a message
                     (default 1800)
  --print-config     print the config as training would use it (its "extends" chain merged, every key
                     spelled out, -o and -j applied) as JSON on stdout, check it, and exit; trains nothing

A config may hold "extends": "OTHER.json" (a path relative to the config) and only the keys that differ:
objects merge key by key, any other value replaces the one of OTHER.json; chains are allowed.

Started by mpirun or srun, every rank computes its share of each global batch (the config's batch_size
stays the global batch) and the gradients are summed over the ranks every step; rank 0 writes the log,
the checkpoints and the model card. OUT and the data must be visible to every rank. --resume works with
any number of ranks. See train/README.md, "Data-parallel training".

Inference afterwards: lc2wf-infer --weights OUT cloud... -o DIR. A bad config, a split naming a building
with no cloud file, or a split none of whose clouds can be read is a data error (exit 3) naming the file and
the key. A cloud that cannot be read (or has no segments) is skipped and named on stderr, also with -q; the
run trains without it and exits 1.
)";

struct Args {
  fs::path config;
  std::string stage = "all";
  bool resume = false, quiet = false, print_config = false;
  std::string out;
  std::optional<int> threads;
  CommunicatorOptions comm;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&] { return flag_value(argc, argv, i); };
    if (f == "--stage") {
      a.stage = value();
      if (a.stage != "junction" && a.stage != "edge" && a.stage != "all")
        throw UsageError("--stage must be junction, edge or all, got '" + a.stage + "'");
    } else if (f == "--print-config") {
      a.print_config = true;
    } else if (f == "--resume") {
      a.resume = true;
    } else if (f == "-q" || f == "--quiet") {
      a.quiet = true;
    } else if (f == "-o" || f == "--out") {
      a.out = value();
    } else if (f == "-j" || f == "--threads") {
      a.threads = threads_flag(f, value());
    } else if (f == "--comm-timeout") {
      a.comm.timeout_s = number_flag(f, value());
      if (a.comm.timeout_s <= 0) throw UsageError("--comm-timeout must be > 0 seconds");
    } else if (!f.empty() && f[0] == '-') {
      throw UsageError("unknown option '" + f + "'");
    } else if (a.config.empty()) {
      a.config = f;
    } else {
      throw UsageError("more than one config file given ('" + a.config.string() + "', '" + f + "')");
    }
  }
  if (a.config.empty()) throw UsageError("a config file is required");
  return a;
}

int train(const Args& a, Communicator& comm) {
  const bool writer = comm.rank() == 0;
  TrainConfig config = TrainConfig::from_file(a.config);
  if (!a.out.empty()) config.out = a.out;
  if (a.threads) config.threads = *a.threads;
  set_num_threads(static_cast<int>(config.threads));
  config.threads = num_threads();  // -j 0 resolved, so config.json records a valid count
  set_matmul_precision(parse_matmul_precision(config.precision, "precision"));
  const StageRun run{config.out, a.resume, a.quiet || !writer, config.init_weights, &comm};
  // Every input is read before OUT is touched: a bad split or cloud leaves no half-made run folder.
  const BuildingSet train = load_building_set(config.data, config.data.train_split, "data.train_split of " + a.config.string(), run.quiet);
  const BuildingSet val = load_building_set(config.data, config.data.val_split, "data.val_split of " + a.config.string(), run.quiet);
  // Named also with -q: quiet silences progress, not what was left out (exit 1 at the end).
  if (writer)
    for (const BuildingSet* set : {&train, &val})
      for (const std::string& s : set->skipped) std::fprintf(stderr, "lc2wf-train: skipped building %s (listed in %s)\n", s.c_str(), set->split.c_str());
  const bool partly = !train.skipped.empty() || !val.skipped.empty();
  fs::create_directories(run.out);
  if (writer) write_text_atomically(run.out / "config.json", config.to_json().dump(2) + "\n");
  RunLog log(run.out / "log.jsonl");
  if (!run.quiet)
    std::fprintf(stderr, "lc2wf-train: %zu training and %zu validation buildings, %d rank(s) x %lld threads, matrix products by %s in %s, output %s\n",
                 train.clouds.size(), val.clouds.size(), comm.size(), static_cast<long long>(config.threads),
                 gemm_backend_name().c_str(), to_string(matmul_precision()).c_str(), run.out.string().c_str());
  if (!run.quiet && matmul_precision() == MatmulPrecision::kBf16 && !cpu_has_bf16_dot_product())
    std::fprintf(stderr, "lc2wf-train: precision bf16 is emulated (this CPU has no AVX512-BF16): same numbers, slower than fp32\n");
  if (a.stage == "junction" || a.stage == "all") train_junction_stage(config, train, val, log, run);
  if (a.stage == "edge" || a.stage == "all") {
    const fs::path handoff = write_junction_handoff(train, val, log, run, edge_training_selection(config.edge));
    train_edge_stage(config, train, val, handoff, log, run);
  }
  if (writer) write_model_card(run.out, a.config, config, train, val);
  if (!run.quiet) {
    std::fprintf(stderr, "lc2wf-train: done. Log: %s\n", log.path().string().c_str());
    if (a.stage != "junction")
      std::fprintf(stderr, "Weights: %s (junction.safetensors, edge.safetensors, model card README.md); run lc2wf-infer --weights %s ...\n",
                   run.out.string().c_str(), run.out.string().c_str());
  }
  if (partly && writer)
    std::fprintf(stderr, "lc2wf-train: %zu building(s) skipped (named above): trained and validated without them\n",
                 train.skipped.size() + val.skipped.size());
  return partly ? kExitPartly : kExitDone;
}

// The resolved, checked config with the command line's overrides, as train() would use it.
int print_config(const Args& a) {
  TrainConfig config = TrainConfig::from_file(a.config);
  if (!a.out.empty()) config.out = a.out;
  if (a.threads) {  // as train() resolves it: -j 0 = every core
    set_num_threads(*a.threads);
    config.threads = num_threads();
  }
  config.Check();
  std::fputs((config.to_json().dump(2) + "\n").c_str(), stdout);
  return kExitDone;
}

int run(const Args& a) {
  if (a.print_config) return print_config(a);
  const std::unique_ptr<Communicator> comm = open_communicator(nullptr, nullptr, a.comm);
  try {
    return train(a, *comm);
  } catch (const std::exception& e) {
    if (comm->size() == 1) throw;
    // The other ranks would wait for this one forever: say why, then end the whole job.
    std::fprintf(stderr, "\nlc2wf-train: rank %d of %d: error: %s\nlc2wf-train: rank %d ends the MPI job.\n",
                 comm->rank(), comm->size(), e.what(), comm->rank());
    comm->abort_job(kExitDataError);
    throw;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return lc2wf::cli_main({"lc2wf-train", kUsage, {kEnvStorageCache, kEnvGemm}}, argc, argv, parse_args, run);
}

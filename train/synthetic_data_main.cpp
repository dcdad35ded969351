// lc2wf-synthetic-data: the project's own synthetic buildings as line clouds plus train/val/test split
// files, for the demo and the integration test when no rendered dataset is at hand.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/util/atomic_file.h"
#include "core/util/cli.h"
#include "core/util/progress.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-synthetic-data -o OUT [--count N] [--val K] [--test K] [--seed S]

Writes N seeded random buildings (rectangles and L shapes, hip or gable ends, Roof-Image sizes) as
synthetic line clouds OUT/clouds/synth_<i>.lcloud (noisy pieces of the GT edges, roof/wall texture lines
and clutter, labelled by construction) and the split files OUT/{train,val,test}.txt (the last K + K
buildings are validation and test). Deterministic for a seed. One thread.

  -o, --out OUT       output folder (required)
  --count N           number of buildings (default 12)
  --val K             validation buildings (default 2)
  --test K            test buildings (default 2)
  --seed S            seed (default 1555)
  -q, --quiet         no progress output
)";

struct Args {
  fs::path out;
  int count = 12, val = 2, test = 2;
  uint64_t seed = 1555;
  bool quiet = false;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto small_count = [&] {
      const std::string v = flag_value(argc, argv, i);
      const long long x = parse_count_flag(f, v);
      if (x > 1000000) throw UsageError(f + " is too large (" + v + ")");
      return static_cast<int>(x);
    };
    if (f == "-q" || f == "--quiet") a.quiet = true;
    else if (f == "-o" || f == "--out") a.out = flag_value(argc, argv, i);
    else if (f == "--count") a.count = small_count();
    else if (f == "--val") a.val = small_count();
    else if (f == "--test") a.test = small_count();
    else if (f == "--seed") a.seed = static_cast<uint64_t>(parse_count_flag(f, flag_value(argc, argv, i)));
    else throw UsageError(f.rfind('-', 0) == 0 ? "unknown option '" + f + "'" : "unexpected argument '" + f + "'");
  }
  if (a.out.empty()) throw UsageError("-o OUT is required");
  if (a.count < 1 || a.val + a.test >= a.count) throw UsageError("--count must exceed --val + --test (and be >= 1)");
  return a;
}

int run(const Args& a) {
  std::vector<std::string> names;
  fs::create_directories(a.out / "clouds");
  std::unique_ptr<Progress> bar;
  if (!a.quiet) bar = std::make_unique<Progress>("synthetic buildings", a.count, stderr);
  for (int i = 0; i < a.count; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "synth_%04d", i);
    const uint64_t building_seed = a.seed * 1000003ull + static_cast<uint64_t>(i);
    const Building building = make_random_building(building_seed, name);
    LineCloud cloud = make_synthetic_line_cloud(building, building_seed ^ 0x9e3779b97f4a7c15ull);
    cloud.name = name;
    write_line_cloud(a.out / "clouds" / (std::string(name) + ".lcloud"), cloud);
    names.push_back(name);
    if (bar) bar->step();
  }
  if (bar) bar->finish();
  const int train = a.count - a.val - a.test;
  auto write_split = [&](const std::string& file, int first, int n) {
    std::string text;
    for (int k = first; k < first + n; ++k) text += names[k] + "\n";
    write_text_atomically(a.out / file, text);
  };
  write_split("train.txt", 0, train);
  write_split("val.txt", train, a.val);
  write_split("test.txt", train + a.val, a.test);
  if (!a.quiet)
    std::fprintf(stderr, "lc2wf-synthetic-data: %d line clouds in %s, splits %d/%d/%d\n", a.count,
                 (a.out / "clouds").string().c_str(), train, a.val, a.test);
  return kExitDone;
}

}  // namespace

int main(int argc, char** argv) {
  return lc2wf::cli_main({"lc2wf-synthetic-data", kUsage, {}}, argc, argv, parse_args, run);
}

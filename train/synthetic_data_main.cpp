// lc2wf-synthetic-data: the project's own synthetic buildings as line clouds plus train/val/test split
// files, for the demo and the integration test when no rendered dataset is at hand.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/util/atomic_file.h"
#include "core/util/progress.h"
#include "dataset/line_cloud_io.h"
#include "dataset/synthetic_building.h"
#include "dataset/synthetic_line_cloud.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-synthetic-data --out DIR [--count N] [--val K] [--test K] [--seed S]

Writes N seeded random buildings (rectangles and L shapes, hip or gable ends, Roof-Image sizes) as
synthetic line clouds DIR/clouds/synth_<i>.lcloud (noisy pieces of the GT edges, roof/wall texture lines
and clutter, labelled by construction) and the split files DIR/{train,val,test}.txt (the last K + K
buildings are validation and test). Deterministic for a seed.

  --out DIR    output folder (required)
  --count N    number of buildings (default 12)
  --val K      validation buildings (default 2)
  --test K     test buildings (default 2)
  --seed S     seed (default 1555)
  --quiet      no progress output
  -h, --help   this text
Exit codes: 0 success, 1 I/O error, 2 bad command line.
)";

int parse_int(const std::string& flag, const std::string& v) {
  size_t used = 0;
  int x = 0;
  try {
    x = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || x < 0) throw std::invalid_argument(flag + " needs a non-negative integer, got '" + v + "'");
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  fs::path out;
  int count = 12, val = 2, test = 2;
  unsigned long long seed = 1555;
  bool quiet = false;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string f = argv[i];
      if (f == "-h" || f == "--help") {
        std::fputs(kUsage, stdout);
        return 0;
      }
      if (f == "--quiet") {
        quiet = true;
        continue;
      }
      if (i + 1 >= argc) throw std::invalid_argument(f.rfind("--", 0) == 0 ? f + " needs a value" : "unexpected argument '" + f + "'");
      const std::string v = argv[++i];
      if (f == "--out") out = v;
      else if (f == "--count") count = parse_int(f, v);
      else if (f == "--val") val = parse_int(f, v);
      else if (f == "--test") test = parse_int(f, v);
      else if (f == "--seed") seed = static_cast<unsigned long long>(parse_int(f, v));
      else throw std::invalid_argument("unknown option '" + f + "'");
    }
    if (out.empty()) throw std::invalid_argument("--out DIR is required");
    if (count < 1 || val + test >= count) throw std::invalid_argument("--count must exceed --val + --test (and be >= 1)");
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "lc2wf-synthetic-data: %s\nRun 'lc2wf-synthetic-data --help' for usage.\n", e.what());
    return 2;
  }
  try {
    std::vector<std::string> names;
    fs::create_directories(out / "clouds");
    std::unique_ptr<Progress> bar;
    if (!quiet) bar = std::make_unique<Progress>("synthetic buildings", count, stderr);
    for (int i = 0; i < count; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "synth_%04d", i);
      const uint64_t building_seed = seed * 1000003ull + static_cast<uint64_t>(i);
      const Building building = make_random_building(building_seed, name);
      LineCloud cloud = make_synthetic_line_cloud(building, building_seed ^ 0x9e3779b97f4a7c15ull);
      cloud.name = name;
      write_line_cloud(out / "clouds" / (std::string(name) + ".lcloud"), cloud);
      names.push_back(name);
      if (bar) bar->step();
    }
    if (bar) bar->finish();
    const int train = count - val - test;
    auto write_split = [&](const std::string& file, int first, int n) {
      std::string text;
      for (int k = first; k < first + n; ++k) text += names[k] + "\n";
      write_text_atomically(out / file, text);
    };
    write_split("train.txt", 0, train);
    write_split("val.txt", train, val);
    write_split("test.txt", train + val, test);
    if (!quiet)
      std::fprintf(stderr, "lc2wf-synthetic-data: %d line clouds in %s, splits %d/%d/%d\n", count,
                   (out / "clouds").string().c_str(), train, val, test);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-synthetic-data: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

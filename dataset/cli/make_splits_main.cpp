// lc2wf-make-splits: writes train.txt / val.txt / test.txt from the Roof-Image building names.
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/util/cli.h"
#include "dataset/geometry/building.h"
#include "dataset/splits/splits.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-make-splits --meshes DIR -o OUT [--seed N] [--test N] [--val N]

Writes OUT/train.txt, val.txt and test.txt (one building name per line) from the .polyshape files in
--meshes (e.g. ../shared/data/roof-image/res_building). Rule: sort names by mix(FNV-1a-64(name), seed);
the first --test are test, the next --val validation, the rest train. Prints the counts on stdout.
One thread.

  --meshes DIR        Roof-Image meshes (*.polyshape); the names are the file stems
  -o, --out OUT       output folder (configs/splits for the published splits)
  --seed N            split seed (default 1555)
  --test N            test buildings (default 757)
  --val N             validation buildings (default 200)
  -q, --quiet         do not print the counts
An entry named *.polyshape that is not a regular file (a folder, a FIFO) is left out of the splits and
named on stderr, also with -q (exit 1). A folder without any .polyshape file is a data error (exit 3).
)";

struct Args {
  fs::path meshes, out;
  SplitRule rule;
  bool quiet = false;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&] { return flag_value(argc, argv, i); };
    auto count = [&] {
      const long long n = parse_count_flag(f, value());
      if (n > 1000000000) throw UsageError(f + " is too large");
      return static_cast<int>(n);
    };
    if (f == "--meshes") a.meshes = value();
    else if (f == "-o" || f == "--out") a.out = value();
    else if (f == "--seed") a.rule.seed = static_cast<uint64_t>(parse_count_flag(f, value()));
    else if (f == "--test") a.rule.test_count = count();
    else if (f == "--val") a.rule.val_count = count();
    else if (f == "-q" || f == "--quiet") a.quiet = true;
    else throw UsageError("unknown option '" + f + "'");
  }
  if (a.meshes.empty()) throw UsageError("--meshes DIR is required");
  if (a.out.empty()) throw UsageError("-o OUT is required");
  return a;
}

int run(const Args& a) {
  std::vector<std::string> names;
  int skipped = 0;
  for (const std::string& name : list_polyshape_names(a.meshes)) {
    const fs::path mesh = a.meshes / (name + ".polyshape");
    std::error_code ec;
    if (fs::is_regular_file(mesh, ec)) {
      names.push_back(name);
    } else {  // no building's mesh: lc2wf-dataset could not read it either
      std::fprintf(stderr, "lc2wf-make-splits: skipped %s: not a regular file\n", mesh.string().c_str());
      ++skipped;
    }
  }
  if (names.empty()) throw std::runtime_error(a.meshes.string() + ": no .polyshape file: nothing to split");
  // Checked here to name the folder and the flags (make_splits can only name its own fields).
  if (names.size() < static_cast<size_t>(a.rule.test_count) + static_cast<size_t>(a.rule.val_count))
    throw std::runtime_error(a.meshes.string() + ": " + std::to_string(names.size()) + " building(s), fewer than --test " +
                             std::to_string(a.rule.test_count) + " + --val " + std::to_string(a.rule.val_count));
  const Splits s = make_splits(names, a.rule);
  fs::create_directories(a.out);
  write_name_list(a.out / "train.txt", s.train);
  write_name_list(a.out / "val.txt", s.val);
  write_name_list(a.out / "test.txt", s.test);
  if (!a.quiet)
    std::printf("%zu buildings: %zu train, %zu val, %zu test -> %s\n", names.size(), s.train.size(), s.val.size(), s.test.size(),
              a.out.string().c_str());
  return skipped > 0 ? kExitPartly : kExitDone;
}

}  // namespace

int main(int argc, char** argv) { return cli_main({"lc2wf-make-splits", kUsage, {}}, argc, argv, parse_args, run); }

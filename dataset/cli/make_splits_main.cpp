// lc2wf-make-splits: writes train.txt / val.txt / test.txt from the Roof-Image building names, or with
// --by-tile from real city models by map tile (dataset/splits/city_split.h) with their statistics.
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/util/atomic_file.h"
#include "core/util/cli.h"
#include "core/util/thread_count.h"
#include "dataset/geometry/building.h"
#include "dataset/splits/city_split.h"
#include "dataset/splits/splits.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-make-splits --meshes DIR -o OUT [--seed N] [--test N] [--val N]
       lc2wf-make-splits --by-tile --meshes PATH [--meshes PATH...] -o OUT [--source PATTERN=NAME...]
                         [--root DIR] [--tile-size M] [--test-share F] [--val-share F] [--lod L] [--seed N]

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
  -j, --threads N     buildings loaded in parallel with --by-tile (default: all cores)

--by-tile splits real city models (CityJSON, CityJSONSeq, CityGML; polyshapes too) by map tile, never by
building: every building of each --meshes folder (its files, not sub-folders) or file is loaded as
lc2wf-dataset loads it; tile = (file, x and y of its footprint centre floored to --tile-size metres);
per source, tiles in the order of mix(FNV-1a-64(tile), seed) go to test until --test-share of the source's
buildings are, then to val until --val-share, the rest to train. Writes OUT/train.txt, val.txt, test.txt,
OUT/buildings.csv (per building: name, source, file, split, position, height, footprint, roof kind,
junctions, edges) and OUT/statistics.md (per source and split); buildings that cannot be loaded are
named on stderr and left out (exit 1).
  --source PATTERN=NAME  the source of files whose path relative to --root matches the shell pattern
                      (first match wins; default: the file's folder name)
  --root DIR          the folder source patterns and buildings.csv paths are relative to (default: none)
  --tile-size M       tile side in metres (default 500)
  --test-share F      share of each source's buildings in test (default 0.08)
  --val-share F       share of each source's buildings in val (default 0.04)
  --lod L             city models: the LoD 2.x to use (2.2, 2.1, 2; default: each building's highest)
An entry named *.polyshape that is not a regular file (a folder, a FIFO) is left out of the splits and
named on stderr, also with -q (exit 1). A folder without any .polyshape file is a data error (exit 3).
)";

struct Args {
  fs::path meshes, out;
  SplitRule rule;
  bool quiet = false;
  bool by_tile = false;
  CitySplitOptions city;
};

Args parse_args(int argc, char** argv) {
  Args a;
  a.city.threads = 0;  // no -j: the default thread count
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&] { return flag_value(argc, argv, i); };
    auto count = [&] {
      const long long n = parse_count_flag(f, value());
      if (n > 1000000000) throw UsageError(f + " is too large");
      return static_cast<int>(n);
    };
    if (f == "--meshes") {
      a.meshes = value();
      a.city.inputs.push_back(a.meshes);
    } else if (f == "--by-tile") a.by_tile = true;
    else if (f == "--source") a.city.source_rules.push_back(value());
    else if (f == "--root") a.city.root = value();
    else if (f == "--tile-size") a.city.rule.tile_size_m = number_flag(f, value());
    else if (f == "--test-share") a.city.rule.test_share = number_flag(f, value());
    else if (f == "--val-share") a.city.rule.val_share = number_flag(f, value());
    else if (f == "--lod") a.city.sources.lod = value();
    else if (f == "-j" || f == "--threads") a.city.threads = resolve_thread_count(threads_flag(f, value()));
    else if (f == "-o" || f == "--out") a.out = value();
    else if (f == "--seed") a.city.rule.seed = a.rule.seed = static_cast<uint64_t>(parse_count_flag(f, value()));
    else if (f == "--test") a.rule.test_count = count();
    else if (f == "--val") a.rule.val_count = count();
    else if (f == "-q" || f == "--quiet") a.quiet = true;
    else throw UsageError("unknown option '" + f + "'");
  }
  if (a.meshes.empty()) throw UsageError("--meshes DIR is required");
  if (a.out.empty()) throw UsageError("-o OUT is required");
  if (a.by_tile) {
    if (a.city.threads < 1) a.city.threads = default_thread_count();
    check_options([&] { a.city.Check(); }, {{"tile_size_m", "--tile-size"}, {"test_share and val_share", "--test-share and --val-share"},
                                             {"lod", "--lod"}, {"source rule", "--source"}});
  }
  return a;
}

int run_by_tile(const Args& a) {
  const CitySplitResult r = make_city_split(a.city);
  for (const auto& [name, reason] : r.skipped) std::fprintf(stderr, "lc2wf-make-splits: skipped %s: %s\n", name.c_str(), reason.c_str());
  if (r.buildings.empty()) throw std::runtime_error("no building could be loaded: nothing to split");
  fs::create_directories(a.out);
  write_name_list(a.out / "train.txt", r.splits.train);
  write_name_list(a.out / "val.txt", r.splits.val);
  write_name_list(a.out / "test.txt", r.splits.test);
  std::string csv = "name,source,file,split,x_m,y_m,height_m,footprint_long_m,footprint_short_m,roof_kind,junctions,edges\n";
  char row[160];
  for (const CitySplitBuilding& b : r.buildings) {
    std::snprintf(row, sizeof row, ",%.1f,%.1f,%.2f,%.2f,%.2f,", b.x, b.y, b.height_m, b.long_side_m, b.short_side_m);
    csv += b.name + "," + b.source + "," + b.file + "," + b.split + row + b.roof_kind + "," + std::to_string(b.junctions) + "," +
           std::to_string(b.edges) + "\n";
  }
  write_file_atomic(a.out / "buildings.csv", csv);
  write_file_atomic(a.out / "statistics.md", city_split_statistics_markdown(r));
  if (!a.quiet)
    std::printf("%zu buildings: %zu train, %zu val, %zu test, %zu skipped -> %s\n", r.buildings.size(), r.splits.train.size(),
                r.splits.val.size(), r.splits.test.size(), r.skipped.size(), a.out.string().c_str());
  return r.skipped.empty() ? kExitDone : kExitPartly;
}

int run(const Args& a) {
  if (a.by_tile) return run_by_tile(a);
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

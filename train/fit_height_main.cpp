// lc2wf-fit-height: the height model (dataset/photo/line_height.h) that scales photo clouds and line maps no
// other evidence scales, fitted on metric line clouds of buildings whose heights it then reads back.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/util/cli.h"
#include "core/util/input_file.h"
#include "core/util/parallel_items.h"
#include "core/util/thread_count.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/photo/line_height.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-fit-height -o MODEL.json [--list FILE]... [CLOUD.lcloud | FOLDER]...

Makes the height model lc2wf-reconstruct and lc2wf-infer use when nothing else gives a cloud's scale
(no --scale, --known-distance, GPS, --building-height or storey rhythm): the statistics of each cloud's
lines (the share of its lines in each half-octave of length over its height, by direction, and its
footprint's proportions) with the building's height; a new cloud is as tall as the median of its k
nearest. The clouds must be metric and z up, as lc2wf-dataset writes them; render them the way the
model's users' clouds look (photo textures for photos). k is chosen by cross-validation (contiguous
folds of the clouds sorted by path, so one tile's buildings are held out together); the model records
it and the cross-validated median and 90th-percentile height errors. Deterministic.

  -o, --out FILE       the model, JSON (written atomically); weights folders keep it as height.json
  --list FILE          more clouds: one path per line (blank lines and # comments skipped)
  --ks K,K,...         neighbour counts to choose from (default 3,5,7,9,11,15)
  --folds K            cross-validation folds (default 5)
  -j, --threads N      clouds read at once (default: all cores)
  -q, --quiet          no summary on stderr
)";

struct Args {
  fs::path out;
  std::vector<fs::path> inputs, lists;  // clouds or folders of them; files listing more
  HeightFitOptions fit;
  int threads = 0;
  bool quiet = false;
};

std::vector<int> int_list(const std::string& flag, const std::string& text) {
  std::vector<int> v;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) v.push_back(int_flag(flag, item));
  return v;
}

// Every fold leaves more training clouds than the largest k asks for.
size_t min_clouds(const HeightFitOptions& o) { return static_cast<size_t>(o.folds) * static_cast<size_t>(*std::max_element(o.ks.begin(), o.ks.end()) + 1); }

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    if (f == "-q" || f == "--quiet") a.quiet = true;
    else if (f == "-o" || f == "--out") a.out = flag_value(argc, argv, i);
    else if (f == "-j" || f == "--threads") a.threads = threads_flag(f, flag_value(argc, argv, i));
    else if (f == "--ks") a.fit.ks = int_list(f, flag_value(argc, argv, i));
    else if (f == "--folds") a.fit.folds = int_flag(f, flag_value(argc, argv, i));
    else if (f == "--list") a.lists.push_back(flag_value(argc, argv, i));
    else if (f.rfind('-', 0) == 0 && f.size() > 1) throw UsageError("unknown option '" + f + "'");
    else a.inputs.push_back(f);
  }
  if (a.out.empty()) throw UsageError("-o MODEL.json is required");
  if (a.inputs.empty() && a.lists.empty()) throw UsageError("no cloud given (CLOUD.lcloud, FOLDER or --list FILE)");
  check_options([&] { a.fit.Check(); }, {{"HeightFitOptions.ks", "--ks"}, {"HeightFitOptions.folds", "--folds"}});
  return a;
}

// The .lcloud files of `p` (a folder, searched recursively) or `p` itself; a path that does not exist is
// a data error naming it.
void add_clouds(const fs::path& p, std::vector<fs::path>* out) {
  if (!fs::exists(p)) throw std::runtime_error(p.string() + ": no such file or folder");
  if (!fs::is_directory(p)) return out->push_back(p);
  for (const auto& e : fs::recursive_directory_iterator(p))
    if (e.is_regular_file() && e.path().extension() == ".lcloud") out->push_back(e.path());
}

std::vector<fs::path> cloud_paths(const Args& a) {
  std::vector<fs::path> clouds;
  for (const fs::path& p : a.inputs) add_clouds(p, &clouds);
  for (const fs::path& list : a.lists) {
    std::stringstream ss(read_input_file(list, 64 << 20));
    for (std::string line; std::getline(ss, line);) {
      line.erase(line.find_last_not_of(" \t\r") + 1);
      if (!line.empty() && line[0] != '#') add_clouds(line, &clouds);
    }
  }
  std::sort(clouds.begin(), clouds.end());
  clouds.erase(std::unique(clouds.begin(), clouds.end()), clouds.end());
  if (clouds.size() < min_clouds(a.fit))
    throw std::runtime_error("needs at least " + std::to_string(min_clouds(a.fit)) + " clouds (--folds x (largest --ks + 1)), got " +
                             std::to_string(clouds.size()));
  return clouds;
}

int run(const Args& a) {
  const std::vector<fs::path> clouds = cloud_paths(a);
  std::vector<LineStatistics> stats(clouds.size());
  std::vector<std::string> problems(clouds.size());
  for_each_item(static_cast<int64_t>(clouds.size()), resolve_thread_count(a.threads), [&](int64_t i) {
    try {
      stats[i] = line_statistics(read_line_cloud(clouds[i]).segments);
    } catch (const std::exception& e) {
      problems[i] = e.what();
    }
  }, 4);
  std::vector<LineStatistics> used;
  std::vector<double> heights;
  int skipped = 0;
  for (size_t i = 0; i < clouds.size(); ++i) {
    if (!problems[i].empty()) {
      std::fprintf(stderr, "lc2wf-fit-height: skipped %s: %s\n", clouds[i].string().c_str(), problems[i].c_str());
      ++skipped;
      continue;
    }
    heights.push_back(stats[i].height);  // metric clouds: their own height is the truth
    used.push_back(stats[i]);
  }
  if (used.size() < min_clouds(a.fit))
    throw std::runtime_error("only " + std::to_string(used.size()) + " readable clouds, fewer than --folds x (largest --ks + 1)");
  const HeightModel m = fit_height_model(used, heights, a.fit);
  write_height_model(a.out, m);
  if (!a.quiet)
    std::fprintf(stderr, "lc2wf-fit-height: %zu clouds (%d skipped), k %d, cross-validated height error median %.1f %%, p90 %.1f %% -> %s\n",
                 used.size(), skipped, m.k, 100 * m.cv_median_error, 100 * m.cv_p90_error, a.out.string().c_str());
  return skipped > 0 ? kExitPartly : kExitDone;
}

}  // namespace

int main(int argc, char** argv) {
  return lc2wf::cli_main({"lc2wf-fit-height", kUsage, {}}, argc, argv, parse_args, run);
}

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

Fits the height model lc2wf-reconstruct and lc2wf-infer use when nothing else gives a cloud's scale
(no --scale, --known-distance, GPS, --building-height or storey rhythm): a ridge regression from the
statistics of a cloud's lines (the share of its lines in each half-octave of length over its height, by
direction, and its footprint's proportions) to the logarithm of the building's height. The clouds must be
metric and z up with labels' units in metres, as lc2wf-dataset writes them; render them the way the
model's users' clouds look (photo textures for photos). The ridge penalty is chosen by cross-validation
(folds by the clouds' order after sorting by path); the model file records it and the cross-validated
median and 90th-percentile height errors. Deterministic.

  -o, --out FILE       the model, JSON (written atomically); weights folders keep it as height.json
  --list FILE          more clouds: one path per line (blank lines and # comments skipped)
  --lambdas L,L,...    ridge penalties to choose from (default 1,3,10,30,100,300)
  --folds K            cross-validation folds (default 5)
  -j, --threads N      clouds read at once (default: all cores)
  -q, --quiet          no summary on stderr
)";

struct Args {
  fs::path out;
  std::vector<fs::path> clouds;
  HeightFitOptions fit;
  int threads = 0;
  bool quiet = false;
};

std::vector<double> number_list(const std::string& flag, const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) v.push_back(number_flag(flag, item));
  return v;
}

void add_path(const fs::path& p, std::vector<fs::path>* out) {
  if (fs::is_directory(p)) {
    for (const auto& e : fs::recursive_directory_iterator(p))
      if (e.is_regular_file() && e.path().extension() == ".lcloud") out->push_back(e.path());
  } else {
    out->push_back(p);
  }
}

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    if (f == "-q" || f == "--quiet") a.quiet = true;
    else if (f == "-o" || f == "--out") a.out = flag_value(argc, argv, i);
    else if (f == "-j" || f == "--threads") a.threads = threads_flag(f, flag_value(argc, argv, i));
    else if (f == "--lambdas") a.fit.lambdas = number_list(f, flag_value(argc, argv, i));
    else if (f == "--folds") a.fit.folds = int_flag(f, flag_value(argc, argv, i));
    else if (f == "--list") {
      const fs::path list = flag_value(argc, argv, i);
      std::string text;
      try {
        text = read_input_file(list, 64 << 20);
      } catch (const std::exception& e) {
        throw UsageError(std::string("--list: ") + e.what());
      }
      std::stringstream ss(text);
      for (std::string line; std::getline(ss, line);) {
        line.erase(line.find_last_not_of(" \t\r") + 1);
        if (!line.empty() && line[0] != '#') add_path(line, &a.clouds);
      }
    } else if (f.rfind('-', 0) == 0 && f.size() > 1) throw UsageError("unknown option '" + f + "'");
    else add_path(f, &a.clouds);
  }
  if (a.out.empty()) throw UsageError("-o MODEL.json is required");
  check_options([&] { a.fit.Check(); }, {{"HeightFitOptions.lambdas", "--lambdas"}, {"HeightFitOptions.folds", "--folds"}});
  std::sort(a.clouds.begin(), a.clouds.end());
  a.clouds.erase(std::unique(a.clouds.begin(), a.clouds.end()), a.clouds.end());
  if (a.clouds.size() < static_cast<size_t>(2 * a.fit.folds))
    throw UsageError("needs at least " + std::to_string(2 * a.fit.folds) + " clouds (2 per fold), got " + std::to_string(a.clouds.size()));
  return a;
}

int run(const Args& a) {
  std::vector<LineStatistics> stats(a.clouds.size());
  std::vector<std::string> problems(a.clouds.size());
  for_each_item(static_cast<int64_t>(a.clouds.size()), resolve_thread_count(a.threads), [&](int64_t i) {
    try {
      stats[i] = line_statistics(read_line_cloud(a.clouds[i]).segments);
    } catch (const std::exception& e) {
      problems[i] = e.what();
    }
  }, 4);
  std::vector<LineStatistics> used;
  std::vector<double> heights;
  int skipped = 0;
  for (size_t i = 0; i < a.clouds.size(); ++i) {
    if (!problems[i].empty()) {
      std::fprintf(stderr, "lc2wf-fit-height: skipped %s: %s\n", a.clouds[i].string().c_str(), problems[i].c_str());
      ++skipped;
      continue;
    }
    heights.push_back(stats[i].height);  // metric clouds: their own height is the truth
    used.push_back(stats[i]);
  }
  if (used.size() < static_cast<size_t>(2 * a.fit.folds))
    throw std::runtime_error("only " + std::to_string(used.size()) + " readable clouds, fewer than 2 per fold");
  const HeightModel m = fit_height_model(used, heights, a.fit);
  write_height_model(a.out, m);
  if (!a.quiet)
    std::fprintf(stderr, "lc2wf-fit-height: %zu clouds (%d skipped), lambda %g, cross-validated height error median %.1f %%, p90 %.1f %% -> %s\n",
                 used.size(), skipped, m.lambda, 100 * m.cv_median_error, 100 * m.cv_p90_error, a.out.string().c_str());
  return skipped > 0 ? kExitPartly : kExitDone;
}

}  // namespace

int main(int argc, char** argv) {
  return lc2wf::cli_main({"lc2wf-fit-height", kUsage, {}}, argc, argv, parse_args, run);
}

// What the junction stage is taught: over a split, the share of junction patches labelled positive, how far
// their offset targets reach, and how many GT junctions some patch is labelled with (the recall a perfect
// junction model could reach with this sampling), for the release's labels, for endpoint labels kept
// only within a distance of their junction (`junction.endpoint_label_max_distance_m`, --max-distance) and
// for patches kept positive only within a distance of their junction (`junction.positive_radius_m`,
// --positive-radius).
//   lc2wf_junction_label_stats --data CLOUDS --split FILE [--max-distance D]... [--positive-radius R]... [--limit N]
// Prints a Markdown table, one row per label rule (the first: the release's).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/util/cli.h"
#include "dataset/formats/cloud_input.h"
#include "dataset/sampling/network_input.h"
#include "dataset/splits/splits.h"

namespace fs = std::filesystem;
using namespace lc2wf;

struct RuleStats {
  std::string name;
  double max_distance_m = std::numeric_limits<double>::infinity();
  double positive_radius_m = std::numeric_limits<double>::infinity();
  int64_t patches = 0, positives = 0, gt_junctions = 0, labelled_junctions = 0, near_junctions = 0;
  std::vector<double> offsets_m;  // positives' |target - sample point|

  void add(const LineCloud& cloud, const JunctionPatches& p, const NetworkFrame& frame) {
    const double metres_per_unit = frame.scale_m;
    std::vector<char> labelled(cloud.wireframe.junctions.size(), 0), near(labelled.size(), 0);
    for (int g = 0; g < p.num_patches; ++g) {
      ++patches;
      const Vec3 point(p.points[3 * g], p.points[3 * g + 1], p.points[3 * g + 2]);
      for (size_t j = 0; j < near.size(); ++j)
        if ((point - frame.to_network(cloud.wireframe.junctions[j])).norm() * metres_per_unit <= 0.35) near[j] = 1;
      if (p.label[g] < 0) continue;
      ++positives;
      labelled[static_cast<size_t>(p.label[g])] = 1;
      const Vec3 offset(p.offset[3 * g], p.offset[3 * g + 1], p.offset[3 * g + 2]);
      offsets_m.push_back(offset.norm() * metres_per_unit);
    }
    gt_junctions += static_cast<int64_t>(labelled.size());
    labelled_junctions += std::count(labelled.begin(), labelled.end(), 1);
    near_junctions += std::count(near.begin(), near.end(), 1);
  }

  double percentile(double q) {
    if (offsets_m.empty()) return 0;
    std::sort(offsets_m.begin(), offsets_m.end());
    return offsets_m[static_cast<size_t>(q * static_cast<double>(offsets_m.size() - 1))];
  }
  double share_beyond(double m) const {
    return offsets_m.empty() ? 0
                             : static_cast<double>(std::count_if(offsets_m.begin(), offsets_m.end(),
                                                                 [m](double d) { return d > m; })) /
                                   static_cast<double>(offsets_m.size());
  }
};

int run(int argc, char** argv) {
  fs::path data, split;
  std::vector<RuleStats> rules{RuleStats{"the release's"}};
  int64_t limit = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string f = argv[i], v = argv[i + 1];
    if (f == "--data") data = v;
    else if (f == "--split") split = v;
    else if (f == "--max-distance") rules.push_back(RuleStats{"endpoints within " + v + " m", number_flag(f, v)});
    else if (f == "--positive-radius")
      rules.push_back(RuleStats{"patches within " + v + " m", std::numeric_limits<double>::infinity(), number_flag(f, v)});
    else if (f == "--limit") limit = static_cast<int64_t>(number_flag(f, v));
    else {
      std::fprintf(stderr, "lc2wf_junction_label_stats: unknown argument '%s'\n", f.c_str());
      return 2;
    }
  }
  if (data.empty() || split.empty()) {
    std::fprintf(stderr, "usage: lc2wf_junction_label_stats --data CLOUDS --split FILE [--max-distance D]... "
                 "[--positive-radius R]... [--limit N]\n");
    return 2;
  }
  std::vector<std::string> names = read_name_list(split);
  if (limit > 0 && static_cast<int64_t>(names.size()) > limit) names.resize(static_cast<size_t>(limit));
  for (const std::string& name : names) {
    const LineCloud cloud = load_line_cloud(find_cloud_file(data, name), CloudFormat::kAuto);
    for (RuleStats& rule : rules) {
      JunctionSampleOptions options;  // inference's sampling: no augmentation, no near-GT samples
      options.endpoint_label_max_distance_m = rule.max_distance_m;
      options.patch.positive_radius_m = rule.positive_radius_m;
      rule.add(cloud, make_junction_sample(cloud, options, 1), options.patch.frame);
    }
  }
  std::printf("%zu buildings of %s\n\n", names.size(), split.string().c_str());
  std::printf("| label rule | positive patches | offset target, m (median / p90) | offsets > 1 m "
              "| GT junctions some patch is labelled with | GT junctions with a sample point within 0.35 m |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (RuleStats& r : rules) {
    std::printf("| %s | %.1f %% | %.2f / %.2f | %.1f %% | %.1f %% | %.1f %% |\n", r.name.c_str(),
                100.0 * static_cast<double>(r.positives) / static_cast<double>(std::max<int64_t>(r.patches, 1)), r.percentile(0.5),
                r.percentile(0.9), 100.0 * r.share_beyond(1.0),
                100.0 * static_cast<double>(r.labelled_junctions) / static_cast<double>(std::max<int64_t>(r.gt_junctions, 1)),
                100.0 * static_cast<double>(r.near_junctions) / static_cast<double>(std::max<int64_t>(r.gt_junctions, 1)));
  }
  return 0;
}

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf_junction_label_stats: %s\n", e.what());
    return 3;
  }
}

// How much of the ground truth the line clouds show: for each GT edge, the share of its length the cloud's
// segments run along (SegmentSupport of dataset/selection/pair_support.h: segments with both ends within
// --radius of the edge's line and within --angle of its direction). An edge no segment covers can only be
// guessed by a model, so the shares bound what reconstruction from lines can find. Per group (a folder of name
// lists, e.g. the groups/ of bench/real/score_groups.sh): GT edges, the share covered for < 20 % and for
// >= 60 % of their length (by count and by length), the uncovered share of the vertical edges' length, and the
// share shorter than 0.5 m. With --prediction DIR (<name>.obj wireframes in metres, e.g. lc2wf_oracle_junctions
// --keep-wireframes) also the share of the GT edges in each coverage band that a predicted edge matches (the
// distances of its two endpoints to the GT edge's sum to < 0.5 m).
//   lc2wf_gt_line_coverage --data CLOUDS --split FILE [--groups DIR] [--prediction DIR] [--radius M] [--angle DEG]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/util/cli.h"
#include "dataset/formats/cloud_input.h"
#include "dataset/selection/pair_support.h"
#include "dataset/splits/splits.h"
#include "infer/prediction_io.h"

namespace fs = std::filesystem;
using namespace lc2wf;

namespace {

constexpr double kBare = 0.2, kSeen = 0.6, kShort = 0.5, kMatch = 0.5;

struct Tally {
  double edges = 0, length = 0, bare = 0, bare_length = 0, seen = 0, seen_length = 0, shorter = 0;
  double vertical_length = 0, vertical_bare_length = 0;
  double found[3] = {0, 0, 0}, in_band[3] = {0, 0, 0};  // bands: bare, partly covered, seen
  void add(const Tally& t) {
    edges += t.edges, length += t.length, bare += t.bare, bare_length += t.bare_length, seen += t.seen;
    seen_length += t.seen_length, shorter += t.shorter, vertical_length += t.vertical_length;
    vertical_bare_length += t.vertical_bare_length;
    for (int b = 0; b < 3; ++b) found[b] += t.found[b], in_band[b] += t.in_band[b];
  }
};

bool matched(const Vec3& p, const Vec3& q, const ScoredWireframe& prediction) {
  for (const auto& e : prediction.wireframe.edges) {
    const Vec3& a = prediction.wireframe.junctions[e[0]];
    const Vec3& b = prediction.wireframe.junctions[e[1]];
    const double d = std::min((a - p).norm() + (b - q).norm(), (a - q).norm() + (b - p).norm());
    if (d < kMatch) return true;
  }
  return false;
}

Tally building_tally(const LineCloud& cloud, const ScoredWireframe* prediction, double radius, double angle) {
  const SegmentSupport support(cloud.segments);
  Tally t;
  for (const auto& e : cloud.wireframe.edges) {
    const Vec3& p = cloud.wireframe.junctions[e[0]];
    const Vec3& q = cloud.wireframe.junctions[e[1]];
    const double length = (q - p).norm();
    const double covered = support.support(p, q, radius, angle);
    const bool vertical = length > 0 && std::abs(q[2] - p[2]) / length > 0.95;
    const int band = covered < kBare ? 0 : covered < kSeen ? 1 : 2;
    t.edges += 1, t.length += length, t.shorter += length < kShort;
    if (band == 0) t.bare += 1, t.bare_length += length;
    if (band == 2) t.seen += 1, t.seen_length += length;
    if (vertical) t.vertical_length += length, t.vertical_bare_length += band == 0 ? length : 0;
    t.in_band[band] += 1;
    if (prediction && matched(p, q, *prediction)) t.found[band] += 1;
  }
  return t;
}

std::string share(double part, double whole) {
  if (whole <= 0) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %%", 100.0 * part / whole);
  return text;
}

int run(int argc, char** argv) {
  fs::path data, split, groups, prediction;
  double radius = 0.15, angle = 10.0;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    const std::string v = flag_value(argc, argv, i);
    if (f == "--data") data = v;
    else if (f == "--split") split = v;
    else if (f == "--groups") groups = v;
    else if (f == "--prediction") prediction = v;
    else if (f == "--radius") radius = number_flag(f, v);
    else if (f == "--angle") angle = number_flag(f, v);
    else throw UsageError("unknown argument '" + f + "'");
  }
  if (data.empty() || split.empty() || !(radius > 0) || !(angle > 0 && angle < 90))
    throw UsageError("usage: lc2wf_gt_line_coverage --data CLOUDS --split FILE [--groups DIR] [--prediction DIR] "
                     "[--radius M > 0] [--angle DEG in (0, 90)]");
  std::map<std::string, Tally> per_building;
  for (const std::string& name : read_name_list(split)) {
    const LineCloud cloud = load_line_cloud(find_cloud_file(data, name), CloudFormat::kAuto);
    ScoredWireframe predicted;
    if (!prediction.empty()) predicted = read_prediction(prediction / (name + ".obj"));
    per_building[name] = building_tally(cloud, prediction.empty() ? nullptr : &predicted, radius, angle);
  }
  std::map<std::string, std::vector<std::string>> members{{"all", {}}};
  for (const auto& [name, tally] : per_building) members["all"].push_back(name);
  if (!groups.empty()) {
    for (const auto& entry : fs::directory_iterator(groups)) {
      if (entry.path().extension() != ".txt" || entry.path().stem() == "all") continue;
      for (const std::string& name : read_name_list(entry.path()))
        if (per_building.count(name)) members[entry.path().stem().string()].push_back(name);
    }
  }
  std::printf("| group | buildings | GT edges | covered < 20 %%: edges / length | covered >= 60 %%: edges / length | "
              "vertical length covered < 20 %% | shorter than 0.5 m |%s\n",
              prediction.empty() ? "" : " matched: covered < 20 % / 20-60 % / >= 60 % |");
  std::printf("|---|---|---|---|---|---|---|%s\n", prediction.empty() ? "" : "---|");
  for (const auto& [group, names] : members) {
    Tally t;
    for (const std::string& name : names) t.add(per_building[name]);
    std::printf("| %s | %zu | %.0f | %s / %s | %s / %s | %s | %s |", group.c_str(), names.size(), t.edges,
                share(t.bare, t.edges).c_str(), share(t.bare_length, t.length).c_str(), share(t.seen, t.edges).c_str(),
                share(t.seen_length, t.length).c_str(), share(t.vertical_bare_length, t.vertical_length).c_str(),
                share(t.shorter, t.edges).c_str());
    if (!prediction.empty())
      std::printf(" %s / %s / %s |", share(t.found[0], t.in_band[0]).c_str(), share(t.found[1], t.in_band[1]).c_str(),
                  share(t.found[2], t.in_band[2]).c_str());
    std::printf("\n");
  }
  std::printf("\nSegments within %.2f m of an edge's line and %.0f degrees of its direction count as covering it.\n",
              radius, angle);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "lc2wf_gt_line_coverage: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf_gt_line_coverage: %s\n", e.what());
    return 3;
  }
}

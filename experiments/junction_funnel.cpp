// Where the GT junctions are lost on the way through the pipeline of `lc2wf-eval --weights`: for each GT
// junction, whether some junction candidate lies within η of it (any confidence, any offset), one above the
// confidence cut, one that also passes the offset screen, a selected (NMS'd, refined) junction, and a junction
// of the final wireframe. Each stage's share of the GT junctions the metric's matching would count within η
// (model/ap_metric.h, points in confidence order), at its three vertex η: the recall each stage would allow.
//   lc2wf_junction_funnel --weights DIR --data CLOUDS --split FILE [--precision fp32|bf16|auto] [selection flags]
// Selection flags as lc2wf-eval's (infer/post_process_flags.h). Prints a Markdown table.
#include <array>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "core/matmul_precision.h"
#include "core/util/cli.h"
#include "dataset/formats/cloud_input.h"
#include "dataset/geometry/wireframe_graph.h"
#include "dataset/splits/splits.h"
#include "model/ap_metric.h"
#include "infer/batch_inference.h"
#include "model/inference.h"
#include "infer/post_process_flags.h"

namespace fs = std::filesystem;
using namespace lc2wf;

namespace {

constexpr std::array<double, 3> kEta = {0.15, 0.25, 0.35};  // the vertex η of the metrics (metres)

enum Stage { kCandidate, kConfident, kNear, kAgreed, kSelected, kFinal, kStages };
const char* const kStageNames[kStages] = {
    "a junction candidate (any confidence, any offset)",
    "a candidate above the confidence cut",
    "... also within the offset screen",
    "... or a far vote that 2 other far votes agree with (within 0.25 m)",
    "a selected junction (NMS, refined)",
    "a junction of the final wireframe",
};

// The points of one stage with their confidences.
struct StagePoints {
  std::vector<Vec3> positions;
  std::vector<double> scores;
  void add(const Vec3& p, double score) { positions.push_back(p), scores.push_back(score); }
};

// GT junctions the metric's matching (model/ap_metric.h) would count as found if these points were the output.
int64_t matched(const std::vector<Vec3>& gt, const StagePoints& points, double eta) {
  int64_t n = 0;
  for (const RankedHit& hit : match_junctions(points.positions, points.scores, gt, eta, -1.0)) n += hit.true_positive;
  return n;
}

// Whether some point lies within `radius` of p (skipping index `self` of the same list).
bool any_within(const Vec3& p, const std::vector<Vec3>& points, double radius, size_t self = SIZE_MAX) {
  for (size_t k = 0; k < points.size(); ++k)
    if (k != self && (points[k] - p).norm() <= radius) return true;
  return false;
}

double percent(int64_t part, int64_t whole) { return 100.0 * static_cast<double>(part) / static_cast<double>(whole ? whole : 1); }

}  // namespace

int run(int argc, char** argv) {
  fs::path weights, data, split;
  std::string precision = "fp32";
  PostProcessFlags flags;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    if (flags.parse(f, argc, argv, i)) continue;
    if (i + 1 >= argc) throw UsageError(f + " needs a value");
    const std::string v = argv[++i];
    if (f == "--weights") weights = v;
    else if (f == "--data") data = v;
    else if (f == "--split") split = v;
    else if (f == "--precision") precision = v;
    else throw UsageError("unknown argument '" + f + "'");
  }
  if (weights.empty() || data.empty() || split.empty())
    throw UsageError("usage: lc2wf_junction_funnel --weights DIR --data CLOUDS --split FILE [--precision P] [selection flags]");
  const WireframePredictor predictor(weights);
  const MatmulPrecisionGuard guard(precision_flag(precision));
  const PostProcessOptions options = flags.options();
  const JunctionSelectionOptions& sel = options.selection;
  std::array<std::array<int64_t, kStages>, kEta.size()> found{};
  std::array<int64_t, kStages> points{};
  int64_t missed_low_few_ends = 0, gt_low = 0, missed = 0, missed_few_ends = 0, missed_degree = 0, missed_low = 0, missed_close = 0;
  int64_t gt_total = 0, close_gt = 0, buildings = 0;
  for (const std::string& name : read_name_list(split)) {
    const LineCloud cloud = load_line_cloud(find_cloud_file(data, name), CloudFormat::kAuto);
    const InferenceResult r = predictor.predict(cloud, options);
    std::array<StagePoints, kStages> at;
    StagePoints far;
    std::vector<char> near(r.junctions.positions.size(), 0);
    for (int k : offset_screened(r.junctions, sel)) near[static_cast<size_t>(k)] = 1;
    for (size_t k = 0; k < r.junctions.positions.size(); ++k) {
      const Vec3& p = r.junctions.positions[k];
      const double c = r.junctions.confidence[k];
      at[kCandidate].add(p, c);
      if (c <= sel.min_confidence) continue;
      at[kConfident].add(p, c);
      if (near[k]) at[kNear].add(p, c), at[kAgreed].add(p, c);
      else far.add(p, c);
    }
    for (size_t a = 0; a < far.positions.size(); ++a) {
      int others = 0;
      for (size_t b = 0; b < far.positions.size(); ++b) others += b != a && (far.positions[b] - far.positions[a]).norm() <= 0.25;
      if (others >= 2) at[kAgreed].add(far.positions[a], far.scores[a]);
    }
    at[kSelected] = {r.selection.positions, r.selection.confidences};
    at[kFinal] = {r.wireframe.wireframe.junctions, r.wireframe.junction_scores};
    const std::vector<Vec3>& gt = cloud.wireframe.junctions;
    for (int s = 0; s < kStages; ++s) {
      for (size_t e = 0; e < kEta.size(); ++e) found[e][s] += matched(gt, at[s], kEta[e]);
      points[s] += static_cast<int64_t>(at[s].positions.size());
    }
    // What the GT junctions without any candidate within the largest η look like.
    const std::vector<int> degree = junction_degrees(cloud.wireframe);
    for (size_t g = 0; g < gt.size(); ++g) {
      const bool low = gt[g].z() < 0.5;
      gt_low += low;
      close_gt += any_within(gt[g], gt, sel.nms_radius_m, g);
      if (any_within(gt[g], at[kCandidate].positions, kEta.back())) continue;
      ++missed;
      int ends = 0;
      for (const Segment3& seg : cloud.segments) ends += ((seg.a - gt[g]).norm() <= kEta.back()) + ((seg.b - gt[g]).norm() <= kEta.back());
      missed_few_ends += ends < 2;
      missed_degree += degree[g];
      missed_low += low;
      missed_low_few_ends += low && ends < 2;
      missed_close += any_within(gt[g], gt, 1.0, g);
    }
    gt_total += static_cast<int64_t>(gt.size());
    ++buildings;
  }
  std::printf("%lld buildings, %lld GT junctions; %.1f %% of them have another GT junction within the NMS radius %.2f m\n\n",
              static_cast<long long>(buildings), static_cast<long long>(gt_total), percent(close_gt, gt_total), sel.nms_radius_m);
  std::printf("| GT junctions with ... within η | η = 0.15 | η = 0.25 | η = 0.35 | points per building | of them matching no GT junction within 0.35 m |\n|---|---|---|---|---|---|\n");
  const double per = static_cast<double>(buildings ? buildings : 1);
  for (int s = 0; s < kStages; ++s) {
    std::printf("| %s |", kStageNames[s]);
    for (size_t e = 0; e < kEta.size(); ++e) std::printf(" %.1f %% |", percent(found[e][s], gt_total));
    std::printf(" %.1f | %.1f |\n", static_cast<double>(points[s]) / per,
                static_cast<double>(points[s] - found[kEta.size() - 1][s]) / per);
  }
  std::printf("\nGT junctions without any candidate within %.2f m: %lld (%.1f %%); of them %.1f %% with fewer than 2 cloud "
              "endpoints within %.2f m, %.1f %% with another GT junction within 1 m, %.1f %% below 0.5 m height (of all GT "
              "junctions %.1f %%; of the missed ones below 0.5 m, %.1f %% with fewer than 2 endpoints); mean degree %.2f\n",
              kEta.back(), static_cast<long long>(missed), percent(missed, gt_total), percent(missed_few_ends, missed), kEta.back(),
              percent(missed_close, missed), percent(missed_low, missed), percent(gt_low, gt_total),
              percent(missed_low_few_ends, missed_low), static_cast<double>(missed_degree) / static_cast<double>(missed ? missed : 1));
  return 0;
}

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "lc2wf_junction_funnel: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf_junction_funnel: %s\n", e.what());
    return 3;
  }
}

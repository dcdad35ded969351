// Sample points of the junction stage (release section 2.1): density seeds among the segment endpoints,
// completed by farthest point sampling to G. Radii are in metres (release raw 6 / 3 / 1.5 = 0.3 / 0.15 /
// 0.075 m). Deterministic; the optional near-GT positives (the paper's training-time sampling, absent
// from the release) are drawn from a caller-seeded generator.
#pragma once

#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

class DataRng;

// Which endpoints seed the sample: candidates have A_i > min_count and C_i > min_ratio (SamplingOptions
// below), thinned by a suppressor NMS of radius nms_m on C.
struct DensitySeedRule {
  int min_count = 12;     // the release's
  double min_ratio = 0.7;
  double nms_m = 0.075;   // release raw 1.5
  static DensitySeedRule release() { return {}; }
  // Not in the release: with its rule our clouds get ≈ 25 seeds and the 256 points cover 85 % of the GT
  // junctions within 0.35 m; these get ≈ 80 and cover 96 % (experiments/README.md, "Density seeds").
  static DensitySeedRule loose() { return {4, 0.5, 0.3}; }
  bool operator==(const DensitySeedRule&) const = default;
  void Check() const;  // throws std::invalid_argument naming the bad field
  // "release", "loose", or "MIN_COUNT,MIN_RATIO,NMS_M" for any other rule; parse() reads the same forms.
  std::string str() const;
  static DensitySeedRule parse(const std::string& text);  // throws std::invalid_argument
};

struct SamplingOptions {
  int num_samples = 256;                 // G
  double density_radius_m = 0.30;        // A_i = #endpoints within this (self included)
  double density_inner_radius_m = 0.15;  // B_i = #endpoints within this; C_i = B_i / (A_i + 1e-3)
  DensitySeedRule seeds;                 // the release's by default (training); inference picks its own
  int near_gt_samples = 0;               // training option: endpoints near GT junctions drawn first
  double near_gt_radius_m = 0.35;        // "near" = within this of a GT junction
  // Inference option (the release: 1): passes x num_samples points, the first num_samples exactly the
  // one-pass sample, the rest farthest-point sampling continued from them (sampling_passes in
  // junction_selection.h).
  int passes = 1;
  void Check() const;
};

// Density seeds: endpoint indices after the NMS on C_i, the most endpoints within density_radius_m (A_i)
// first, ties in descending C_i (may be empty).
std::vector<int> density_seeds(const std::vector<Vec3>& endpoints, const SamplingOptions& options);

// Farthest point sampling to `count` starting from `seeds` (first occurrence kept, capped at count). With
// no seeds the first endpoint starts the chain (the release would fail). With <= count points the result
// is [0, 1, ..., count-1] mod n, as the release. Returns {} for no points.
std::vector<int> farthest_point_sampling(const std::vector<Vec3>& points, int count, const std::vector<int>& seeds);

// The full rule: [near-GT picks] + density seeds, then FPS to num_samples; with passes > 1, more points
// after those. `gt_junctions` and `rng` are only used when near_gt_samples > 0.
// The sampling passes a cloud needs so its size sets the budget of sample points, not a fixed count: one pass
// per `metres_per_pass` of the longer horizontal side of its segments' endpoint box (2nd-98th percentile, so a
// few stray lines do not count), at least 1 and at most `max_passes`; 1 when metres_per_pass <= 0.
int passes_for_extent(const std::vector<Segment3>& segments, double metres_per_pass, int max_passes = 8);

std::vector<int> sample_endpoints(const std::vector<Vec3>& endpoints, const SamplingOptions& options,
                                  const std::vector<Vec3>* gt_junctions = nullptr, DataRng* rng = nullptr);

// Endpoints of segments in the release order: segment k -> 2k (a), 2k+1 (b).
std::vector<Vec3> segment_endpoints(const std::vector<Segment3>& segments);

}  // namespace lc2wf

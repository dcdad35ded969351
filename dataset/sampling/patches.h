// Junction patches (release section 2.2-2.3) and pair patches (3.5) as plain float arrays with shapes,
// ready to be wrapped into tensors. Geometry comes in metres (already augmented); features leave in
// network units (NetworkFrame). Segment selection is by default the release's: the `lines_per_patch`
// segments nearest to the query point by distance to the segment's *infinite line*, slots farther than
// the radius become padding; a junction model may choose the distance to the segment instead
// (JunctionNetConfig::patch_distance). Infinite-line distance cannot be bounded by a spatial index, so
// selection is a linear scan over a structure-of-arrays copy of the segments (SegmentSet).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/geometry/network_frame.h"

namespace lc2wf {

// What padded slots contain. Release: segment 0's endpoints (relative to the query point) and the point-
// to-segment distance of the far segment that fell in that slot; the mask marks them either way (but
// the release's mean pooling and batch norm still see them). Zero: all-zero features.
enum class PaddingMode { Release, Zero };

// Which distance picks a patch's lines. InfiniteLine: the release's. Segment: the distance to the segment
// itself, so that on a facade of windows a corner's patch holds the lines at the corner rather than the
// window rows' sills and lintels whose extensions pass through it (experiments/README.md, "Segment patches").
enum class PatchDistance { InfiniteLine, Segment };
// "infinite_line" / "segment"; throws std::invalid_argument naming `where` for anything else.
PatchDistance parse_patch_distance(const std::string& name, const std::string& where);
const char* patch_distance_name(PatchDistance d);

struct PatchOptions {
  int lines_per_patch = 32;
  double radius_m = 0.2 * kReleaseStdRaw / kRawUnitsPerMetre;  // 0.2 network units = 2.662 m
  int negative_noise_count = 16;                       // patch negative if >= this many noise lines
  // Not in the release: a patch whose majority junction lies farther than this from its sample point is
  // negative too, so the junction model learns to find nearby junctions instead of voting for ones metres
  // away (with the plain labels of our fragment clouds, 58 % of the patches are positive and most offsets
  // exceed 1 m: experiments/README.md). Infinity = the release's rule.
  double positive_radius_m = std::numeric_limits<double>::infinity();
  PaddingMode padding = PaddingMode::Release;
  PatchDistance distance = PatchDistance::InfiniteLine;
  NetworkFrame frame;
  void Check() const;
};

// Segments prepared for repeated queries (read-only after construction; queries are thread-safe).
class SegmentSet {
 public:
  explicit SegmentSet(const std::vector<Segment3>& segments);
  size_t size() const { return segments_.size(); }
  const Segment3& segment(size_t i) const { return segments_[i]; }
  // Indices of the `k` segments nearest to q by `distance` (to the infinite line, or to the segment; ties: lower
  // index), in ascending distance; `dist` receives those distances. Zero-length segments count as infinitely far.
  void nearest(const Vec3& q, int k, PatchDistance distance, std::vector<int>& idx, std::vector<double>& dist) const;
  // Euclidean distance from q to segment i (the release's point-to-segment feature).
  double segment_distance(size_t i, const Vec3& q) const;

 private:
  std::vector<Segment3> segments_;
  std::vector<double> ax_, ay_, az_, dx_, dy_, dz_, inv_len_;  // A and B - A; 1 / (|AB| + 1e-6), 0 if zero length
  std::vector<double> inv_len2_;                                // 1 / |AB|^2, 0 if zero length
  std::vector<double> far_;                                     // squared 1e5 for zero-length segments, else 0
};

// Arrays have a leading batch dimension `batch` (1 for one building; stack() concatenates buildings).
struct JunctionPatches {
  int batch = 1;
  int num_patches = 0;  // G
  int lines = 0;        // L
  static constexpr int kFeatures = 7;
  std::vector<float> features;    // G x L x 7: [near - x, far - x, point-to-segment distance] (network units)
  std::vector<uint8_t> padded;    // G x L, 1 = padding (the release's word_mask)
  std::vector<float> points;      // G x 3 sample points (network units)
  std::vector<int32_t> label;     // G: GT junction id, or -1 (negative)
  std::vector<float> offset;      // G x 3: GT junction - point (network units), 0 for negatives
  std::vector<int32_t> endpoint;  // G: the endpoint index each sample point is
};

// `endpoint_labels`: 2N per-endpoint labels (GT junction id or -1), may be empty (then every label is -1).
// `gt_junctions`: augmented GT junctions in metres (for the offsets), may be empty when unlabelled.
// `samples`: endpoint indices (2k = segment k's a, 2k+1 its b).
JunctionPatches build_junction_patches(const SegmentSet& segments, const std::vector<int>& endpoint_labels,
                                       const std::vector<Vec3>& gt_junctions, const std::vector<int>& samples,
                                       const PatchOptions& options);

// A pair of junctions to classify. `label` is the 5-class pair label (or -1 when unknown).
struct JunctionPair {
  Vec3 u = Vec3::Zero();
  Vec3 v = Vec3::Zero();
  int i = -1;  // index of u in its junction list (GT or predicted, see from_gt)
  int j = -1;
  int label = -1;
  bool from_gt = false;
};

struct PairPatches {
  int batch = 1;
  int num_pairs = 0;  // P (per building; stacking needs equal counts)
  int lines = 0;      // 2 L
  static constexpr int kFeatures = 6;
  std::vector<float> features;  // P x 2L x 6: [near - m, far - m] around the pair midpoint m (network units)
  std::vector<uint8_t> padded;  // P x 2L
  std::vector<int32_t> label;   // P
};

// Concatenate buildings along the batch dimension; all parts must have the same G/P and L.
JunctionPatches stack(const std::vector<JunctionPatches>& parts);
PairPatches stack(const std::vector<PairPatches>& parts);
// Buildings [first, first + count) of a batch: the inverse of stack(), for micro-batches.
JunctionPatches slice(const JunctionPatches& batch, int first, int count);
PairPatches slice(const PairPatches& batch, int first, int count);

PairPatches build_pair_patches(const SegmentSet& segments, const std::vector<JunctionPair>& pairs, const PatchOptions& options);

}  // namespace lc2wf

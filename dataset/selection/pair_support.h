// Line support of a junction pair: the share of the straight line between the two junctions that the
// cloud's segments run along. Inference can skip pairs without support before the edge model sees them
// (PairSupportOptions::min_support > 0): the model's cost grows with the pairs, while a true edge almost
// always has segments along it. Off by default (the release classifies every pair).
#pragma once

#include <utility>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/sampling/patches.h"

namespace lc2wf {

struct PairSupportOptions {
  double min_support = 0.0;          // keep pairs whose support is >= this share of their length; 0 keeps all
  double radius_m = 0.35;            // a segment counts when both endpoints lie this close to the pair's line
  double max_angle_deg = 20.0;       // and its direction is within this angle of the pair's
  double keep_shorter_than_m = 1.0;  // always keep shorter pairs (two detections of one junction are close)

  bool enabled() const { return min_support > 0; }
  void Check() const;  // throws std::invalid_argument naming the bad field
};

// A cloud's segments ordered by their smallest x (those without a finite length or a direction left out), so
// that the ones whose x range meets an interval are found without looking at the others.
class SegmentsByX {
 public:
  explicit SegmentsByX(const std::vector<Segment3>& segments);
  const std::vector<Segment3>& segments() const { return segments_; }
  // Indices [first, last) into segments() holding every segment whose x range meets [x_lo, x_hi].
  std::pair<size_t, size_t> meeting(double x_lo, double x_hi) const;

 private:
  std::vector<Segment3> segments_;
  std::vector<double> min_x_;  // ascending
  double max_x_extent_ = 0;    // of any segment
};

// The segments of one cloud, prepared for many support queries: a query scans the ones whose x range meets
// its own, not the whole cloud.
class SegmentSupport {
 public:
  explicit SegmentSupport(const std::vector<Segment3>& segments);
  // Share in [0, 1] of the segment u-v covered by the union of the counted segments' projections onto it
  // (u == v: 1). A segment counts when both its endpoints lie within radius_m of the line u-v and its
  // direction is within max_angle_deg of it.
  double support(const Vec3& u, const Vec3& v, double radius_m, double max_angle_deg) const;

 private:
  friend class AnchoredSegmentSupport;
  SegmentsByX by_x_;
  std::vector<Vec3> dir_;  // unit direction of each segment of by_x_
  std::vector<double> length_;
};

// The segments near one point, prepared for the many support queries that start there (a junction's pairs):
// every segment is tested against every query, without SegmentSupport's x window, and the share is
// SegmentSupport's bit for bit. Give it the segments that can reach the queries. Queries may run at once.
class AnchoredSegmentSupport {
 public:
  AnchoredSegmentSupport(const std::vector<Segment3>& segments, const Vec3& anchor);
  // SegmentSupport::support(anchor, v, radius_m, max_angle_deg) over these segments.
  double support(const Vec3& v, double radius_m, double max_angle_deg) const;

 private:
  Vec3 anchor_;
  std::vector<Vec3> a_, b_;         // each segment's ends relative to the anchor
  std::vector<double> dir_xyz_[3];  // its unit direction's x, y and z apart (the screening loop reads them so)
};

// The pairs that pass the option's test, in their order (all of them when the option is off).
std::vector<JunctionPair> supported_pairs(const std::vector<JunctionPair>& pairs, const std::vector<Segment3>& segments,
                                          const PairSupportOptions& options);

}  // namespace lc2wf

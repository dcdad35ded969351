// Which segments of a cloud run along one another: the test behind the merged-map rule
// (overlapped_long_fraction, segment_split.h) and the confirmation of photo clouds' lines
// (line_confirmation.h), kept in one place so both mean the same by "overlapped".
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/geometry/spatial_grid.h"

namespace lc2wf {

constexpr double kOverlapRadiusM = 0.10;               // the midpoint's distance from the other segment
constexpr double kOverlapMinCos = 0.9961946980917455;  // directions within 5 degrees

// True when `s`'s midpoint lies within kOverlapRadiusM of `other`, between its ends, and the two
// directions are within 5 degrees. False for a degenerate `other`.
bool midpoint_runs_along(const Segment3& s, const Segment3& other);

// A grid of points along every segment (every 25 cm, sparser for clouds longer than `max_points` x 25 cm), so
// that the segments a midpoint runs along are found without comparing every pair. Keeps a reference to
// `segments`, which must outlive it.
class SegmentOverlapIndex {
 public:
  explicit SegmentOverlapIndex(const std::vector<Segment3>& segments, int64_t max_points = 2'000'000);
  // The segments j != i that segment i's midpoint runs along (midpoint_runs_along), ascending, each once.
  void runs_along(size_t i, std::vector<int>& out) const;

 private:
  struct Samples {
    std::vector<Vec3> points;
    std::vector<int> owner;  // the segment each point lies on
    double radius = 0.0;     // query radius: kOverlapRadiusM widened by half the spacing
  };
  static Samples sample_along(const std::vector<Segment3>& segments, int64_t max_points);

  const std::vector<Segment3>& segments_;
  Samples samples_;
  SpatialGrid grid_;
};

}  // namespace lc2wf

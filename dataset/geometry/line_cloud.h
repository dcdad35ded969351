// A building's 3D line cloud: segments in metres, their supporting 2D observations, the cameras, the GT
// wireframe, the raw<->metre transform and the per-segment label tuple (f, i1, d1, i2, d2).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// One 2D segment that supports a 3D segment: the view (index into LineCloud::cameras) and its pixels.
struct Observation {
  int view = -1;
  Segment2 seg;
};

// f = 1: the segment lies on GT edge (i1, i2) with i1 the junction at the segment's first endpoint `a`
// and i2 at `b`; d1 = |a - J[i1]|, d2 = |b - J[i2]| in metres. f = 0: i1 = i2 = -1, d1 = d2 = -1.
// Release-compatible data may carry a junction on one endpoint only (then f = 0 and the other id is -1).
struct SegmentLabel {
  bool f = false;
  int i1 = -1;
  double d1 = -1;
  int i2 = -1;
  double d2 = -1;
  friend bool operator==(const SegmentLabel&, const SegmentLabel&) = default;
};

struct LineCloud {
  std::string name;
  std::vector<Segment3> segments;                 // metres, building frame (z up, ground 0)
  std::vector<std::vector<Observation>> support;  // empty, or one (possibly empty) list per segment
  std::vector<Camera> cameras;                    // view id = index
  Wireframe wireframe;                            // ground truth in metres (may be empty when unknown)
  UnitTransform units;                            // metres <-> raw units of the source building
  std::vector<SegmentLabel> labels;               // empty (unlabelled) or one per segment
  // Read from another program's line map (Line3D++, LIMAP, line OBJ: external_line_map.h), whose lines merge
  // the views' fragments; our files and the release's JSON hold per-view fragments. Not stored in files.
  bool external_line_map = false;
};

// The release's per-endpoint labels (2N values: GT junction id or -1), derived from `labels`:
// endpoint a -> i1, endpoint b -> i2. All -1 when the cloud is unlabelled. With a finite
// `max_distance_m` an endpoint keeps its junction only when it lies within that distance of it (d1/d2),
// so a piece from the middle of a long edge does not point at junctions metres away.
std::vector<int> endpoint_labels(const LineCloud& cloud, double max_distance_m = std::numeric_limits<double>::infinity());

// Label tuple for a segment known to lie on GT edge (j, k): orders the junctions to match the segment's
// endpoints (the pairing with the smaller summed endpoint distance) and fills the distances.
SegmentLabel make_edge_label(const Segment3& segment, const Wireframe& wireframe, int j, int k);

// The segments with keep[i] true, with their labels and supports; everything else of the cloud as it is.
LineCloud keep_segments(const LineCloud& cloud, const std::vector<bool>& keep);

// FNV-1a over the name and the segments' coordinates (as stored): tells whether predictions made from a
// cloud still belong to it, e.g. after the dataset was regenerated on another machine.
uint64_t segments_fingerprint(const LineCloud& cloud);

// Throws DataError(source, "...") naming the first inconsistency: non-finite values, zero-length segments,
// support/label counts, view ids or junction ids out of range, bad cameras or wireframe edges.
void validate_line_cloud(const LineCloud& cloud, const std::string& source);

}  // namespace lc2wf

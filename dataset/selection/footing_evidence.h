// Whether a junction on the ground has the building standing over it. A footprint corner carries its wall:
// segment ends rise above it (the wall's edge, the eaves' corner). Corners on the ground with nothing above
// them are the outlines of cast shadows, paths or a neighbour's plot, which the corner check passes (two
// directions end there): on the Roof-Image validation clouds (Blender, with the sun's shadows) `general`
// drew 265 false junctions on the ground, 219 of them with nothing above, and all its 750 true ground
// junctions had segment ends above them (infer/README.md, "Footing evidence").
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct FootingEvidenceOptions {
  double radius_m = 0.0;         // segment ends this close horizontally count (metres); 0 = every junction passes
  double min_rise_m = 1.0;       // ... when at least this much higher than the junction
  double ground_band_m = 0.3;    // junctions at most this far above the ground are tested
  // The ground's height in the cloud's frame: every cloud lc2wf makes or reads is z up with the ground at 0
  // (dataset/geometry/line_cloud.h; lc2wf-reconstruct and foreign line maps are put there). Not a quantile of
  // the lines: triangulation outliers put the 1st percentile of the segment ends' heights 0.9 m below the
  // ground on half the Roof-Image validation clouds (down to 9.7 m), and a layer search misses low buildings.
  double ground_z_m = 0.0;
  bool enabled() const { return radius_m > 0; }
  void Check() const;            // throws std::invalid_argument naming the bad field
};

// For each junction: false when it lies at most ground_band_m above ground_z_m (or below it) and no segment end
// within radius_m horizontally lies min_rise_m or more above it; true otherwise, or when the options are off.
// Time: one pass over the segments, then one grid query per ground junction.
std::vector<char> footing_evidence(const std::vector<Vec3>& junctions, const std::vector<Segment3>& segments,
                                   const FootingEvidenceOptions& options);

}  // namespace lc2wf

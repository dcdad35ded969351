// Whether a junction on the ground has the building standing over it. A footprint corner carries its wall:
// segment ends rise above it (the wall's edge, the eaves' corner). Corners on the ground with nothing above
// them are the outlines of cast shadows, paths or a neighbour's plot, which the corner check passes (two
// directions end there): on the Roof-Image validation clouds (Blender, with the sun's shadows) `general`
// paired 136 such junctions, none of them true, and every one of its 339 true ground junctions had segment
// ends above it within 0.3 m (infer/README.md, "Footing evidence").
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct FootingEvidenceOptions {
  double radius_m = 0.0;         // segment ends this close horizontally count (metres); 0 = every junction passes
  double min_rise_m = 1.0;       // ... when at least this much higher than the junction
  double ground_band_m = 0.3;    // junctions at most this far above the ground level are tested
  double ground_quantile = 0.01; // the ground level: this quantile of the segment ends' heights (z up)
  bool enabled() const { return radius_m > 0; }
  void Check() const;            // throws std::invalid_argument naming the bad field
};

// For each junction: false when it lies within ground_band_m of the cloud's ground level (or below it) and no
// segment end within radius_m horizontally lies min_rise_m or more above it; true otherwise, or when the
// options are off. Time: one pass over the segments, then one grid query per ground junction.
std::vector<char> footing_evidence(const std::vector<Vec3>& junctions, const std::vector<Segment3>& segments,
                                   const FootingEvidenceOptions& options);

}  // namespace lc2wf

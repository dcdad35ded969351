// Junction refinement (beyond the paper): the junction model regresses a position from a 32-line patch,
// which is coarse (tens of centimetres); the line cloud's own segments ending near a junction usually pin
// it much more precisely. Each selected junction moves to the least-squares meeting point of the lines
// through the segments that end near it, regularised towards the predicted position and, with a robust
// scale, reweighted so that lines passing the junction by are outvoted by those meeting there.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct JunctionRefineOptions {
  double radius = 0.0;          // metres; segments with an endpoint this close take part; 0 = off
  int min_segments = 2;         // fewer supporting segments: the junction stays where it was
  double prior_weight = 0.05;   // pull towards the predicted position, relative to one supporting line
  double min_length = 0.2;      // metres; shorter segments carry no usable direction
  // metres; > 0: reweighted least squares (Cauchy weights of each line's distance from the estimate, this
  // scale) so that a stray line near the junction does not drag it; 0 = plain least squares
  double robust_scale = 0.0;
  int robust_iterations = 4;

  void Check() const;  // throws std::invalid_argument naming the bad field
};

// Refined copies of `junctions` (same order). A junction whose supporting lines do not pin a point within
// `radius` of it (too few segments, or near-parallel lines only) is returned unchanged.
std::vector<Vec3> refine_junctions(const std::vector<Vec3>& junctions, const std::vector<Segment3>& segments,
                                   const JunctionRefineOptions& options);

}  // namespace lc2wf

// A wireframe with a confidence per junction and per edge: what inference produces and what the metrics
// rank. Coordinates are metres (see dataset/geometry/geometry.h).
#pragma once

#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct ScoredWireframe {
  Wireframe wireframe;
  std::vector<double> junction_scores;  // one per wireframe.junctions entry (junction classifier confidence)
  std::vector<double> edge_scores;      // one per wireframe.edges entry (connect probability)

  // Throws std::invalid_argument (prefixed with `what`) on score counts that do not match, edge indices out of
  // range, or non-finite coordinates/scores.
  void check(const std::string& what) const;
  // All scores set to 1: the ranking used for wireframes that come without confidences.
  static ScoredWireframe with_unit_scores(Wireframe wireframe);
};

// The junctions referenced by at least one edge (first-appearance order over the edge list) and all edges,
// re-indexed; this is the vertex set the paper's metrics evaluate (isolated vertices are not predictions).
ScoredWireframe referenced_junctions_only(const ScoredWireframe& in);

}  // namespace lc2wf

// Faces within one candidate plane: the plane's edges as a planar graph in the plane's 2D frame, its
// bounded faces found by angular ordering around each junction, and the edges that would close its open
// chains (a missing side of a face).
#pragma once

#include <array>
#include <vector>

#include "infer/surfaces/plane_candidates.h"

namespace lc2wf {

// Closed rings of junction ids (no vertex repeated, a simple polygon in the plane), counter-clockwise
// around the plane's normal: the bounded faces of the plane's edges once dangling edges are pruned.
// `budget` (when given) is charged with the plane's graph and each ring's simplicity test (its sides squared);
// once it is exhausted the rings found so far are returned.
std::vector<std::vector<int>> plane_cycles(const Wireframe& wireframe, const CandidatePlane& plane, double eps,
                                           WorkBudget* budget = nullptr);

struct ClosingEdge {
  std::array<int, 2> ends;  // junction ids, ends[0] < ends[1]
  bool mutual_nearest;      // each end is the other's nearest open chain end in this plane
  int chain_edges;          // edges on the shortest path between the ends in this plane (the face would have one more)
};

// Pairs of open chain ends (junctions with one edge in the plane) of one connected chain system whose
// straight join crosses no edge of the plane: the missing side that would close a face. `budget` (when given)
// is charged with the pairs of open ends and, per join tried, the plane's graph; once it is exhausted the joins
// found so far are returned.
std::vector<ClosingEdge> closing_edges(const Wireframe& wireframe, const CandidatePlane& plane, double eps,
                                       WorkBudget* budget = nullptr);

}  // namespace lc2wf

// Candidate face planes of a wireframe: every pair of non-parallel edges meeting at a junction spans one;
// near-coplanar ones are clustered into one plane, refitted to the junctions of the edges lying in it.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"
#include "infer/surfaces/polygon_geometry.h"
#include "infer/surfaces/surface_options.h"
#include "infer/surfaces/work_budget.h"

namespace lc2wf {

struct CandidatePlane {
  Plane plane;
  std::vector<int> edges;  // ids of the wireframe edges lying in the plane (both ends within plane_distance_m)
};

// Planes with at least two edges, each edge set distinct, ordered by how many junction pairs voted for them.
// Time: linear in the pairs of edges at a junction (a grid over normal and offset finds the plane a pair joins)
// plus the planes times the junctions, which `budget` (when given) is charged with: one step per pair, one
// per junction tested against a plane. Once it is exhausted the planes found so far are returned.
std::vector<CandidatePlane> candidate_planes(const Wireframe& wireframe, const SurfaceOptions& options,
                                             WorkBudget* budget = nullptr);

// The ids of the edges whose both ends lie within `distance` of the plane.
std::vector<int> edges_in_plane(const Wireframe& wireframe, const Plane& plane, double distance);

}  // namespace lc2wf

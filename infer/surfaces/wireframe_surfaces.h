// Faces from a wireframe: the planar cycles of its graph that bound the building (roof facets, walls, the
// ground), found when edges are missing or spurious, made into a closed, consistently oriented shell where
// the evidence allows, with the reasons when it does not. The steps (infer/README.md, "Surfaces"):
// clean_wireframe -> candidate_planes -> closing_edges (gaps) -> plane_cycles -> select_shell_faces ->
// merge_coplanar_faces -> orient_faces -> snap_vertices_to_planes -> label_faces -> check_shell, and once
// more with walls completed down to the ground when the first shell is open.
#pragma once

#include <vector>

#include "infer/surfaces/surface_model.h"
#include "infer/surfaces/surface_options.h"
#include "infer/surfaces/shell_checks.h"

namespace lc2wf {

// Deterministic. The work is bounded: graphs with more than options.max_edges edges are not searched, and the
// search stops once it has taken options.max_work_steps steps (work_budget.h; about 5 ns each): the model then
// keeps what was finished (no faces when the first shell was not) and its reasons say where the budget ran
// out. model.work_steps is the work taken. Throws std::invalid_argument on bad options.
SurfaceModel surfaces_from_wireframe(const Wireframe& wireframe, const SurfaceOptions& options = {});

// The same for a predicted wireframe with its edge probabilities (`edge_scores`, one per edge): the faces of
// the confident edges (score >= options.min_edge_score) when they close into a valid solid, else of all the
// edges when those do, else of the confident ones (with the budget's reason when the search of all the edges
// ran out of it). One work budget for both searches. Throws std::invalid_argument when the counts differ.
SurfaceModel surfaces_from_wireframe(const Wireframe& wireframe, const std::vector<double>& edge_scores,
                                     const SurfaceOptions& options = {});

}  // namespace lc2wf

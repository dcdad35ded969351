// Geometric validity of a surface model, computed from the geometry alone (not from how it was built):
// planarity, closure, orientation and self-intersection. Used by surfaces_from_wireframe() for its status,
// by the writers' tests and by lc2wf-eval (share of buildings with a valid closed solid).
#pragma once

#include <string>
#include <vector>

#include "infer/surfaces/surface_model.h"
#include "infer/surfaces/work_budget.h"

namespace lc2wf {

struct ShellCheck {
  double max_planarity_m = 0;   // largest distance of a face vertex from its face's least-squares plane
  int non_planar_faces = 0;     // faces with a vertex farther than the tolerance
  int open_edges = 0;           // sides bounding one face only
  int overused_edges = 0;       // sides bounding three or more faces
  int misoriented_edges = 0;    // sides two faces run in the same direction
  double signed_volume = 0;     // positive when the oriented shell's normals point outwards
  int self_intersecting_faces = 0;  // rings that are not simple polygons
  int intersecting_face_pairs = 0;  // faces crossing or overlapping another face away from shared sides

  bool planar() const { return non_planar_faces == 0; }
  bool closed() const { return open_edges == 0 && overused_edges == 0; }
  bool oriented() const { return misoriented_edges == 0 && signed_volume > 0; }
  bool simple() const { return self_intersecting_faces == 0 && intersecting_face_pairs == 0; }
  bool valid_solid() const { return planar() && closed() && oriented() && simple(); }
  // One sentence per failed check ("3 edges bound only one face"); empty for a valid solid.
  std::vector<std::string> problems() const;
};

// `planarity_tolerance`: metres; also the distance below which two points count as one. `budget` (when given)
// is charged with the work (each ring's tests, every pair of vertices, every pair of faces and, for pairs whose
// boxes meet, their sides against each other); once it is exhausted the check stops and its counts are partial.
ShellCheck check_shell(const SurfaceModel& model, double planarity_tolerance, WorkBudget* budget = nullptr);

}  // namespace lc2wf

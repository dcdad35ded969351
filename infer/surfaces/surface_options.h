// Settings of the face finder (surfaces_from_wireframe). Distances in metres, angles in degrees; the
// defaults suit predicted wireframes, whose junctions are off by 0.1-0.3 m.
#pragma once

namespace lc2wf {

struct SurfaceOptions {
  double merge_distance_m = 0.1;    // junctions closer than this are one; a junction this close to an edge splits it
  double plane_distance_m = 0.2;    // a junction this close to a plane lies in it (snaps near-coplanar facets)
  double plane_angle_deg = 5;       // candidate planes whose normals differ by less than this are one plane
  double min_edge_angle_deg = 10;   // two edges at a junction closer than this to (anti)parallel span no plane
  double wall_tilt_deg = 15;        // a face within this of vertical is a wall
  double planarity_tolerance_m = 0.01;  // the shell checks: a face vertex farther from the face's plane is non-planar
  bool complete_walls = true;       // walls down from eave corners to the ground level of the vertical edges
  double min_edge_score = 0.9;      // scored wireframes: faces from the edges this confident first (0: every edge)
  bool prism_walls = true;          // an open shell: walls extruded from the roof outline, ground = footprint
  int max_edges = 2000;             // larger graphs are not searched (bounded time); the model says why
  // Work budget of one building (both searches of a scored wireframe): the steps that can grow faster than the
  // graph (edge pairs at junctions, junctions tested against candidate planes, the planes' graphs and rings,
  // face pairs checked) stop here, and the model says so in its reasons (work_budget.h). A step is about 5 ns:
  // the default stops after roughly 0.1-0.25 s. Predictions of real buildings take up to 20 million, but for
  // the search of all the edges of the densest one (665 edges), which stops here.
  long max_work_steps = 25'000'000;
  // Throws std::invalid_argument naming the setting ("surfaces.plane_distance_m must be > 0").
  void Check() const;
};

}  // namespace lc2wf

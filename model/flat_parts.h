// Flat fragments of a photo cloud's wireframe: a building is a solid, so the parts of its wireframe span three
// dimensions, while the networks also draw small groups of edges around window frames, doors and a neighbour's
// face - flat, and apart from the building's own edges. After the edge-support rule, every connected part but
// the largest (by drawn length) that has fewer than `max_edges` edges and whose junctions all lie within
// `plane_tolerance_m` of one plane is dropped. The largest part always stays (a single facade seen from the
// street is flat too).
// Off by default; lc2wf-reconstruct turns it on for every capture (infer/README.md, "Flat fragments").
#pragma once

#include "model/scored_wireframe.h"

namespace lc2wf {

struct FlatPartOptions {
  int max_edges = 0;               // parts with fewer edges may go; 0 = off
  double plane_tolerance_m = 0.75;  // every junction this close to the part's best-fitting plane: flat
  // Only where the cloud's cameras leave a side unseen (as EdgeSupportOptions): on full photo orbits it cost
  // the known-camera clouds 4 points of vAP (infer/README.md). false: every cloud.
  bool partial_captures_only = true;
  bool enabled() const { return max_edges > 0; }
  void Check() const;  // throws std::invalid_argument naming the bad field
};

struct FlatPartsDropped {
  ScoredWireframe wireframe;  // the kept edges in their order, and the junctions they use
  int dropped_parts = 0, dropped_edges = 0;
};

FlatPartsDropped drop_flat_parts(const ScoredWireframe& in, const FlatPartOptions& options);

}  // namespace lc2wf

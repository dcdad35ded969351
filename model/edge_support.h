// Edges something was seen of: after post-processing, an edge is kept when the cloud's segments run along
// enough of its length (the measure of dataset/selection/pair_support.h) or, when the cloud has cameras, when
// enough cameras had it in view (model/edge_visibility.h); junctions left without an edge go. On a capture
// of one or two sides the networks still propose corners and edges of the sides nobody photographed: no line
// supports those and no camera faced them. The cameras' half (off by default) keeps the few outer edges a
// clean cloud draws no line along (low contrast between a wall and its roof); in photo clouds it kept the
// edges the networks drew between window corners, which every camera faces (infer/README.md).
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/selection/pair_support.h"
#include "model/scored_wireframe.h"

namespace lc2wf {

struct EdgeSupportOptions {
  // Keep edges whose length the segments cover at least this share of; 0 keeps all (and turns the judge
  // below off). Chosen on photo-like street captures of validation buildings (infer/README.md).
  double min_support = 0.85;
  // Which segment counts, as for pairs (pair_support.h): one rule for "a line runs along it".
  double radius_m = PairSupportOptions{}.radius_m;
  double max_angle_deg = PairSupportOptions{}.max_angle_deg;
  // Or kept when at least this many of the cloud's cameras saw where it is; 0: the lines alone decide.
  int min_cameras = 0;
  double occlusion_tolerance_m = 0.5;  // a point this close behind the building's outer surface is still seen
  // Only where the cloud's cameras leave a side of the building unseen (dataset/photo/camera_coverage.h): a
  // full orbit's wireframe stays as the networks drew it (the rule cost 0.4 sAP on the Roof-Image test split),
  // and a cloud without cameras is not judged. false: every cloud.
  bool partial_captures_only = true;
  // Where the rule above leaves a wireframe alone, the edges of a junction with more than this many edges are
  // still judged, by their lines alone (0: never). A building's corner meets a few edges; where the edge model
  // accepts a near-complete subgraph (tall blocks, dense clutter) one junction meets dozens, most of them
  // running through the building where no line is, and every camera sees the inside of a building's hull.
  // Chosen on validation (infer/README.md, "Over-connected junctions"): no Roof-Image score moves at 8.
  int judge_degree_above = 8;
  double judge_min_support = 0.2;  // the share of line cover those edges need (the rule's share before 2026-12-06)

  bool enabled() const { return min_support > 0; }
  void Check() const;  // throws std::invalid_argument naming the bad field
};

struct SupportedEdges {
  ScoredWireframe wireframe;  // the kept edges, in their order, and the junctions they use
  int dropped_edges = 0;
  int dropped_junctions = 0;
  int kept_by_cameras = 0;  // kept for the cameras alone (too little line support)
};

// Which edges the test judges: every one, or only those of over-connected junctions (judge_degree_above).
enum class JudgedEdges { every_edge, over_connected_only };

// The edges of `in` that pass the test (all of them when the option is off), junctions without an edge dropped.
SupportedEdges keep_supported_edges(const ScoredWireframe& in, const std::vector<Segment3>& segments,
                                    const std::vector<Camera>& cameras, const EdgeSupportOptions& options,
                                    JudgedEdges judged = JudgedEdges::every_edge);

}  // namespace lc2wf

// Building3D-style wireframe metrics (Building3D, ICCV 2023), the family
// recent building-wireframe papers report: corner and edge precision / recall / F1 (CP/CR/CF1, EP/ER/EF1), the
// average corner offset (ACO) and a GT-length-normalised edit distance, named B3D-nWED so it is never read as
// the LC2WF paper's WED.
//
// Calculator variant: Building3D's 2023 calculator (branch `main`) for the counts —
//  1. frame: coordinates centred on the input cloud's centroid and divided by its maximum radius;
//  2. confidence cut: predicted edges with score > 0.7 and the corners they reference;
//  3. corners: Hungarian matching of predicted to GT corners on Euclidean distance; a pair with distance
//     <= 0.1 (normalised) is a corner TP; ACO = mean distance of the TP pairs, in metres;
//  4. edges: a kept predicted edge is a TP when both endpoints are TP corners matched to the two ends of a
//     GT edge;
//  5. CP/CR/CF1 and EP/ER/EF1 from counts pooled over all buildings; ACO pooled over all TP corners.
// B3D-nWED follows the 2024 calculator's graph edit distance, applied to the kept prediction: each kept
// corner moves to its nearest GT corner (cost: the distance), mapped edges that are GT edges remove them,
// other mapped edges cost their mapped length, GT edges never hit cost their length; the sum is divided by
// the building's total GT edge length; mean over buildings with GT edges (empty prediction: 1).
#pragma once

#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "model/scored_wireframe.h"

namespace lc2wf {

// Normalisation frame: normalised = (metres - centroid) / radius.
struct NormalisationFrame {
  Vec3 centroid = Vec3::Zero();
  double radius = 1.0;  // metres; maximum distance of an input point from the centroid
};

// Centroid and maximum radius of `points`; radius 1 (and centroid 0) when there are none or all coincide.
NormalisationFrame frame_of_points(const std::vector<Vec3>& points);
// The frame of a line cloud: its segment endpoints.
NormalisationFrame frame_of_segments(const std::vector<Segment3>& segments);

struct Building3dOptions {
  double distance_threshold = 0.1;    // normalised units (the cloud's radius = 1)
  double confidence_threshold = 0.7;  // predicted edges scoring > this are kept, with their corners

  void Check() const;  // throws std::invalid_argument naming the bad field
};

// One building's counts (what the pooled summary adds up).
struct Building3dCounts {
  int tp_corners = 0, pred_corners = 0, gt_corners = 0;
  double corner_offset_sum = 0.0;  // metres, summed over the TP corner pairs
  int tp_edges = 0, pred_edges = 0, gt_edges = 0;
  double nwed = 0.0;          // B3D-nWED of this building (0 when it has no GT edge)
  bool has_gt_edges = false;  // whether nwed enters the mean
  double frame_radius = 1.0;  // metres
};

Building3dCounts building3d_counts(const ScoredWireframe& pred, const Wireframe& gt, const NormalisationFrame& frame,
                                   const Building3dOptions& options = {});

struct Building3dSummary {
  Building3dOptions options;
  std::string frame_source;  // what the frame was computed from (e.g. "line-cloud segment endpoints")
  int buildings = 0;
  Building3dCounts totals;  // summed counts (nwed: sum over buildings with GT edges)
  double cp = 0, cr = 0, cf1 = 0, ep = 0, er = 0, ef1 = 0;  // in [0, 1]; 0 when undefined
  double aco = 0;            // metres; 0 without TP corners
  double nwed_mean = 0;      // over buildings with GT edges
  double mean_radius = 0;    // metres: the threshold in metres is distance_threshold * radius per building
};

Building3dSummary summarize_building3d(const std::vector<Building3dCounts>& per_building, const Building3dOptions& options,
                                       const std::string& frame_source);

}  // namespace lc2wf

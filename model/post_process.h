// Inference post-processing: from the edge model's pair probabilities over the selected junctions
// (dataset/selection/junction_selection.h) to the final wireframe, as the release's post-processing. Everything is in metres. No input
// makes these functions crash: degenerate cases (no candidates, < 2 junctions, no identical pair, no
// candidate edge) give a valid, possibly empty, result and a note saying what happened.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "model/post_process_options.h"
#include "model/scored_wireframe.h"

namespace lc2wf {

// All index pairs (i < j) of n junctions in lexicographic order: the order of selection_pairs().
std::vector<std::array<int, 2>> all_pairs(int n);

// Edge-model output for one pair of selected junctions.
struct PairPrediction {
  int i = 0;
  int j = 0;
  double merge = 0.0;    // P(identical), class 0
  double connect = 0.0;  // P(connected), class 1
};

struct PostProcessInput {
  std::vector<Vec3> junctions;        // selected junctions (usually JunctionSelection::positions)
  std::vector<double> confidences;    // their confidences
  std::vector<PairPrediction> pairs;  // distinct unordered pairs (usually selection_pairs order)
};

// How many junctions/edges each step removed (diagnostics and tests).
struct PostProcessStats {
  int pruned_junctions = 0;    // identical-pair pruning
  int candidate_edges = 0;     // connect > threshold, after pruning
  int isolated_edges = 0;      // removed: both endpoints of degree 1
  int merged_junctions = 0;    // Hamming merge
  int transferred_edges = 0;   // edges moved onto a surviving junction (sound rule)
  int merge_removed_edges = 0; // edges deleted by the merge (release rule, or duplicates/degenerate after transfer)
  int line_nms_edges = 0;      // removed by line NMS
  int crossing_edges = 0;      // removed: crossed a higher-scoring edge
  int dangling_edges = 0;      // removed: an endpoint of degree 1
};

struct PostProcessResult {
  // Final wireframe: junctions referenced by the remaining edges (first appearance over the edge list),
  // edges by ascending score (the release's order), junction scores = confidences, edge scores = P(connected).
  ScoredWireframe wireframe;
  ScoredWireframe candidates;  // the candidate edges of step 3, before any clean-up ("before process")
  PostProcessStats stats;
  std::vector<std::string> notes;  // degenerate cases met on the way
};

// Identical-pair pruning, candidate edges, isolated-edge removal, Hamming junction merge, line NMS, crossing
// edges and dangling-edge removal. Throws std::invalid_argument on malformed input (bad indices, repeated pairs,
// probabilities outside [0, 1]).
PostProcessResult post_process(const PostProcessInput& input, const PostProcessOptions& options);

}  // namespace lc2wf

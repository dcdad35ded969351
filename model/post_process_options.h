// Constants and rule choices of the inference post-processing (the release's defaults, in metres).
// Defaults are the release's constants with the sound rule wherever the release has a quirk;
// release_quirks() reproduces the release's behaviour exactly.
#pragma once

#include "dataset/selection/junction_selection.h"
#include "dataset/selection/pair_cap.h"
#include "dataset/selection/pair_support.h"
#include "dataset/geometry/segment_split.h"
#include "model/edge_support.h"
#include "model/flat_parts.h"

namespace lc2wf {

struct PostProcessOptions {
  // Not in the release: segments longer than this are cut into two staggered chains of pieces before
  // inference (dataset/geometry/segment_split.h), for line maps with one line per edge stretch (Line3D++, LIMAP);
  // 0 = never. With merged_maps_only, only clouds read from such a map (LineCloud::external_line_map) whose
  // long lines are rarely overlapped (overlapped_long_fraction below kMergedMapOverlap) are cut: our clouds,
  // the release's and other programs' maps of per-view fragments pass unchanged.
  double max_segment_length_m = kMergedMapPieceLength;
  bool merged_maps_only = true;
  // A cut cloud's junction model runs on at least this many sampling passes: at a corner of a cut map meet
  // two chains' endpoints per edge, not one per view, so the density seeds find 78 % of the GT junctions
  // (our clouds 94 %); chosen on validation (reconstruct/README.md, "Sampling a cut map").
  int cut_sampling_passes = 3;
  // Junction selection before pairing: the rule training uses too (dataset/selection/junction_selection.h).
  JunctionSelectionOptions selection;
  // Which pairs of the selection the edge model classifies: all of them unless min_support > 0
  // (dataset/selection/pair_support.h); a skipped pair is no edge and no identical pair.
  PairSupportOptions pair_support;
  // Not in the release (every pair): above pair_cap.max_pairs, the pairs with the most line support near their
  // junctions, at most max_pairs_per_junction per junction (dataset/selection/pair_cap.h), so a cluttered map's
  // hundreds of junction candidates cannot make the edge model's time explode.
  PairCapOptions pair_cap;
  // Not in the release (one view): each pair's class probabilities are the edge model's mean over this many
  // views of the building's pairs (1, 2, 4 or 8; model/test_time_symmetry.h), at views x its time.
  int edge_test_time_views = 1;

  // Identical-pair pruning (post-processing step 2): P(identical) > merge_threshold marks the less confident junction.
  double merge_threshold = 0.2;
  // Release true: a junction already marked by an earlier pair still marks its partner, so a chain
  // A ~ B ~ C deletes C through the deleted B; false skips pairs whose survivor is already deleted.
  bool prune_through_deleted = false;

  // Candidate edges (step 3): P(connected) > connect_threshold; the probability is the edge score.
  double connect_threshold = 0.3;

  // Hamming junction merge (step 6): junctions whose adjacency rows differ in < hamming_threshold
  // entries and that are closer than junction_merge_distance collapse onto the more confident one.
  int hamming_threshold = 3;
  double junction_merge_distance = 1.5;  // metres (release: 30 raw)
  bool transfer_edges_on_merge = true;   // release false: the dropped junction's edges are deleted
  // Release true: junctions deleted by identical-pair pruning still take part (as rows without edges) and
  // can absorb a nearby junction of degree < hamming_threshold.
  bool pruned_junctions_in_merge = false;

  // Line NMS (step 7): edges whose summed endpoint distance (best orientation) is < line_nms_distance.
  double line_nms_distance = 1.0;    // metres (release: 20 raw)
  bool line_nms_keep_higher = true;  // release false: edges are visited by ascending score, so the lower one stays

  // Not in the release (keeps both): of two edges that cross - closest points within crossing_distance_m of
  // each other and at least crossing_end_margin_m from every end (dataset/geometry/segment_crossing.h) - the
  // lower-scoring one is dropped, since a building's edges meet only at junctions. 0 = off; 0.25 chosen on
  // validation (infer/README.md, "Crossing edges").
  double crossing_distance_m = 0.25;
  double crossing_end_margin_m = 0.3;

  // Not in the release (keeps every edge): after the clean-up, edges the cloud's lines do not run along are
  // dropped, with the junctions left without an edge (model/edge_support.h): nothing on unphotographed sides.
  EdgeSupportOptions edge_support;
  // Not in the release: then the small flat parts other than the largest go (model/flat_parts.h); off here,
  // on in lc2wf-reconstruct.
  FlatPartOptions flat_parts;

  void Check() const;  // throws std::invalid_argument naming the bad field
  static PostProcessOptions release_quirks();
};

}  // namespace lc2wf

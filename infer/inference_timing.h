// What a batch of inferences cost, per stage: kept apart from the networks so that the metrics' output
// (infer/eval_report_io.h) can report it without depending on them.
#pragma once

#include <cstdint>
#include <string>

#include "model/post_process_options.h"

namespace lc2wf {

struct InferenceTiming {
  int buildings = 0;        // predicted (possibly empty wireframes)
  int empty = 0;            // no edge in the final wireframe
  int cut = 0;              // clouds whose long segments were cut first (InferenceResult::segments_cut)
  double total_seconds = 0; // networks + post-processing, excluding file I/O
  double max_seconds = 0;
  double junction_seconds = 0, edge_seconds = 0, post_seconds = 0;
  int64_t pairs = 0;        // junction pairs the edge model classified, all buildings
  int threads = 1;          // compute threads the networks ran on
  std::string precision = "fp32";  // the networks' matrix-product operands (fp32 or bf16)
  double pair_support = 0;  // PairSupportOptions::min_support: 0 = every pair of junctions was classified
  // The junction selection the scores depend on, so a metrics file says how it was made.
  double min_confidence = JunctionSelectionOptions{}.min_confidence, nms_radius_m = JunctionSelectionOptions{}.nms_radius_m;
  double max_offset_m = JunctionSelectionOptions{}.max_offset_m;  // infinity: every candidate
  double corner_radius_m = JunctionSelectionOptions{}.corner.radius_m;  // 0: every junction paired
  double footing_radius_m = JunctionSelectionOptions{}.footing.radius_m;  // 0: every ground junction paired
  int sampling_passes = JunctionSelectionOptions{}.sampling_passes;
  int test_time_views = JunctionSelectionOptions{}.test_time_views;
  std::string density_seeds = JunctionSelectionOptions{}.density_seeds.str();
  int edge_test_time_views = 1;  // PostProcessOptions::edge_test_time_views
  double max_segment_length_m = 0;  // PostProcessOptions::max_segment_length_m: 0 = the clouds as they are
  bool merged_maps_only = false;    // PostProcessOptions::merged_maps_only
  int cut_sampling_passes = 1;      // PostProcessOptions::cut_sampling_passes

  void record_selection(const PostProcessOptions& o) {
    const JunctionSelectionOptions& s = o.selection;
    pair_support = o.pair_support.min_support;
    min_confidence = s.min_confidence;
    nms_radius_m = s.nms_radius_m;
    max_offset_m = s.max_offset_m;
    corner_radius_m = s.corner.radius_m;
    footing_radius_m = s.footing.radius_m;
    sampling_passes = s.sampling_passes;
    test_time_views = s.test_time_views;
    density_seeds = s.density_seeds.str();
    edge_test_time_views = o.edge_test_time_views;
    max_segment_length_m = o.max_segment_length_m;
    merged_maps_only = o.merged_maps_only;
    cut_sampling_passes = o.cut_sampling_passes;
  }
};

}  // namespace lc2wf

#include "model/post_process_options.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lc2wf {
namespace {

void require(bool ok, const char* field, const std::string& rule, double value) {
  if (!ok)
    throw std::invalid_argument(std::string("PostProcessOptions.") + field + " must be " + rule + ", got " +
                                std::to_string(value));
}

bool probability(double p) { return std::isfinite(p) && p >= 0.0 && p <= 1.0; }

}  // namespace

void PostProcessOptions::Check() const {
  selection.Check();
  pair_support.Check();
  pair_cap.Check();
  edge_support.Check();
  flat_parts.Check();
  require(max_segment_length_m == 0.0 || (max_segment_length_m >= 0.05 && max_segment_length_m <= 100.0),
          "max_segment_length_m", "0 (off) or in [0.05, 100] metres", max_segment_length_m);
  require(cut_sampling_passes >= 1 && cut_sampling_passes <= 8, "cut_sampling_passes", "in [1, 8]", cut_sampling_passes);
  require(JunctionSelectionOptions::valid_view_count(edge_test_time_views), "edge_test_time_views", "1, 2, 4 or 8",
          edge_test_time_views);
  require(probability(merge_threshold), "merge_threshold", "in [0, 1]", merge_threshold);
  require(probability(connect_threshold), "connect_threshold", "in [0, 1]", connect_threshold);
  require(hamming_threshold >= 0, "hamming_threshold", ">= 0", hamming_threshold);
  require(std::isfinite(junction_merge_distance) && junction_merge_distance >= 0.0, "junction_merge_distance",
          ">= 0 metres", junction_merge_distance);
  require(std::isfinite(line_nms_distance) && line_nms_distance >= 0.0, "line_nms_distance", ">= 0 metres",
          line_nms_distance);
  require(std::isfinite(crossing_distance_m) && crossing_distance_m >= 0.0 && crossing_distance_m <= 10.0,
          "crossing_distance_m", "in [0, 10] metres (0 = off)", crossing_distance_m);
  require(std::isfinite(crossing_end_margin_m) && crossing_end_margin_m >= 0.0 && crossing_end_margin_m <= 10.0,
          "crossing_end_margin_m", "in [0, 10] metres", crossing_end_margin_m);
  if (transfer_edges_on_merge && pruned_junctions_in_merge)
    throw std::invalid_argument(
        "PostProcessOptions.pruned_junctions_in_merge cannot be combined with transfer_edges_on_merge: edges would "
        "move onto junctions deleted by identical-pair pruning");
}

PostProcessOptions PostProcessOptions::release_quirks() {
  PostProcessOptions o;
  o.selection = JunctionSelectionOptions::release();
  o.prune_through_deleted = true;
  o.transfer_edges_on_merge = false;
  o.pruned_junctions_in_merge = true;
  o.line_nms_keep_higher = false;
  o.crossing_distance_m = 0.0;  // the release keeps crossing edges
  o.max_segment_length_m = 0.0;  // the release runs on the cloud as it is
  o.edge_support.min_support = 0.0;  // the release keeps every edge the post-processing leaves
  o.edge_support.min_cameras = 0;
  return o;
}

}  // namespace lc2wf

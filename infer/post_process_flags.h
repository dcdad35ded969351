// The post-processing flags every inference command shares (lc2wf-infer, lc2wf-eval --weights,
// lc2wf-reconstruct): read in any order, turned into PostProcessOptions once the whole command line is
// read (so --release-quirks never undoes a flag written before it).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>

#include "core/util/cli.h"
#include "model/post_process_options.h"

namespace lc2wf {

struct PostProcessFlags {
  bool release_quirks = false;              // --release-quirks
  bool no_junction_refine = false;          // --no-junction-refine
  std::optional<double> min_confidence;     // --min-confidence C
  std::optional<double> pair_support;       // --pair-support S
  std::optional<double> edge_support;       // --edge-support S
  bool edge_support_everywhere = false;     // --edge-support-everywhere
  std::optional<int64_t> judge_degree;      // --judge-degree-above N
  std::optional<int64_t> edge_cameras;      // --edge-cameras N
  std::optional<int64_t> flat_parts;        // --drop-flat-parts N
  std::optional<double> nms_radius;         // --nms-radius M
  std::optional<double> max_offset;         // --max-offset M
  std::optional<double> corner_radius;      // --corner-radius M
  std::optional<double> footing_radius;     // --footing-radius M
  std::optional<int64_t> sampling_passes;   // --sampling-passes N
  std::optional<double> metres_per_pass;    // --metres-per-pass M
  std::optional<std::string> density_seeds; // --density-seeds release|loose|A,C,R
  std::optional<int64_t> test_time_views;   // --test-time-views N
  std::optional<int64_t> edge_test_time_views;   // --edge-test-time-views N
  std::optional<double> max_segment_length;      // --max-segment-length M (a number: every cloud)
  bool max_segment_length_auto = false;          // --max-segment-length auto
  std::optional<int64_t> max_pairs;              // --max-pairs N
  std::optional<int64_t> max_pairs_per_junction; // --max-pairs-per-junction N
  std::optional<double> crossing_distance;       // --crossing-distance M

  bool any() const {
    return release_quirks || no_junction_refine || min_confidence || pair_support || edge_support || edge_support_everywhere || judge_degree || edge_cameras || flat_parts || nms_radius || max_offset || corner_radius || footing_radius || sampling_passes || metres_per_pass ||
           density_seeds || test_time_views || edge_test_time_views || max_segment_length || max_segment_length_auto ||
           max_pairs || max_pairs_per_junction || crossing_distance;
  }

  // Consumes argv[i] (and its value) when it is one of these flags.
  bool parse(const std::string& flag, int argc, char** argv, int& i) {
    if (flag == "--release-quirks") release_quirks = true;
    else if (flag == "--no-junction-refine") no_junction_refine = true;
    else if (flag == "--min-confidence") min_confidence = number_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--pair-support") pair_support = number_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--edge-support") edge_support = number_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--edge-support-everywhere") edge_support_everywhere = true;
    else if (flag == "--judge-degree-above") judge_degree = parse_count_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--edge-cameras") edge_cameras = parse_count_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--drop-flat-parts") flat_parts = parse_count_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--nms-radius") nms_radius = number_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--max-offset") max_offset = number_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--corner-radius") corner_radius = number_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--footing-radius") footing_radius = number_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--sampling-passes") sampling_passes = parse_count_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--metres-per-pass") metres_per_pass = number_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--density-seeds") density_seeds = flag_value(argc, argv, i);
    else if (flag == "--test-time-views") test_time_views = parse_count_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--edge-test-time-views") edge_test_time_views = parse_count_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--max-pairs") max_pairs = int_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--max-pairs-per-junction") max_pairs_per_junction = int_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--crossing-distance") crossing_distance = number_flag(flag, flag_value(argc, argv, i));
    else if (flag == "--max-segment-length") {
      const std::string value = flag_value(argc, argv, i);
      max_segment_length_auto = value == "auto";
      max_segment_length.reset();
      if (!max_segment_length_auto) max_segment_length = number_flag(flag, value);
    }
    else return false;
    return true;
  }

  // The options asked for over a command's own defaults (lc2wf-reconstruct's differ for photo clouds); a value
  // out of range is a usage error naming its flag.
  PostProcessOptions options(const PostProcessOptions& defaults = {}) const {
    PostProcessOptions o = release_quirks ? PostProcessOptions::release_quirks() : defaults;
    if (no_junction_refine) o.selection.refine.radius = 0.0;
    if (min_confidence) o.selection.min_confidence = *min_confidence;
    if (pair_support) o.pair_support.min_support = *pair_support;
    if (edge_support) o.edge_support.min_support = *edge_support;
    if (edge_support_everywhere) o.edge_support.partial_captures_only = false;
    if (judge_degree) o.edge_support.judge_degree_above = static_cast<int>(std::min<int64_t>(*judge_degree, 1 << 30));
    if (edge_cameras) o.edge_support.min_cameras = static_cast<int>(std::min<int64_t>(*edge_cameras, 1 << 30));
    if (flat_parts) o.flat_parts.max_edges = static_cast<int>(std::min<int64_t>(*flat_parts, 1 << 30));
    if (nms_radius) o.selection.nms_radius_m = *nms_radius;
    // --max-offset 0 (or less): every candidate, as the release (the config's edge.max_offset_m <= 0 too).
    if (max_offset) o.selection.max_offset_m = JunctionSelectionOptions::offset_limit(*max_offset);
    if (corner_radius) o.selection.corner.radius_m = *corner_radius;
    if (footing_radius) o.selection.footing.radius_m = *footing_radius;
    if (sampling_passes) o.selection.sampling_passes = static_cast<int>(std::min<int64_t>(*sampling_passes, 1000));
    if (metres_per_pass) o.selection.metres_per_pass = *metres_per_pass;
    if (density_seeds) {
      try {
        o.selection.density_seeds = DensitySeedRule::parse(*density_seeds);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--density-seeds: ") + e.what());
      }
    }
    if (test_time_views) o.selection.test_time_views = static_cast<int>(std::min<int64_t>(*test_time_views, 1000));
    if (edge_test_time_views) o.edge_test_time_views = static_cast<int>(std::min<int64_t>(*edge_test_time_views, 1000));
    if (max_segment_length_auto) {
      o.max_segment_length_m = kMergedMapPieceLength;
      o.merged_maps_only = true;
    }
    if (max_segment_length) o.max_segment_length_m = *max_segment_length, o.merged_maps_only = false;
    if (max_pairs) o.pair_cap.max_pairs = static_cast<int>(std::clamp<int64_t>(*max_pairs, -1, 1 << 30));
    if (max_pairs_per_junction)
      o.pair_cap.max_pairs_per_junction = static_cast<int>(std::clamp<int64_t>(*max_pairs_per_junction, -1, 1 << 30));
    if (crossing_distance) o.crossing_distance_m = *crossing_distance;
    check_options([&] { o.Check(); }, {{"PostProcessOptions.crossing_distance_m", "--crossing-distance"},
                                       {"JunctionSelectionOptions.min_confidence", "--min-confidence"},
                                       {"PairSupportOptions.min_support", "--pair-support"},
                                       {"EdgeSupportOptions.min_support", "--edge-support"},
                                       {"FlatPartOptions.max_edges", "--drop-flat-parts"},
                                       {"JunctionSelectionOptions.nms_radius_m", "--nms-radius"},
                                       {"JunctionSelectionOptions.max_offset_m", "--max-offset"},
                                       {"CornerEvidenceOptions.radius_m", "--corner-radius"},
                                       {"FootingEvidenceOptions.radius_m", "--footing-radius"},
                                       {"JunctionSelectionOptions.sampling_passes", "--sampling-passes"},
                                       {"JunctionSelectionOptions.metres_per_pass", "--metres-per-pass"},
                                       {"JunctionSelectionOptions.test_time_views", "--test-time-views"},
                                       {"PostProcessOptions.edge_test_time_views", "--edge-test-time-views"},
                                       {"PostProcessOptions.max_segment_length_m", "--max-segment-length"},
                                       {"PairCapOptions.max_pairs_per_junction", "--max-pairs-per-junction"},
                                       {"PairCapOptions.max_pairs", "--max-pairs"}});
    return o;
  }
};

}  // namespace lc2wf

#include "infer/building3d_io.h"

#include <cstdio>

#include "core/util/number_format.h"

namespace lc2wf {
namespace {

std::string pct(double v) { return format_number("%.1f", 100 * v); }

nlohmann::json counts_json(const Building3dCounts& c) {
  return {{"tp_corners", c.tp_corners}, {"pred_corners", c.pred_corners}, {"gt_corners", c.gt_corners},
          {"corner_offset_sum_m", c.corner_offset_sum}, {"tp_edges", c.tp_edges}, {"pred_edges", c.pred_edges},
          {"gt_edges", c.gt_edges}, {"nwed", c.nwed}, {"has_gt_edges", c.has_gt_edges},
          {"frame_radius_m", c.frame_radius}};
}

}  // namespace

std::string building3d_markdown(const Building3dReport& r, const std::string& method) {
  const Building3dSummary& s = r.summary;
  std::string md = "\n## (c) Building3D-style metrics (not the paper's; comparable in kind, not in value)\n\n";
  md += "| method | CP | CR | CF1 | EP | ER | EF1 | ACO (m) | B3D-nWED |\n|---|---|---|---|---|---|---|---|---|\n";
  md += "| " + method + " | " + pct(s.cp) + " | " + pct(s.cr) + " | " + pct(s.cf1) + " | " + pct(s.ep) + " | " +
        pct(s.er) + " | " + pct(s.ef1) + " | " + format_number("%.3f", s.aco) + " | " + format_number("%.3f", s.nwed_mean) + " |\n\n";
  md += "Frame: centred on the " + s.frame_source + " centroid, divided by its maximum radius (mean " +
        format_number("%.2f", s.mean_radius) + " m). Threshold: " + format_number("%g", s.options.distance_threshold) +
        " normalised (≈ " + format_number("%.2f", s.options.distance_threshold * s.mean_radius) +
        " m at the mean radius). Confidence cut: predicted edges with score > " +
        format_number("%g", s.options.confidence_threshold) +
        " and their corners. Variant: Building3D 2023 calculator (Hungarian corner matching; an edge is a TP when "
        "both ends match the ends of a GT edge), counts pooled over buildings; ACO over all TP corners, in metres. "
        "B3D-nWED: the 2024 calculator's edit distance (corner moves + spurious and missed edge lengths) over the "
        "GT edge length, mean over buildings — a different quantity from the paper's WED in (b).\n";
  return md;
}

nlohmann::json building3d_json(const Building3dReport& r) {
  const Building3dSummary& s = r.summary;
  nlohmann::json j = {
      {"variant", "building3d-2023 counts, building3d-2024 normalised WED"},
      {"frame", s.frame_source + " centroid, divided by the maximum radius"},
      {"distance_threshold", s.options.distance_threshold},
      {"confidence_threshold", s.options.confidence_threshold},
      {"mean_frame_radius_m", s.mean_radius},
      {"buildings", s.buildings},
      {"cp", s.cp}, {"cr", s.cr}, {"cf1", s.cf1},
      {"ep", s.ep}, {"er", s.er}, {"ef1", s.ef1},
      {"aco_m", s.aco}, {"nwed", s.nwed_mean},
      {"totals", counts_json(s.totals)}};
  j["per_building"] = nlohmann::json::array();
  for (size_t k = 0; k < r.per_building.size(); ++k) {
    nlohmann::json x = counts_json(r.per_building[k]);
    x["name"] = k < r.names.size() ? r.names[k] : "";
    j["per_building"].push_back(std::move(x));
  }
  return j;
}

}  // namespace lc2wf

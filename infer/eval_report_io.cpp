#include "infer/eval_report_io.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>

#include "core/util/atomic_file.h"
#include "core/util/json_text.h"
#include "core/util/number_format.h"
#include "core/util/version_json.h"

namespace lc2wf {
namespace {


// Table 2b style: 0.766, 1.810, 11.49, 124.8.
std::string wed_number(double v) {
  const double a = std::fabs(v);
  return format_number(a < 10 ? "%.3f" : a < 100 ? "%.2f" : "%.1f", v);
}

std::string pct_pair(double ap, double recall) { return format_number("%.1f", 100 * ap) + "/" + format_number("%.1f", 100 * recall); }

std::string eta(double metres) { return format_number("%.2f", metres); }

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

nlohmann::json wed_json(const WedResult& w) {
  return {{"gt_vertices", w.gt_vertices},   {"gt_edges", w.gt_edges},
          {"pred_vertices", w.pred_vertices}, {"pred_edges", w.pred_edges},
          {"move", w.move},                 {"add_vertex", w.add_vertex},
          {"del_vertex", w.del_vertex},     {"add_edge", w.add_edge},
          {"add_edge_length", w.add_edge_length}, {"del_edge", w.del_edge},
          {"del_edge_length", w.del_edge_length}, {"total_num", w.total_num()},
          {"total_dist", w.total_dist()}};
}

nlohmann::json wed_mean_json(const WedMean& w) {
  return {{"add_vertex", w.add_vertex}, {"del_vertex", w.del_vertex}, {"add_edge", w.add_edge},
          {"del_edge", w.del_edge},     {"total_num", w.total_num},   {"move", w.move},
          {"add_edge_length", w.add_edge_length}, {"del_edge_length", w.del_edge_length},
          {"total_dist", w.total_dist}};
}

nlohmann::json ap_json(const ApSummary& s, double raw_per_metre) {
  return {{"threshold_m", s.threshold},   {"threshold_raw", s.threshold * raw_per_metre},
          {"ap", s.ap},                   {"recall", s.recall},
          {"true_positives", s.true_positives}, {"predictions", s.predictions},
          {"ground_truth", s.ground_truth}};
}

std::string wed_cell(double num, double dist) { return wed_number(num) + " / " + wed_number(dist); }

}  // namespace

std::string eval_markdown(const EvalReport& r, const std::string& method) {
  const auto missing = r.missing_predictions();
  std::string s = "# Evaluation: " + method + "\n\n";
  s += std::to_string(r.buildings.size()) + " buildings";
  if (!missing.empty()) s += " (" + std::to_string(missing.size()) + " without a prediction, scored as empty)";
  s += ". Distances in metres; thresholds η in metres (release raw units = η × " + format_number("%g", r.options.raw_per_metre) +
       ").\n\n";

  s += "## (a) vAP / vRecall and sAP / sRecall (%)\n\n| method |";
  for (const auto& v : r.vertex) s += " v η=" + eta(v.threshold) + " |";
  s += " v avg. |";
  for (const auto& e : r.edge) s += " s η=" + eta(e.threshold) + " |";
  s += " s avg. |\n|---|";
  for (size_t k = 0; k < r.vertex.size() + r.edge.size() + 2; ++k) s += "---|";
  s += "\n| " + method + " |";
  for (const auto& v : r.vertex) s += " " + pct_pair(v.ap, v.recall) + " |";
  s += " " + pct_pair(r.vertex_ap_mean, r.vertex_recall_mean) + " |";
  for (const auto& e : r.edge) s += " " + pct_pair(e.ap, e.recall) + " |";
  s += " " + pct_pair(r.edge_ap_mean, r.edge_recall_mean) + " |\n\n";

  s += "## (b) WED, mean per building (Num / Dist m)\n\n";
  s += "| method | +vertex | +edge | −edge | total |\n|---|---|---|---|---|\n";
  s += "| " + method + " | " + wed_cell(r.wed.add_vertex, r.wed.move) + " | " +
       wed_cell(r.wed.add_edge, r.wed.add_edge_length) + " | " + wed_cell(r.wed.del_edge, r.wed.del_edge_length) +
       " | " + wed_cell(r.wed.total_num, r.wed.total_dist) + " |\n\n";
  s += "Release WED: \"+vertex Dist\" is the move cost Σ sqrt(raw distance)/" + format_number("%g", r.options.raw_per_metre) +
       "; spurious edges and extra vertices are free.\n";
  if (r.options.strict_wed) {
    const WedMean& w = r.wed_strict;
    s += "\n## (b') Strict WED, mean per building (Num / Dist m)\n\n";
    s += "| method | +vertex (move) | −vertex | +edge | −edge | total |\n|---|---|---|---|---|---|\n";
    s += "| " + method + " | " + wed_cell(w.add_vertex, w.move) + " | " + wed_number(w.del_vertex) + " | " +
         wed_cell(w.add_edge, w.add_edge_length) + " | " + wed_cell(w.del_edge, w.del_edge_length) + " | " +
         wed_cell(w.total_num, w.total_dist) + " |\n\n";
    s += "Strict WED: moves cost the Euclidean distance; extra vertices and every non-GT, duplicate or degenerate "
         "edge are charged.\n";
  }
  if (!missing.empty()) {
    s += "\nBuildings without a prediction:";
    const size_t shown = std::min<size_t>(missing.size(), 20);
    for (size_t k = 0; k < shown; ++k) s += " " + missing[k];
    if (shown < missing.size()) s += " … (" + std::to_string(missing.size() - shown) + " more in metrics.json)";
    s += "\n";
  }
  return s;
}

nlohmann::json eval_json(const EvalReport& r, const std::string& method) {
  const EvalOptions& o = r.options;
  nlohmann::json j;
  j["method"] = method;
  add_version_fields(j);
  j["buildings"] = r.buildings.size();
  j["missing_predictions"] = r.missing_predictions();
  j["options"] = {{"vertex_thresholds_m", o.vertex_thresholds},
                  {"edge_thresholds_m", o.edge_thresholds},
                  {"min_score", o.min_score},
                  {"ties", o.ties == ApTieRule::kGroupTies ? "group" : "list_order"},
                  {"raw_per_metre", o.raw_per_metre},
                  {"strict_wed", o.strict_wed}};
  j["vertex"] = nlohmann::json::array();
  for (const auto& v : r.vertex) j["vertex"].push_back(ap_json(v, o.raw_per_metre));
  j["vertex_avg"] = {{"ap", r.vertex_ap_mean}, {"recall", r.vertex_recall_mean}};
  j["edge"] = nlohmann::json::array();
  for (const auto& e : r.edge) j["edge"].push_back(ap_json(e, o.raw_per_metre));
  j["edge_avg"] = {{"ap", r.edge_ap_mean}, {"recall", r.edge_recall_mean}};
  j["wed"] = wed_mean_json(r.wed);
  if (o.strict_wed) j["wed_strict"] = wed_mean_json(r.wed_strict);
  j["per_building"] = nlohmann::json::array();
  for (const auto& b : r.buildings) {
    nlohmann::json x = {{"name", b.name},
                        {"prediction_missing", b.prediction_missing},
                        {"gt_vertices", b.gt_vertices},
                        {"gt_edges", b.gt_edges},
                        {"pred_vertices", b.pred_vertices},
                        {"pred_edges", b.pred_edges},
                        {"vertex_tp", b.vertex_tp},
                        {"edge_tp", b.edge_tp},
                        {"wed", wed_json(b.wed)}};
    if (o.strict_wed) x["wed_strict"] = wed_json(b.wed_strict);
    j["per_building"].push_back(std::move(x));
  }
  return j;
}

std::string eval_per_building_csv(const EvalReport& r) {
  const bool strict = r.options.strict_wed;
  std::string s = "name,prediction_missing,gt_vertices,gt_edges,pred_vertices,pred_edges";
  for (double t : r.options.vertex_thresholds) s += ",vertex_tp@" + eta(t);
  for (double t : r.options.edge_thresholds) s += ",edge_tp@" + eta(t);
  s += ",wed_add_vertex,wed_move,wed_add_edge,wed_add_edge_length,wed_del_edge,wed_del_edge_length,wed_total_num,"
       "wed_total_dist";
  if (strict)
    s += ",strict_add_vertex,strict_del_vertex,strict_move,strict_add_edge,strict_add_edge_length,strict_del_edge,"
         "strict_del_edge_length,strict_total_num,strict_total_dist";
  s += "\n";
  auto num = [](double v) { return format_number("%.9g", v); };
  for (const auto& b : r.buildings) {
    s += csv_field(b.name) + "," + (b.prediction_missing ? "1" : "0") + "," + std::to_string(b.gt_vertices) + "," +
         std::to_string(b.gt_edges) + "," + std::to_string(b.pred_vertices) + "," + std::to_string(b.pred_edges);
    for (int tp : b.vertex_tp) s += "," + std::to_string(tp);
    for (int tp : b.edge_tp) s += "," + std::to_string(tp);
    const WedResult& w = b.wed;
    s += "," + std::to_string(w.add_vertex) + "," + num(w.move) + "," + std::to_string(w.add_edge) + "," +
         num(w.add_edge_length) + "," + std::to_string(w.del_edge) + "," + num(w.del_edge_length) + "," +
         std::to_string(w.total_num()) + "," + num(w.total_dist());
    if (strict) {
      const WedResult& x = b.wed_strict;
      s += "," + std::to_string(x.add_vertex) + "," + std::to_string(x.del_vertex) + "," + num(x.move) + "," +
           std::to_string(x.add_edge) + "," + num(x.add_edge_length) + "," + std::to_string(x.del_edge) + "," +
           num(x.del_edge_length) + "," + std::to_string(x.total_num()) + "," + num(x.total_dist());
    }
    s += "\n";
  }
  return s;
}

std::string inference_markdown(const InferenceTiming& s) {
  const double n = std::max(1, s.buildings);
  const std::string support = s.pair_support > 0 ? " (pairs with line support >= " + format_number("%g", s.pair_support) + ")" : "";
  // The screens after the NMS: the offset limit and the corner check.
  std::string screens = std::isfinite(s.max_offset_m) ? ", offsets <= " + format_number("%g", s.max_offset_m) + " m" : "";
  if (s.corner_radius_m > 0) screens += ", two line directions ending within " + format_number("%g", s.corner_radius_m) + " m";
  if (s.footing_radius_m > 0)
    screens += ", ground junctions with lines above within " + format_number("%g", s.footing_radius_m) + " m";
  // The options that differ from a one-pass, one-view, uncut run, in the order of the pipeline.
  std::string passes;
  if (s.sampling_passes > 1) passes += ", " + std::to_string(s.sampling_passes) + " sampling passes";
  if (s.density_seeds != JunctionSelectionOptions{}.density_seeds.str()) passes += ", " + s.density_seeds + " density seeds";
  if (s.test_time_views > 1) passes += ", " + std::to_string(s.test_time_views) + " test-time views";
  if (s.edge_test_time_views > 1) passes += ", " + std::to_string(s.edge_test_time_views) + " edge views";
  if (s.max_segment_length_m > 0) {
    passes += ", segments cut at " + format_number("%g", s.max_segment_length_m) + " m";
    if (s.merged_maps_only) passes += " in merged line maps";
    passes += " (" + std::to_string(s.cut) + " of " + std::to_string(s.buildings) + " clouds cut";
    if (s.cut_sampling_passes > s.sampling_passes)
      passes += ", sampled in " + std::to_string(s.cut_sampling_passes) + " passes";
    passes += ")";
  }
  char line[1024];
  std::snprintf(line, sizeof line,
                "\nInference (%d buildings, %d threads, %s products): %.3f s per building on average (junction model %.3f, edge model "
                "%.3f, selection and post-processing %.3f; max %.3f), %.1f classified pairs per building%s; junctions with "
                "confidence > %g after NMS %g m%s%s.\n",
                s.buildings, s.threads, s.precision.c_str(), s.total_seconds / n, s.junction_seconds / n, s.edge_seconds / n, s.post_seconds / n,
                s.max_seconds, static_cast<double>(s.pairs) / n, support.c_str(), s.min_confidence, s.nms_radius_m, screens.c_str(), passes.c_str());
  return line;
}

nlohmann::json inference_json(const InferenceTiming& s) {
  const double n = std::max(1, s.buildings);
  return {{"buildings", s.buildings},
          {"threads", s.threads},
          {"precision", s.precision},
          {"seconds_per_building", s.total_seconds / n},
          {"junction_seconds_per_building", s.junction_seconds / n},
          {"edge_seconds_per_building", s.edge_seconds / n},
          {"post_seconds_per_building", s.post_seconds / n},
          {"max_seconds", s.max_seconds},
          {"pairs_per_building", static_cast<double>(s.pairs) / n},
          {"pair_support", s.pair_support},
          {"min_confidence", s.min_confidence},
          {"nms_radius_m", s.nms_radius_m},
          {"max_offset_m", std::isfinite(s.max_offset_m) ? nlohmann::json(s.max_offset_m) : nlohmann::json(nullptr)},
          {"corner_radius_m", s.corner_radius_m},
          {"footing_radius_m", s.footing_radius_m},
          {"sampling_passes", s.sampling_passes},
          {"test_time_views", s.test_time_views},
          {"density_seeds", s.density_seeds},
          {"edge_test_time_views", s.edge_test_time_views},
          {"max_segment_length_m", s.max_segment_length_m},
          {"merged_maps_only", s.merged_maps_only},
          {"cut_sampling_passes", s.cut_sampling_passes},
          {"cut_clouds", s.cut},
          {"empty_wireframes", s.empty}};
}

InferenceTiming inference_from_json(const nlohmann::json& j) {
  InferenceTiming s;
  s.buildings = j.at("buildings").get<int>();
  const double n = std::max(1, s.buildings);
  s.threads = j.at("threads").get<int>();
  s.precision = j.value("precision", s.precision);
  s.total_seconds = j.at("seconds_per_building").get<double>() * n;
  s.junction_seconds = j.at("junction_seconds_per_building").get<double>() * n;
  s.edge_seconds = j.at("edge_seconds_per_building").get<double>() * n;
  s.post_seconds = j.at("post_seconds_per_building").get<double>() * n;
  s.max_seconds = j.at("max_seconds").get<double>();
  s.pairs = static_cast<int64_t>(std::llround(j.at("pairs_per_building").get<double>() * n));
  s.pair_support = j.value("pair_support", s.pair_support);
  // Metrics written before the selection was recorded (2026-12-03) were made with the release's, then the default.
  const JunctionSelectionOptions then = JunctionSelectionOptions::release();
  s.min_confidence = j.value("min_confidence", then.min_confidence);
  s.nms_radius_m = j.value("nms_radius_m", then.nms_radius_m);
  s.max_offset_m = j.contains("max_offset_m") && !j["max_offset_m"].is_null() ? j["max_offset_m"].get<double>() : then.max_offset_m;
  s.corner_radius_m = j.value("corner_radius_m", 0.0);  // every junction paired before the option existed
  s.footing_radius_m = j.value("footing_radius_m", 0.0);
  s.sampling_passes = j.value("sampling_passes", 1);  // one pass before the option existed
  s.test_time_views = j.value("test_time_views", 1);  // one view before the option existed
  s.density_seeds = j.value("density_seeds", std::string("release"));  // the release's before the option existed
  s.edge_test_time_views = j.value("edge_test_time_views", 1);
  s.max_segment_length_m = j.value("max_segment_length_m", 0.0);  // uncut before the option existed
  s.merged_maps_only = j.value("merged_maps_only", false);
  s.cut_sampling_passes = j.value("cut_sampling_passes", 1);  // the selection's passes before the option existed
  s.cut = j.value("cut_clouds", 0);
  s.empty = j.value("empty_wireframes", s.empty);
  return s;
}

void write_eval_outputs(const std::filesystem::path& dir, const EvalReport& report, const std::string& method,
                        const Building3dReport* building3d, const InferenceTiming* inference, const FaceReport* faces) {
  std::string md = eval_markdown(report, method);
  nlohmann::json j = eval_json(report, method);
  if (building3d) {
    md += building3d_markdown(*building3d, method);
    j["building3d"] = building3d_json(*building3d);
  }
  if (faces) {
    md += faces_markdown(*faces, method);
    j["faces"] = faces_json(*faces);
  }
  if (inference) {
    md += inference_markdown(*inference);
    j["inference"] = inference_json(*inference);
  }
  md += "\nlc2wf " + version_line() + "\n";
  write_text_atomically(dir / "metrics.md", md);
  write_text_atomically(dir / "metrics.json", json_text(j, 2) + "\n");
  write_text_atomically(dir / "per_building.csv", eval_per_building_csv(report));
}

}  // namespace lc2wf

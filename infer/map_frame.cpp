#include "infer/map_frame.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/util/number_format.h"
#include "dataset/photo/line_up.h"

namespace lc2wf {

namespace {

// "x", "-y", ... or a direction "X,Y,Z" (finite, not zero), unit length; empty for anything else.
std::optional<Vec3> given_up(const std::string& up) {
  const bool negative = !up.empty() && up[0] == '-';
  const std::string axis = negative ? up.substr(1) : up;
  Vec3 v;
  if (axis == "x") v = Vec3::UnitX();
  else if (axis == "y") v = Vec3::UnitY();
  else if (axis == "z") v = Vec3::UnitZ();
  else {
    const std::optional<Vec3> d = parse_xyz(up);
    if (!d || !(d->norm() > 0)) return std::nullopt;
    return d->normalized();
  }
  return negative ? Vec3(-v) : v;
}

nlohmann::json vec_json(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

nlohmann::json similarity_json(const Similarity& s) {
  nlohmann::json R = nlohmann::json::array();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R.push_back(s.R(r, c));
  return {{"scale", s.scale}, {"R", R}, {"t", vec_json(s.t)}};
}

LineCloud transformed(const LineCloud& map, const Similarity& s) {
  LineCloud out = map;
  for (Segment3& seg : out.segments) seg = s.apply(seg);
  for (Camera& c : out.cameras) c = s.apply(c);
  return out;
}

}  // namespace

void MapFrameOptions::Check() const {
  if (up != "auto" && !given_up(up))
    throw std::invalid_argument("MapFrameOptions.up must be auto, x, y, z, -x, -y, -z or a direction X,Y,Z (finite, not zero), got '" + up + "'");
  if (!(scale >= 0) || !std::isfinite(scale)) throw std::invalid_argument("MapFrameOptions.scale must be > 0");
  if (!(building_height_m >= 0) || !std::isfinite(building_height_m)) throw std::invalid_argument("MapFrameOptions.building_height_m must be > 0");
  if (!(known_distance_m >= 0) || !std::isfinite(known_distance_m)) throw std::invalid_argument("MapFrameOptions.known_distance_m must be > 0");
  if (known_distance_m > 0 && !((known_b - known_a).norm() > 0 && known_a.allFinite() && known_b.allFinite()))
    throw std::invalid_argument("MapFrameOptions.known_distance_m: the two points must differ");
  storeys.Check();
  search.Check();
}

FramedInference infer_in_metric_frame(const WireframePredictor& predictor, const LineCloud& map, const PostProcessOptions& post,
                                      const MapFrameOptions& o) {
  o.Check();
  if (map.segments.empty()) throw std::invalid_argument("the map has no line to find its frame from");
  MetricFrameOptions fo;
  if (o.up == "auto") fo.up = UpSource::kLines;
  else fo.up = UpSource::kGiven, fo.given_up = *given_up(o.up);
  fo.scale = o.scale;
  if (fo.scale == 0 && o.known_distance_m > 0) fo.scale = o.known_distance_m / (o.known_b - o.known_a).norm();
  fo.building_height_m = o.building_height_m;
  fo.storeys = o.storeys;
  fo.height_model = o.height_model;
  FramedInference f;
  f.frame = estimate_metric_frame({}, map.segments, fo);
  if (o.scale == 0 && o.known_distance_m > 0) f.frame.scale_source = "known distance";
  nlohmann::json& rep = f.report;
  rep = {{"format", "lc2wf-map-frame"}, {"version", 1}};
  if (const std::optional<LineUp>& lu = f.frame.line_up) {
    rep["up_evidence"] = {{"rule", lu->by_statistics ? "nearest the height model's clouds" : "most line length perpendicular"},
                          {"candidates", lu->tried.size()}, {"perpendicular_share", lu->perpendicular_share},
                          {"ground", lu->sign_by_statistics ? "the end the nearest clouds' ends say" : "the end that spreads widest"},
                          {"bottom_over_top_spread", lu->spread_ratio}};
    if (lu->by_statistics) {
      rep["up_evidence"]["statistics_distance"] = lu->distance, rep["up_evidence"]["runner_up_distance"] = lu->runner_up_distance;
      rep["up_evidence"]["uncertain"] = lu->uncertain;
    }
    nlohmann::json tried = nlohmann::json::array();
    for (const UpCandidate& c : lu->tried) {
      nlohmann::json t = {{"direction", {c.direction.x(), c.direction.y(), c.direction.z()}}, {"perpendicular_share", c.perpendicular_share}};
      if (c.distance >= 0) t["statistics_distance"] = c.distance;
      tried.push_back(t);
    }
    rep["up_evidence"]["tried"] = tried;
  }
  std::string scale_text;
  if (f.frame.needs_scale_search) {
    const MetricFrame unit = f.frame;
    ScaleSearchResult s = search_scale(
        predictor, [&](double h) { return transformed(map, unit.scaled_by(h).to_metric); }, post, o.search);
    f.frame = unit.scaled_by(s.height_m);
    f.cloud = std::move(s.cloud);
    f.inference = std::move(s.inference);
    nlohmann::json curve = nlohmann::json::array();
    for (const ScaleCandidate& c : s.curve)
      curve.push_back({{"height_m", c.height_m}, {"score", c.score}, {"junctions", c.junctions}, {"edges", c.edges},
                       {"edge_confidence", c.edge_confidence}, {"edge_evidence", c.edge_evidence},
                       {"confident_junctions", c.confident_junctions}, {"junction_mean", c.junction_mean}});
    const double ratio = s.runner_up_score > 0 ? s.best_score / s.runner_up_score : 0.0;
    rep["scale_search"] = {{"measure", to_string(o.search.measure)}, {"height_m", s.height_m}, {"score", s.best_score},
                           {"runner_up_height_m", s.runner_up_height_m}, {"runner_up_score", s.runner_up_score},
                           {"best_over_runner_up", ratio}, {"curve", curve}};
    scale_text = "building height " + format_number("%.1f", s.height_m) + " m by the scale search (score " +
                 format_number("%.3g", s.best_score) + ", " + format_number("%.2f", ratio) + "x the runner-up at " +
                 format_number("%.1f", s.runner_up_height_m) + " m)";
  } else {
    f.cloud = transformed(map, f.frame.to_metric);
    f.inference = predictor.predict(f.cloud, post);
    scale_text = format_number("%.4g", f.frame.to_metric.scale) + " m per map unit (" + f.frame.scale_source + ")";
    if (f.frame.scale_source == "line statistics") scale_text += ", " + line_height_text(f.frame, *o.height_model);
  }
  rep["up_source"] = o.up == "auto" ? f.frame.up_source : "given " + o.up;
  rep["up_input"] = vec_json(f.frame.up_input);
  rep["scale_source"] = f.frame.scale_source;
  if (storeys_consulted(f.frame)) {
    rep["storeys"] = storey_scale_json(f.frame.storeys, o.storeys);
    if (o.height_model) rep["line_statistics"] = line_height_json(f.frame, *o.height_model);
  }
  rep["to_metric"] = similarity_json(f.frame.to_metric);
  rep["height_m"] = f.frame.height_input * f.frame.to_metric.scale;
  rep["note"] = "the wireframe is written in this frame (metres, z up, ground 0); map point p -> scale * R * p + t";
  const Vec3& u = f.frame.up_input;
  f.summary = "up (" + format_number("%.3f", u.x()) + ", " + format_number("%.3f", u.y()) + ", " + format_number("%.3f", u.z()) +
              ") from " + rep["up_source"].get<std::string>() + "; " + scale_text;
  if (f.frame.line_up && f.frame.line_up->uncertain) {
    const Vec3& r = f.frame.line_up->runner_up;
    const std::string why = "the up is uncertain: another direction's lines look almost as much like an upright building (" +
                            format_number("%.3g", f.frame.line_up->runner_up_distance) + " against " +
                            format_number("%.3g", f.frame.line_up->distance) + "); look at the wireframe or give --up (that one: " +
                            format_number("%.3f", r.x()) + "," + format_number("%.3f", r.y()) + "," + format_number("%.3f", r.z()) +
                            " or its opposite)";
    f.warning = why;
    f.inference.notes.push_back(why);
  }
  return f;
}

}  // namespace lc2wf

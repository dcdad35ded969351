// Line maps made elsewhere (Line3D++, LIMAP, line OBJ) come in their own frame: any scale, any up. Before
// inference they are put in the networks' frame (metres, z up, ground at 0) by the machinery lc2wf-reconstruct
// uses: up from the lines' dominant directions (dataset/photo/line_up.h) refined by the near-vertical lines,
// or given; ground from the lowest structure; scale given, from a known distance, a building height or the
// facades' storeys (dataset/photo/storey_scale.h), the height a model reads from the lines' statistics
// (dataset/photo/line_height.h), else found by the scale search (model/scale_search.h). Our
// own clouds are metric and z up and are never touched.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "dataset/photo/metric_frame.h"
#include "model/scale_search.h"

namespace lc2wf {

struct MapFrameOptions {
  bool enabled = false;            // lc2wf-infer: on (foreign maps only); lc2wf-eval: off (frames as read)
  std::string up = "auto";         // auto, x, y, z, -x, -y, -z or a direction "X,Y,Z" in the map's frame
  double scale = 0;                // metres per map unit (0 = not given)
  double building_height_m = 0;    // the building's height above its ground (0 = not given)
  // Two points of the map D metres apart (known_distance_m > 0).
  Vec3 known_a = Vec3::Zero(), known_b = Vec3::Zero();
  double known_distance_m = 0;
  StoreyScaleOptions storeys;      // the facades' storeys, before the scale search (storey_height_m = 0: off)
  std::optional<HeightModel> height_model;  // the height read from the lines' statistics, after the storeys
  ScaleSearchOptions search;
  bool applies_to(const LineCloud& cloud) const { return enabled && cloud.external_line_map; }
  void Check() const;  // throws std::invalid_argument naming the field
};

struct FramedInference {
  LineCloud cloud;           // the map in the networks' frame
  InferenceResult inference;
  MetricFrame frame;         // map -> that frame
  nlohmann::json report;     // what was chosen and why, with the search's curve
  std::string summary;       // one line for stderr
  std::string warning;       // what the user should check (an uncertain up), also with --quiet; empty if nothing
};

// Throws std::invalid_argument when the map has no line or no height, or the options are bad.
FramedInference infer_in_metric_frame(const WireframePredictor& predictor, const LineCloud& map, const PostProcessOptions& post,
                                      const MapFrameOptions& options);

}  // namespace lc2wf

// Fixing the frame of a structure-from-motion reconstruction for the networks, which work in metres with
// z up and the ground at z = 0: a similarity (scale, rotation, translation) from the SfM frame.
//   up:    the GPS frame's up (when the camera centres were fitted to GPS), else the mean of the cameras' up
//          vectors (photos are taken upright), else the lines' own vertical (line_up.h, maps without
//          cameras); refined by the dominant direction of the 3D lines within 15 deg of it (vertical wall
//          corners); or the input z axis, or a given vector.
//   scale: from evidence only, in this order: given (metres per input unit), one known distance between
//          two camera centres, the GPS fit, a given building height, the facades' storeys (storey_scale.h),
//          the height a model reads from the lines' statistics (line_height.h); else it is left to the scale
//          search (model/scale_search.h), and the frame comes back with the cloud's height as its unit.
//   origin: x/y at the median segment midpoint, z = 0 at the cloud's low quantile (the ground lines).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dataset/geometry/geometry.h"
#include "dataset/photo/line_height.h"
#include "dataset/photo/line_up.h"
#include "dataset/photo/storey_scale.h"

namespace lc2wf {

// X' = scale * R * X + t.
struct Similarity {
  double scale = 1.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Vec3 t = Vec3::Zero();

  Vec3 apply(const Vec3& p) const { return scale * R * p + t; }
  Segment3 apply(const Segment3& s) const { return {apply(s.a), apply(s.b)}; }
  Camera apply(const Camera& c) const;  // same image, new frame
  Similarity inverse() const;
};

enum class UpSource { kAuto, kCameras, kLines, kInputZ, kGiven };

struct MetricFrameOptions {
  UpSource up = UpSource::kAuto;  // kAuto: GPS or cameras (the lines' vertical without cameras), refined by near-vertical lines
  Vec3 given_up = Vec3::UnitZ();  // kGiven only
  double vertical_line_max_deg = 15.0;
  int min_vertical_lines = 10;    // fewer near-vertical lines keep the cameras' up
  double scale = 0.0;             // metres per input unit; 0 = known distance, else the estimate
  int known_view_a = -1, known_view_b = -1;  // indices into the camera list
  double known_distance_m = 0.0;             // distance between those two camera centres
  // Input -> local east-north-up metres (camera centres fitted to their GPS positions, similarity_align.h):
  // scale and up, and x east / y north.
  std::optional<Similarity> gps_to_enu;
  double building_height_m = 0.0;            // > 0: the cloud's height above its ground is this many metres
  StoreyScaleOptions storeys;                // after the building height; storey_height_m = 0 skips it
  std::optional<HeightModel> height_model;   // after the storeys; none: the scale search
  // Storeys whose building is more than this factor taller or lower than the height model reads are a wrong
  // rhythm (clean walls' chance repeats gave 10x), and the model's height is used. 3, not 2: on street
  // captures the model was once 2.1x off where the storeys were right (experiments/README.md).
  double max_storey_disagreement = 3.0;
  double ground_quantile = 0.01;  // of the endpoint heights
  double top_quantile = 0.99;
  void Check() const;
};

struct MetricFrame {
  Similarity to_metric;
  Vec3 up_input = Vec3::UnitZ();  // the up direction found, input frame
  std::string up_source;          // "gps", "cameras", "line directions" (each "+lines" when refined by near-vertical lines), "input z", "given"
  int vertical_lines = 0;         // lines used for the refinement
  std::optional<LineUp> line_up;  // up source "line directions": what the lines said
  std::string scale_source;       // "given", "known distance", "gps", "building height", "storeys", "line statistics", "scale search"
  StoreyScale storeys;            // the storey estimate, when nothing before it gave the scale
  double line_height_m = 0;       // scale source "line statistics": the height the model read from the lines
  std::string line_height_why_not;  // when the model was given but could not be used
  std::string storeys_overruled;    // when the storeys were found but disagreed with the height model
  double height_input = 0.0;      // cloud height above its ground, input units
  // Scale source "scale search": no evidence fixed the scale, so to_metric makes the cloud's height 1; the
  // caller multiplies by the height the search finds (scaled_by).
  bool needs_scale_search = false;
  MetricFrame scaled_by(double factor) const;  // the same frame with metric coordinates x factor
};

// Whether the storeys (and the height model) were asked, i.e. nothing before them gave the scale: the reports
// then show what they said.
bool storeys_consulted(const MetricFrame& f);
// One line for the logs: the height read from the lines, its uncertainty, and the storeys it overruled.
std::string line_height_text(const MetricFrame& f, const HeightModel& m);

// What report.json says of the height model's reading (`frame.line_statistics`): the height read, whether it
// was used, why not or which storeys it overruled, and the model's cross-validated errors (its uncertainty).
nlohmann::json line_height_json(const MetricFrame& f, const HeightModel& m);

// `cameras`: the registered cameras (input frame), `segments`: the 3D lines (input frame), `storey_lines`:
// the lines the storey rhythm is read from (default `segments`; a photo cloud's frame lines are only its
// best-supported hundred, too few window lines). Throws std::invalid_argument for bad options, an empty cloud,
// a degenerate up or a zero height/distance.
MetricFrame estimate_metric_frame(const std::vector<Camera>& cameras, const std::vector<Segment3>& segments,
                                  const MetricFrameOptions& options = {}, const std::vector<Segment3>* storey_lines = nullptr);

}  // namespace lc2wf

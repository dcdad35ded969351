// Which part of a building the cameras covered: the arc of camera directions around it and which sides of
// its footprint (the minimum-area rectangle around the given points, dataset/geometry/footprint.h) enough
// cameras see at a usable angle. A capture from the street sees one or two sides; the report says which, so
// a wireframe of the seen sides is not mistaken for the whole building.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct CoverageOptions {
  int min_cameras = 2;              // a side is seen when at least this many cameras see it (two views make a line)
  double max_view_angle_deg = 75.0;  // between the side's outward normal and the horizontal direction to the camera
  void Check() const;  // throws std::invalid_argument naming the bad field
};

struct SideCoverage {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  // footprint corners, counter-clockwise
  double length_m = 0.0;
  double outward_azimuth_deg = 0.0;  // direction the side faces, degrees counter-clockwise from +x, in (-180, 180]
  int cameras = 0;                   // cameras that see it
  bool seen = false;                 // cameras >= min_cameras
};

struct CameraCoverage {
  Vec2 centre = Vec2::Zero();   // of the footprint
  int cameras = 0;              // cameras away from the centre (the others have no direction)
  // The smallest arc holding every camera's direction from the centre, counter-clockwise from `from` to `to`.
  double azimuth_from_deg = 0.0, azimuth_to_deg = 0.0, azimuth_span_deg = 0.0;
  std::vector<SideCoverage> sides;  // empty when the points span no footprint
  double seen_outline_share = 0.0;  // length of the seen sides over the perimeter
  std::string outline;              // what the footprint is of: "wireframe" or "cloud"
  std::string summary() const;      // one line for the log
};

// Coverage of the footprint of `outline_points` (x/y; their mid-height is where a side is projected) by
// `cameras`. A camera sees a side when it faces the side within max_view_angle_deg and a point of the side
// lies in front of it and inside its image (the footprint is convex: a side faced is not hidden by another).
CameraCoverage camera_coverage(const std::vector<Camera>& cameras, const std::vector<Vec3>& outline_points,
                               const CoverageOptions& options = {});

// The same for a result: the footprint of the wireframe's junctions, or of the cloud's segment endpoints when
// the wireframe spans none (fewer than three junctions, or all on one line).
CameraCoverage camera_coverage(const std::vector<Camera>& cameras, const Wireframe& wireframe,
                               const std::vector<Segment3>& segments, const CoverageOptions& options = {});

// For report.json: the arc, the share and each side (corners, length, facing, cameras, seen).
nlohmann::json coverage_json(const CameraCoverage& coverage);

}  // namespace lc2wf

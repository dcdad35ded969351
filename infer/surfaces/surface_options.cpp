#include "infer/surfaces/surface_options.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lc2wf {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("surfaces." + message);
}

}  // namespace

void SurfaceOptions::Check() const {
  require(std::isfinite(merge_distance_m) && merge_distance_m >= 0, "merge_distance_m must be >= 0");
  require(std::isfinite(plane_distance_m) && plane_distance_m > 0, "plane_distance_m must be > 0");
  require(std::isfinite(plane_angle_deg) && plane_angle_deg > 0 && plane_angle_deg < 45, "plane_angle_deg must be in (0, 45)");
  require(std::isfinite(min_edge_angle_deg) && min_edge_angle_deg > 0 && min_edge_angle_deg < 90,
          "min_edge_angle_deg must be in (0, 90)");
  require(std::isfinite(wall_tilt_deg) && wall_tilt_deg >= 0 && wall_tilt_deg < 90, "wall_tilt_deg must be in [0, 90)");
  require(std::isfinite(planarity_tolerance_m) && planarity_tolerance_m > 0, "planarity_tolerance_m must be > 0");
  require(max_edges > 0, "max_edges must be > 0");
  require(max_work_steps > 0, "max_work_steps must be > 0");
  require(std::isfinite(min_edge_score) && min_edge_score >= 0 && min_edge_score <= 1, "min_edge_score must be in [0, 1]");
}

}  // namespace lc2wf

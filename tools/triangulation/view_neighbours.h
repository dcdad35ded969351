// Visual neighbours chosen from the known cameras alone (no SfM points): views whose triangulation angle
// at the scene centre is inside a band are ranked by closeness to a preferred angle.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct NeighbourOptions {
  int count = 10;                 // neighbours per view
  double min_angle_deg = 4.0;     // triangulation angle band at the scene centre
  double max_angle_deg = 60.0;
  double preferred_angle_deg = 20.0;
  void Check() const;
};

// Least-squares intersection of the optical axes (a scene-centre estimate when no box is known).
Vec3 optical_axes_centre(const std::vector<Camera>& cameras);

// neighbours[a] lists up to options.count views for view a, best first (ties by view index).
std::vector<std::vector<int>> select_neighbours(const std::vector<Camera>& cameras, const Vec3& scene_centre,
                                                const NeighbourOptions& options);

}  // namespace lc2wf

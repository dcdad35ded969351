// Depth test against a polygon mesh: is the straight path from a camera centre to a point blocked?
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

class MeshOccluder {
 public:
  explicit MeshOccluder(const PolyMesh& mesh);
  // True when some face crosses the open segment (eye, point) closer to the eye than
  // |point - eye| - tolerance (so faces that contain the point do not hide it).
  bool occluded(const Vec3& eye, const Vec3& point, double tolerance) const;

 private:
  struct Face {
    Vec3 normal;
    double offset = 0;                    // plane: normal . x = offset
    int drop_axis = 0;                    // axis dropped for the 2D point-in-polygon test
    std::vector<Eigen::Vector2d> polygon;
    Vec3 box_min, box_max;
  };
  std::vector<Face> faces_;
};

}  // namespace lc2wf

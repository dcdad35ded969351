// How many cameras saw where an edge is: its points lie in front of the camera, inside the image, and not
// behind the building. "The building" is the inside of the wireframe's footprint (the x/y cells its edges
// enclose, so courtyards and notches stay outside) raised from its lowest to its highest junction: a point
// whose view to a camera crosses that block is hidden from it. An edge the networks propose on a side no
// camera faced counts no camera; on a full orbit every outer edge has many.
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

class FootprintOccluder {
 public:
  // No occluder (nothing is hidden) for a wireframe without edges.
  explicit FootprintOccluder(const Wireframe& wireframe);
  // True when the straight path from `point` towards `eye` crosses the block farther than `tolerance_m` from
  // `point`.
  bool hides(const Vec3& eye, const Vec3& point, double tolerance_m) const;

 private:
  bool inside(const Vec2& xy) const;
  Vec2 origin_ = Vec2::Zero();
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<uint8_t> inside_;  // nx_ * ny_, row-major in y
  double z_lo_ = 0.0, z_hi_ = 0.0;
};

// Cameras for which every one of a few points along u-v (away from its ends, where other faces meet) is in
// front, inside the image and not hidden by `occluder`.
int cameras_seeing(const Vec3& u, const Vec3& v, const std::vector<Camera>& cameras, const FootprintOccluder& occluder,
                   double tolerance_m);

// The part of a wireframe that a capture saw: the edges at least `min_cameras` of `cameras` had in view, with
// the wireframe itself as the occluder, and the junctions they use. Scoring a street capture against this
// part asks for what was seen, not for the sides nobody photographed (lc2wf-eval --gt-seen-by). The block
// over the footprint also hides what a roof rises to inside it (a ridge seen from eye level counts unseen).
Wireframe seen_part(const Wireframe& wireframe, const std::vector<Camera>& cameras, int min_cameras, double tolerance_m);

}  // namespace lc2wf
